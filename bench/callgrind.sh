#!/bin/sh
# callgrind.sh: does a fog-free scene pay for the fog code?  (`make callgrind` runs this.)
#
# Builds bench/nomedium_cost.c twice, normally and with -DFOGRT_NO_MEDIUM, both without OpenMP
# (one thread, so the count is deterministic), runs each under valgrind's callgrind counting
# only the instructions executed inside fogrt_render (--toggle-collect), and prints both totals
# and their ratio. Exits non-zero if the normal build executes more than LIMIT_PERCENT (3)
# percent more instructions than the FOGRT_NO_MEDIUM build for the same fog-free render.
#
# Environment: CC (cc), CFLAGS (-O2 -g), BUILD (build), LIMIT_PERCENT (3). Run from the repo root.
set -eu

CC=${CC:-cc}
CFLAGS=${CFLAGS:--O2 -g}
BUILD=${BUILD:-build}
LIMIT_PERCENT=${LIMIT_PERCENT:-3}
WARN="-std=c99 -Wall -Wextra -pedantic -Wshadow"
OUT="$BUILD/bench"
case $OUT in /*) ;; *) OUT="./$OUT" ;; esac

sh tools/need-package.sh valgrind /usr/bin/valgrind
mkdir -p "$OUT"

# The two builds: identical flags except for the strip macro.
# shellcheck disable=SC2086  # CFLAGS and WARN are word lists
$CC $WARN $CFLAGS -I. -o "$OUT/nomedium_cost" bench/nomedium_cost.c -lm
# shellcheck disable=SC2086
$CC $WARN $CFLAGS -I. -DFOGRT_NO_MEDIUM -o "$OUT/nomedium_cost_stripped" bench/nomedium_cost.c -lm

# run NAME: callgrind over one build; prints the program's own line, returns the total (Ir)
# in the file $OUT/NAME.total.
run() {
    name=$1
    rm -f "$OUT/callgrind.$name.out"
    valgrind --tool=callgrind --toggle-collect=fogrt_render \
        --callgrind-out-file="$OUT/callgrind.$name.out" "$OUT/$name" \
        >"$OUT/$name.txt" 2>"$OUT/$name.valgrind.log" || {
        echo "callgrind.sh: $name failed under valgrind, see $OUT/$name.valgrind.log:" >&2
        cat "$OUT/$name.txt" >&2
        grep -v '^==' "$OUT/$name.valgrind.log" >&2
        exit 1
    }
    # The out file ends with "totals: N" (older valgrind: "summary: N"): the Ir inside fogrt_render.
    total=$(sed -n 's/^totals: *\([0-9]*\).*/\1/p; s/^summary: *\([0-9]*\).*/\1/p' \
        "$OUT/callgrind.$name.out" | tail -n 1)
    if [ -z "$total" ] || [ "$total" = 0 ]; then
        echo "callgrind.sh: no instructions collected in fogrt_render for $name" >&2
        exit 1
    fi
    echo "$total" >"$OUT/$name.total"
}

run nomedium_cost
run nomedium_cost_stripped
normal=$(cat "$OUT/nomedium_cost.total")
stripped=$(cat "$OUT/nomedium_cost_stripped.total")

echo "fog-free render of the default scene (sigma_t = 0), instructions inside fogrt_render:"
echo "  $(cat "$OUT/nomedium_cost.txt")"
echo "  $(cat "$OUT/nomedium_cost_stripped.txt")"
# The two builds should render the same picture (the same random numbers, the same paths).
if [ "$(sed 's/.*checksum //' "$OUT/nomedium_cost.txt")" != \
     "$(sed 's/.*checksum //' "$OUT/nomedium_cost_stripped.txt")" ]; then
    echo "  note: the two builds render different images (checksums differ)"
fi
awk -v n="$normal" -v s="$stripped" -v lim="$LIMIT_PERCENT" 'BEGIN {
    r = n / s
    printf "  normal build          %15.0f Ir\n", n
    printf "  FOGRT_NO_MEDIUM build %15.0f Ir\n", s
    printf "  ratio normal / stripped = %.4f (%+.2f%%; limit +%s%%)\n", r, 100 * (r - 1), lim
    if (r > 1 + lim / 100) { print "  FAIL: the fog-free scene pays for the fog code"; exit 1 }
    print "  OK"
}'
