#!/bin/sh
# check_limits.sh: the headers' functions stay small (`make check-limits`).
#   fogrt.h       no function over 60 lines or cyclomatic complexity 20
#   fogrt_load.h  no function over 100 lines
# Measured by lizard (PyPI): the one on PATH, else one installed into build/lint-venv.
# Prints lizard's warnings (nothing when all is well) and the largest figures of each header.
set -e
cd "$(dirname "$0")/.."
LIZARD=$(command -v lizard 2>/dev/null || true)
if [ -z "$LIZARD" ]; then
    LIZARD=build/lint-venv/bin/lizard
    if [ ! -x "$LIZARD" ]; then
        command -v python3 >/dev/null 2>&1 || { echo "check-limits: needs python3 (for lizard)" >&2; exit 2; }
        echo "check-limits: installing lizard into build/lint-venv" >&2
        { python3 -m venv build/lint-venv && build/lint-venv/bin/pip install -q lizard; } >/dev/null 2>&1 ||
            { echo "check-limits: could not install lizard (python3-venv and PyPI needed)" >&2; exit 2; }
    fi
fi
# largest NAME: the longest function and the most complex one, from lizard's table
largest() {
    "$LIZARD" "$1" | awk -v f="$1" '$NF ~ /@/ && $1 ~ /^[0-9]+$/ {
            n = $NF; sub(/@.*/, "", n)
            if ($5 > len) { len = $5; ln = n } if ($2 > ccn) { ccn = $2; cn = n } }
        END { printf "%s: longest %s (%d lines), most complex %s (CCN %d)\n", f, ln, len, cn, ccn }'
}
status=0
"$LIZARD" -C 20 -L 60 -w fogrt.h || status=1
"$LIZARD" -C 1000 -L 100 -w fogrt_load.h || status=1
largest fogrt.h
largest fogrt_load.h
if [ "$status" = 0 ]; then echo "check-limits: fogrt.h within 60 lines and CCN 20, fogrt_load.h within 100 lines"
else echo "check-limits: functions over the limits (above)"; fi
exit "$status"
