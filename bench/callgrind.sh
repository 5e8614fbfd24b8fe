#!/bin/sh
# callgrind.sh: does a scene pay for a feature it does not use?  (`make callgrind` runs this.)
#
# For each feature, builds bench/strip_cost.c twice, normally and with the macro that strips
# the feature, both without OpenMP (one thread, so the count is deterministic), runs each
# under valgrind's callgrind counting only the instructions executed inside fogrt_render
# (--toggle-collect) on a scene that does not use the feature, and prints both totals and
# their ratio:
#   FOGRT_NO_MEDIUM          a fog-free scene                      (strip_cost medium)
#   FOGRT_NO_GLASS           a scene without glass or refraction   (strip_cost glass)
#   FOGRT_NO_EXACT_FRESNEL   a render with Schlick's Fresnel       (strip_cost exact)
#   FOGRT_NO_MEDIA           grey HG fog, no emission (appendix G)  (strip_cost media)
#   FOGRT_NO_MICROFACET      a scene without rough metals (appendix I) (strip_cost microfacet)
# Exits non-zero if any normal build executes more than LIMIT_PERCENT (1) percent more
# instructions than its stripped build. Last, the path trace hooks: a normal build must
# execute exactly as many instructions as one whose header has the hook lines deleted.
#
# Environment: CC (cc), CFLAGS (-O2 -g), BUILD (build), LIMIT_PERCENT (1). Run from the repo root.
set -eu

CC=${CC:-cc}
CFLAGS=${CFLAGS:--O2 -g}
BUILD=${BUILD:-build}
LIMIT_PERCENT=${LIMIT_PERCENT:-1}
WARN="-std=c99 -Wall -Wextra -pedantic -Wshadow"
OUT="$BUILD/bench"
case $OUT in /*) ;; *) OUT="./$OUT" ;; esac

sh tools/need-package.sh valgrind /usr/bin/valgrind
mkdir -p "$OUT"

# run NAME MODE: callgrind over one build; its total (Ir inside fogrt_render) goes to
# $OUT/NAME.total, its own output line to $OUT/NAME.txt.
run() {
    name=$1 mode=$2
    rm -f "$OUT/callgrind.$name.out"
    valgrind --tool=callgrind --toggle-collect=fogrt_render \
        --callgrind-out-file="$OUT/callgrind.$name.out" "$OUT/$name" "$mode" \
        >"$OUT/$name.txt" 2>"$OUT/$name.valgrind.log" || {
        echo "callgrind.sh: $name $mode failed under valgrind, see $OUT/$name.valgrind.log:" >&2
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

# pair MACRO MODE WHAT: the normal and the stripped build on one scene; prints the ratio and
# returns non-zero above the limit.
status=0
pair() {
    macro=$1 mode=$2 what=$3
    # shellcheck disable=SC2086  # CFLAGS and WARN are word lists
    $CC $WARN $CFLAGS -I. -DSTRIP_COST_BUILD='"normal build"' -o "$OUT/strip_cost_$mode" bench/strip_cost.c -lm
    # shellcheck disable=SC2086
    $CC $WARN $CFLAGS -I. -D"$macro" -DSTRIP_COST_BUILD="\"$macro build\"" -o "$OUT/strip_cost_${mode}_stripped" bench/strip_cost.c -lm
    run "strip_cost_$mode" "$mode"
    run "strip_cost_${mode}_stripped" "$mode"
    echo "$what, instructions inside fogrt_render:"
    echo "  $(cat "$OUT/strip_cost_$mode.txt")"
    echo "  $(cat "$OUT/strip_cost_${mode}_stripped.txt")"
    if [ "$(sed 's/.*checksum //' "$OUT/strip_cost_$mode.txt")" != \
         "$(sed 's/.*checksum //' "$OUT/strip_cost_${mode}_stripped.txt")" ]; then
        echo "  note: the two builds render different images (checksums differ)"
    fi
    awk -v n="$(cat "$OUT/strip_cost_$mode.total")" -v s="$(cat "$OUT/strip_cost_${mode}_stripped.total")" \
        -v lim="$LIMIT_PERCENT" -v m="$macro" 'BEGIN {
        r = n / s
        printf "  normal build %15.0f Ir, %s build %15.0f Ir: ratio %.4f (%+.2f%%; limit +%s%%)\n", n, m, s, r, 100 * (r - 1), lim
        if (r > 1 + lim / 100) { print "  FAIL: the scene pays for code it does not use"; exit 1 }
        print "  OK"
    }' || status=1
}

# The trace hooks (FOGRT_TRACE) must cost nothing when off: the normal build against one
# whose header has every hook line deleted must execute exactly as many instructions.
hooks() {
    mkdir -p "$OUT/nohooks"
    sed '/FOGRT__HOOK(fogrt__trace/d' fogrt.h >"$OUT/nohooks/fogrt.h"
    # shellcheck disable=SC2086
    $CC $WARN $CFLAGS -I. -DSTRIP_COST_BUILD='"normal build"' -o "$OUT/strip_cost_trace" bench/strip_cost.c -lm
    # shellcheck disable=SC2086
    $CC $WARN $CFLAGS -I"$OUT/nohooks" -DSTRIP_COST_BUILD='"header without trace hooks"' -o "$OUT/strip_cost_trace_stripped" bench/strip_cost.c -lm
    # shellcheck disable=SC2086
    $CC $WARN $CFLAGS -I. -DFOGRT_TRACE -DSTRIP_COST_BUILD='"FOGRT_TRACE build, no callback"' -o "$OUT/strip_cost_trace_on" bench/strip_cost.c -lm
    run strip_cost_trace exact
    run strip_cost_trace_stripped exact
    run strip_cost_trace_on exact
    echo "trace hooks (the default scene), instructions inside fogrt_render:"
    awk -v n="$(cat "$OUT/strip_cost_trace.total")" -v s="$(cat "$OUT/strip_cost_trace_stripped.total")" \
        -v t="$(cat "$OUT/strip_cost_trace_on.total")" 'BEGIN {
        printf "  normal build %15.0f Ir, header without the hook lines %15.0f Ir: %+.4f%% (must be 0)\n", n, s, 100 * (n / s - 1)
        printf "  (for comparison: FOGRT_TRACE compiled in, no callback set: %15.0f Ir, %+.2f%%)\n", t, 100 * (t / s - 1)
        if (n != s) { print "  FAIL: the hooks cost something when FOGRT_TRACE is off"; exit 1 }
        print "  OK"
    }' || status=1
}

pair FOGRT_NO_MEDIUM medium "fog-free default scene (sigma_t = 0)"
pair FOGRT_NO_GLASS glass "a fog-filled box without glass (a mirror and a diffuse sphere)"
pair FOGRT_NO_EXACT_FRESNEL exact "the default scene rendered with Schlick's Fresnel"
pair FOGRT_NO_MEDIA media "the default scene: grey HG fog without emission (appendix G unused)"
pair FOGRT_NO_MICROFACET microfacet "a fog-filled box with a diffuse and a mirror sphere (appendix I unused)"
hooks
exit $status
