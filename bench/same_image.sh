#!/bin/sh
# bench/same_image.sh BASE [SHARED]: this tree's images against those of the header of commit
# BASE (`make same-image IMAGE_BASE=...`), at fixed seeds.
#
# BASE's fogrt is built from the repository's history (bench/base_build.sh, into
# build/bench-base/<commit>). Two scenes: the embedded default scene, and the CS184 bunny
# under a spot light in denser, forward-scattering fog (CBbunny_upSpot.dae --density 0.5
# --g 0.6; skipped with a line when SHARED has no scenes).
#   1. with per-pixel rates off (-s 16 -r 160 120 -t 2 --pixel-rates off): the PFMs must be
#      identical byte for byte (cmp);
#   2. with the default settings (-s 64 -r 160 120 --seed 1 -t 2): each channel's image mean
#      must agree within 0.1%. Per-pixel rates spend a pilot's samples differently when
#      their rules change, so these images may differ sample by sample and agree only on
#      average.
# Exit status 1 when a check fails. Needs git history and python3 (to read the PFMs' means).
set -e
BASE=$1 SHARED=${2:-../shared}
if [ -z "$BASE" ]; then
    echo "usage: sh bench/same_image.sh BASE [SHARED]   (BASE: a commit, tag or branch)" >&2
    exit 2
fi
command -v python3 >/dev/null 2>&1 || { echo "same-image: needs python3 (to read the images' means)" >&2; exit 2; }
OLD=$(sh bench/base_build.sh "$BASE" build/fogrt "$SHARED")
NEW=build/fogrt
OUT=${OLD%/build/fogrt}/same-image
mkdir -p "$OUT"
SCENE=$SHARED/scenes/cs184/CBbunny_upSpot.dae
# means FILE: each channel's mean of a PFM (either byte order)
means() {
    python3 - "$1" <<'PY'
import struct, sys
with open(sys.argv[1], "rb") as f:
    head = []
    while len(head) < 4:
        head += f.readline().split()
    w, h, scale = int(head[1]), int(head[2]), float(head[3])
    data = f.read(w * h * 12)
v = struct.unpack(("<" if scale < 0 else ">") + "%df" % (w * h * 3), data)
print(" ".join("%.9g" % (sum(v[c::3]) / (w * h)) for c in range(3)))
PY
}
status=0
check() {   # NAME ARGS...: render with both, compare
    name=$1; shift
    "$OLD" "$@" -f "$OUT/${name}_base.pfm" >/dev/null 2>&1 || { echo "same-image: $BASE's fogrt failed on $name"; status=1; return; }
    "$NEW" "$@" -f "$OUT/${name}_this.pfm" >/dev/null 2>&1 || { echo "same-image: this fogrt failed on $name"; status=1; return; }
    case $name in
    *_rates_off)
        if cmp -s "$OUT/${name}_base.pfm" "$OUT/${name}_this.pfm"; then echo "ok    $name: identical (cmp)"
        else echo "FAIL  $name: the images differ"; status=1; fi ;;
    *)
        b=$(means "$OUT/${name}_base.pfm"); t=$(means "$OUT/${name}_this.pfm")
        if echo "$b $t" | awk '{ for (c = 1; c <= 3; ++c) { d = $(c + 3) / $c - 1; if (d < 0) d = -d; if (!(d <= 0.001)) bad = 1
                                 printf "%s%.4f%%", (c > 1 ? ", " : ""), 100 * ($(c + 3) / $c - 1) } exit bad }' > "$OUT/diff.txt"
        then echo "ok    $name: channel means within 0.1% ($(cat "$OUT/diff.txt"))"
        else echo "FAIL  $name: channel means differ by $(cat "$OUT/diff.txt")"; status=1; fi ;;
    esac
}
check default_rates_off -s 16 -r 160 120 -t 2 --pixel-rates off
check default_means -s 64 -r 160 120 -t 2 --seed 1
if [ -f "$SCENE" ]; then
    check bunny_rates_off -s 16 -r 160 120 -t 2 --pixel-rates off --density 0.5 -g 0.6 "$SCENE"
    check bunny_means -s 64 -r 160 120 -t 2 --seed 1 --density 0.5 -g 0.6 "$SCENE"
else
    echo "skip  bunny: $SCENE not found (the CS184 scenes live in SHARED=$SHARED)"
fi
exit "$status"
