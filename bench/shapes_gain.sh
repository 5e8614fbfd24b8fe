#!/bin/sh
# bench/shapes_gain.sh FOGRT SHARED BASE [SECONDS] [RUNS]: a lamp-lit scene with a medium
# inside a shape, this tree against the header of commit BASE at equal time
# (`make bench-shapes SHAPES_BASE=...` runs this).
#
# The scene: the CS184 bunny under its spot lamp in fog (--density 0.3 --g 0.5), the bunny a
# fog volume of its own (--medium Mesh --interface --density 3 --albedo 0.8), 160 x 120
# pixels. The error is measured against a reference image, not by either renderer's own
# estimate: this tree's fogrt renders it once at 4096 spp (its mean agrees with BASE's where
# both are unbiased, which test_compose and docs/validation.md check). Then RUNS times
# (default 3), alternating, each renderer gets SECONDS (default 10) of render time
# (--time) and reports ref_rel_mse in its --log; the figure of merit is relMSE x seconds,
# and the gain is BASE's over this tree's (above 1: this tree is better). The mean gain
# over the runs is the last line. Needs git history (BASE is built from it,
# bench/base_build.sh) and the CS184 scenes in SHARED.
set -e
FOGRT=$1 SHARED=$2 BASE=$3 SECONDS_=${4:-10} RUNS=${5:-3}
if [ -z "$FOGRT" ] || [ -z "$SHARED" ] || [ -z "$BASE" ]; then
    echo "usage: sh bench/shapes_gain.sh FOGRT SHARED BASE [SECONDS] [RUNS]" >&2
    exit 2
fi
SCENE=$SHARED/scenes/cs184/CBbunny_upSpot.dae
if [ ! -f "$SCENE" ]; then
    echo "shapes-gain: $SCENE not found (the CS184 scenes live in SHARED=$SHARED): nothing measured" >&2
    exit 2
fi
BASE_FOGRT=$(sh bench/base_build.sh "$BASE" build/fogrt "$SHARED")
OUT=build/shapes-gain
mkdir -p "$OUT"
FLAGS="-r 160 120 -t 2 --density 0.3 --g 0.5 --medium Mesh --interface --density 3 --albedo 0.8"
if [ ! -f "$OUT/reference.pfm" ] || [ "$FOGRT" -nt "$OUT/reference.pfm" ]; then
    echo "shapes-gain: the reference, 4096 spp (a few minutes)"
    "$FOGRT" $FLAGS -s 4096 --quiet -f "$OUT/reference.pfm" "$SCENE"
fi
# The last row's ref_rel_mse and seconds of a --log file (columns by the header's names).
last_mse() {
    awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
             { s = $col["seconds"]; m = $col["ref_rel_mse"] } END { printf "%s %s\n", m, s }' "$1"
}
gains=""
printf '%-4s | %-26s | %-26s | %s\n' run "$BASE: relMSE, s" "this tree: relMSE, s" "gain (relMSE x s)"
i=1
while [ "$i" -le "$RUNS" ]; do
    rm -f "$OUT/base.csv" "$OUT/this.csv"
    "$BASE_FOGRT" $FLAGS --time "$SECONDS_" --seed "$i" --quiet --reference "$OUT/reference.pfm" \
        --log "$OUT/base.csv" -f "$OUT/base.pfm" "$SCENE"
    "$FOGRT" $FLAGS --time "$SECONDS_" --seed "$i" --quiet --reference "$OUT/reference.pfm" \
        --log "$OUT/this.csv" -f "$OUT/this.pfm" "$SCENE"
    set -- $(last_mse "$OUT/base.csv") $(last_mse "$OUT/this.csv")
    gain=$(awk -v m0="$1" -v s0="$2" -v m1="$3" -v s1="$4" 'BEGIN { printf "%.2f", (m0 * s0) / (m1 * s1) }')
    printf '%-4s | %-26s | %-26s | %sx\n' "$i" "$1, $2" "$3, $4" "$gain"
    gains="$gains $gain"
    i=$((i + 1))
done
echo "$gains" | awk '{ for (i = 1; i <= NF; ++i) { s += $i; n++ } }
    END { printf "shapes-gain: relMSE x seconds, %s over this tree, mean of %d runs: %.2fx\n", "'"$BASE"'", n, s / n }'
