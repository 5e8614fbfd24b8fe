#!/bin/sh
# bench/base_build.sh BASE TARGET [SHARED] [MAKE ARGS...]: builds TARGET (a make target such as
# build/fogrt) from the tree of commit BASE, in build/bench-base/<commit>, once; prints the
# path of what it built. Comparisons "against another commit in the same run" use it
# (bench/same_run.sh, make bench-mitsuba MITSUBA_BASE=...). Needs git history.
set -e
BASE=$1 TARGET=$2 SHARED=${3:-../shared}
shift 2; [ $# -gt 0 ] && shift
if [ -z "$BASE" ] || [ -z "$TARGET" ]; then
    echo "usage: sh bench/base_build.sh BASE TARGET [SHARED] [MAKE ARGS...]" >&2
    exit 2
fi
if ! SHA=$(git rev-parse --verify -q "$BASE^{commit}"); then
    echo "base_build: $BASE is not a commit of this repository's history: give another, or run from a git clone" >&2
    exit 2
fi
OUT=build/bench-base/$SHA
if [ ! -x "$OUT/$TARGET" ]; then
    echo "base_build: building $BASE's $TARGET ($SHA) in $OUT" >&2
    if [ ! -f "$OUT/Makefile" ]; then
        rm -rf "$OUT" && mkdir -p "$OUT"
        git archive "$SHA" | tar -x -C "$OUT"
    fi
    # BASE's tree sits deeper than this one: it reads the same scenes by an absolute path
    shared_abs=$(cd "$SHARED" 2>/dev/null && pwd || echo "$SHARED")
    make -s -C "$OUT" "$TARGET" SHARED="$shared_abs" "$@" >/dev/null
fi
echo "$OUT/$TARGET"
