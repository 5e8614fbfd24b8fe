#!/bin/sh
# bench/same_run.sh BASE [RUNS] [ARGS] [SHARED]: make bench's figures, this tree against the header of
# any commit BASE, in the same run (`make bench-base BENCH_BASE=...` runs this).
#
# A speed is a property of a machine and of its load at that minute, so a figure measured
# once and compared with a table is not a comparison. This script builds BASE's own bench
# program from the repository's history (git archive, BASE's Makefile, into
# build/bench-base/<commit>; BENCH_EMBREE=0: Embree is not what is compared), then runs the
# two programs alternately RUNS times (default 3): BASE's, this tree's, BASE's, ... Every
# figure of make bench (build seconds, Mrays/s of each ray kind on 1 and 2 threads, render
# samples/s) is kept per run, and the table gives, per figure, the median over the runs of
# this tree's figure over BASE's taken in the same round (speed: above 1 is faster; build
# time is inverted so that above 1 is faster too), and the ratio of each side's best round:
# a busy machine only ever slows a round down, so the best rounds are the least disturbed.
# ARGS go to both programs (e.g. --quick).
# Needs git history (a clone, not an exported tarball).
set -e
BASE=$1 RUNS=${2:-3} ARGS=${3:-} SHARED=${4:-../shared}
if [ -z "$BASE" ]; then
    echo "usage: sh bench/same_run.sh BASE [RUNS] [ARGS]   (BASE: a commit, tag or branch)" >&2
    exit 2
fi
BASE_BENCH=$(sh bench/base_build.sh "$BASE" build/bench/fogrt_bench_alone "$SHARED" BENCH_EMBREE=0)
OUT=${BASE_BENCH%/build/bench/fogrt_bench_alone}
make -s build/bench/fogrt_bench_alone BENCH_EMBREE=0 SHARED="$SHARED" >/dev/null
# One line per figure, "name value", from a bench report (higher is faster).
figures() {
    awk '
        /^== / { sec = $0; sub(/^== /, "", sec); sub(/:.*/, "", sec); sub(/ \(.*/, "", sec); gsub(/ /, "_", sec) }
        $1 == "build" && $2 == "fogrt" { printf "%s:build_per_s %.6g\n", sec, 1.0 / $3 }
        $1 ~ /^(primary|random|bounce|shadow)$/ && $4 == "|" { printf "%s:%s_1T %s\n%s:%s_2T %s\n", sec, $1, $5, sec, $1, $6 }
        $1 ~ /^[12]$/ && $2 == "|" { printf "%s:render_%sT_samples_per_s %s\n", sec, $1, $3 }
    '
}
i=1
: > "$OUT/ratios.txt"
while [ "$i" -le "$RUNS" ]; do
    echo "bench-base: round $i of $RUNS ($BASE, then this tree)"
    "$BASE_BENCH" $ARGS > "$OUT/base.txt" 2>&1
    ./build/bench/fogrt_bench_alone $ARGS > "$OUT/this.txt" 2>&1
    figures < "$OUT/base.txt" > "$OUT/base.fig"
    figures < "$OUT/this.txt" > "$OUT/this.fig"
    awk 'NR == FNR { b[$1] = $2; next } ($1 in b) && b[$1] > 0 { printf "%s %.6g %.6g %.6g\n", $1, b[$1], $2, $2 / b[$1] }' \
        "$OUT/base.fig" "$OUT/this.fig" >> "$OUT/ratios.txt"
    i=$((i + 1))
done
printf '%-44s | %12s | %12s | %11s | %s\n' "figure (median over $RUNS rounds)" "$BASE" "this tree" "this / base" "best / best"
sort -k1,1 -k4,4g "$OUT/ratios.txt" | awk -v runs="$RUNS" '
    function flush() {
        if (name == "") return
        m = int((n + 1) / 2)
        printf "%-44s | %12.4g | %12.4g | %11.3f | %.3f\n", name, base[m], cur[m], r[m], bc / bb
    }
    $1 != name { flush(); name = $1; n = 0; bb = 0; bc = 0 }
    { n++; r[n] = $4; base[n] = $2; cur[n] = $3; if ($2 > bb) bb = $2; if ($3 > bc) bc = $3 }
    END { flush() }'
echo "(build_per_s: builds per second, so that above 1 is faster everywhere; load average at the end: $(cut -d' ' -f1 /proc/loadavg 2>/dev/null || echo n/a))"
