#!/bin/sh
# test_preview.sh - the GLFW preview in a real (virtual) window: scripted runs under Xvfb with
# Mesa's software OpenGL, checked through their --screenshot PNGs.
#
#   sh tests/test_preview.sh build/preview        (make test-preview)
#
# Checks: bad flags, bad --keys and a --medium name the scene lacks give exit status 2 and
# one line; --medium fills an interface cube with fog; a run exits 0, prints its
# summary line and leaves a screenshot that is not black; the same arguments give the same
# screenshot; a key that changes g, the density or the fog, and a scripted mouse drag, change
# the picture by much more than a change of random seed does (the noise floor); `s` writes a
# PNG and a PFM named after the settings; `h` prints the key table.
# Without $FOGRT_PREVIEW_IN_XVFB it re-runs itself under xvfb-run (one X server for all runs).
# Prints one line per failed check and "N passed, M failed"; exit status 1 if any failed.

preview=${1:-build/preview}
case $preview in */*) ;; *) preview=./$preview ;; esac
if [ ! -x "$preview" ]; then
    echo "test_preview.sh: $preview is not built (make preview)"
    echo "0 passed, 1 failed"
    exit 1
fi
if [ -z "$FOGRT_PREVIEW_IN_XVFB" ]; then
    if ! command -v xvfb-run >/dev/null 2>&1; then
        echo "test_preview.sh: xvfb-run not found (Debian package xvfb)"
        echo "0 passed, 1 failed"
        exit 1
    fi
    FOGRT_PREVIEW_IN_XVFB=1 exec xvfb-run -a -s "-screen 0 1280x1024x24" sh "$0" "$@"
fi

tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT
pass=0
fail=0
# check CONDITION DESCRIPTION [RUN-NAME]: on failure also shows that run's stderr
check() {
    if eval "$1"; then
        pass=$((pass + 1))
    else
        echo "FAIL: $2"
        fail=$((fail + 1))
        if [ -n "$3" ] && [ -s "$tmp/$3.err" ]; then sed 's/^/    /' "$tmp/$3.err" | head -5; fi
    fi
}

# ---- a small PNG reader for the checks (stb_image from libstb-dev) ----
cat >"$tmp/pngcheck.c" <<'EOF'
/* pngcheck stats A.png: "width height mean nonblack"  (mean of all channels, 0..255; nonblack:
   the fraction of pixels with a channel above 16)
   pngcheck diff A.png B.png [B]: "mean_abs block_abs"  (mean absolute difference of the channels,
   and of the means of BxB blocks, B = 64 unless given, which averages pixel noise away) */
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb/stb_image.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
static unsigned char *load(const char *path, int *w, int *h)
{
    int n;
    unsigned char *p = stbi_load(path, w, h, &n, 3);
    if (!p) fprintf(stderr, "pngcheck: %s: %s\n", path, stbi_failure_reason());
    return p;
}
int main(int argc, char **argv)
{
    int w, h, w2, h2, x, y, c;
    unsigned char *a, *b;
    if (argc == 3 && strcmp(argv[1], "stats") == 0) {
        double sum = 0.0, lit = 0.0;
        if (!(a = load(argv[2], &w, &h))) return 1;
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                const unsigned char *p = a + 3 * ((size_t)y * w + x);
                sum += p[0] + p[1] + p[2];
                if (p[0] > 16 || p[1] > 16 || p[2] > 16) lit += 1.0;
            }
        printf("%d %d %.3f %.4f\n", w, h, sum / (3.0 * w * h), lit / ((double)w * h));
        return 0;
    }
    if ((argc == 4 || argc == 5) && strcmp(argv[1], "diff") == 0) {
        int B = argc == 5 ? atoi(argv[4]) : 64;
        double d = 0.0, bd = 0.0;
        int blocks = 0, bx, by;
        if (!(a = load(argv[2], &w, &h)) || !(b = load(argv[3], &w2, &h2))) return 1;
        if (w != w2 || h != h2) { fprintf(stderr, "pngcheck: sizes differ\n"); return 1; }
        for (x = 0; x < 3 * w * h; ++x) d += fabs((double)a[x] - (double)b[x]);
        if (B < 1) B = 64;
        for (by = 0; by + B <= h; by += B)
            for (bx = 0; bx + B <= w; bx += B)
                for (c = 0; c < 3; ++c) {
                    double sa = 0.0, sb = 0.0;
                    for (y = by; y < by + B; ++y)
                        for (x = bx; x < bx + B; ++x) {
                            sa += a[3 * ((size_t)y * w + x) + c];
                            sb += b[3 * ((size_t)y * w + x) + c];
                        }
                    bd += fabs(sa - sb) / ((double)B * B);
                    blocks++;
                }
        printf("%.4f %.4f\n", d / (3.0 * w * h), blocks ? bd / blocks : 0.0);
        return 0;
    }
    fprintf(stderr, "usage: pngcheck stats A.png | pngcheck diff A.png B.png [BLOCK]\n");
    return 2;
}
EOF
if ! ${CC:-cc} -O2 -o "$tmp/pngcheck" "$tmp/pngcheck.c" -lm 2>"$tmp/cc.err"; then
    echo "test_preview.sh: cannot build the PNG checker (libstb-dev installed?):"
    sed 's/^/    /' "$tmp/cc.err" | head -5
    echo "0 passed, 1 failed"
    exit 1
fi

# run NAME ARGS...: runs the preview, keeps stdout/stderr in $tmp/NAME.out/.err, status in $rc
run() {
    name=$1
    shift
    "$preview" "$@" >"$tmp/$name.out" 2>"$tmp/$name.err"
    rc=$?
}
frames=12
common="-r 320 240 --scale 2 --frames $frames"

# ---- bad input: exit 2 and exactly one line ----
run badflag --bogus
check "[ $rc -eq 2 ] && [ \$(wc -l <'$tmp/badflag.err') -eq 1 ] && grep -q -- '--bogus' '$tmp/badflag.err'" \
      "unknown flag: exit $rc, expected 2 and one line naming --bogus" badflag
run badkeys --frames 5 --keys "3:w,9:f"
check "[ $rc -eq 2 ] && [ \$(wc -l <'$tmp/badkeys.err') -eq 1 ] && grep -q 'frame 9' '$tmp/badkeys.err'" \
      "--keys with a frame after the last: exit $rc, expected 2 and one line naming frame 9" badkeys
run badkey --frames 5 --keys "3:k"
check "[ $rc -eq 2 ] && [ \$(wc -l <'$tmp/badkey.err') -eq 1 ]" "--keys with an unknown key: exit $rc, expected 2 and one line" badkey
run hugeimage -r 16384 16384 --scale 1 --frames 1
check "[ $rc -eq 2 ] && [ \$(wc -l <'$tmp/hugeimage.err') -eq 1 ] && grep -q -- '-r 16384 16384' '$tmp/hugeimage.err'" \
      "-r 16384 16384 --scale 1 (40 GiB of buffers): exit $rc, expected 2 and one line naming -r before allocating" hugeimage
run bigdrag --frames 5 --keys "3:drag:1e9,0"
check "[ $rc -eq 2 ] && [ \$(wc -l <'$tmp/bigdrag.err') -eq 1 ] && grep -q '1e6' '$tmp/bigdrag.err'" "--keys with a drag of 1e9 pixels: exit $rc, expected 2 and one line giving the range" bigdrag
run badscene "$tmp/nothere.obj"
check "[ $rc -eq 2 ] && [ \$(wc -l <'$tmp/badscene.err') -eq 1 ]" "missing scene file: exit $rc, expected 2 and one line" badscene
# --medium, parsed and applied by cli_common.h as in fogrt: a closed cube (object cube) holds
# fog behind an interface; a name the scene lacks is one line listing its names
{ echo "o cube"; for p in "0 0 0" "1 0 0" "1 0 1" "0 0 1" "0 1 0" "1 1 0" "1 1 1" "0 1 1"; do echo "v $p"; done
  printf 'f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n'; } >"$tmp/cube.obj"
run badmedium --frames 1 --medium nothere --density 1 "$tmp/cube.obj"
check "[ $rc -eq 2 ] && [ \$(wc -l <'$tmp/badmedium.err') -eq 1 ] && grep -q -- '--medium nothere: .*object (o) names: cube' '$tmp/badmedium.err'" \
      "--medium with a name the scene lacks: exit $rc, expected 2 and one line listing the names" badmedium
run medium -r 64 48 --frames 2 --medium cube --interface --density 3 --albedo 0.5 "$tmp/cube.obj"
check "[ $rc -eq 0 ] && grep -q 'frames/s' '$tmp/medium.out'" "--medium cube --interface --density 3: exit status $rc, expected 0" medium

# ---- the default scene: runs, exits 0, not black, reproducible ----
run base $common --screenshot "$tmp/base.png"
check "[ $rc -eq 0 ]" "scripted run: exit status $rc, expected 0" base
check "grep -q 'frames/s' '$tmp/base.out'" "scripted run: no summary line on stdout"
grep 'frames/s' "$tmp/base.out"
set -- $("$tmp/pngcheck" stats "$tmp/base.png" 2>/dev/null)
check "[ '$1x$2' = '640x480' ]" "screenshot size is '$1x$2', expected 640x480 (320x240 at --scale 2)"
check "awk 'BEGIN { exit !(${3:-0} > 20 && ${4:-0} > 0.5) }'" "screenshot is (nearly) black: mean ${3:-?}, lit fraction ${4:-?}"
echo "base screenshot: mean $3 of 255, $4 of the pixels lit"

run again $common --screenshot "$tmp/again.png"   # same arguments, same picture
set -- $("$tmp/pngcheck" diff "$tmp/base.png" "$tmp/again.png" 2>/dev/null)
check "[ $rc -eq 0 ] && [ '${1:-x}' = '0.0000' ]" "the same arguments gave a different screenshot (mean difference ${1:-?})" again

# A restart (r at frame 4) clears the accumulation: frames 4..12 then show exactly what a fresh
# run of 9 frames shows (every sample's random stream is fixed by seed, pixel and index).
run restart $common --keys "4:r" --screenshot "$tmp/restart.png"
run nine -r 320 240 --scale 2 --frames $((frames - 3)) --screenshot "$tmp/nine.png"
set -- $("$tmp/pngcheck" diff "$tmp/restart.png" "$tmp/nine.png" 2>/dev/null)
check "[ $rc -eq 0 ] && [ '${1:-x}' = '0.0000' ]" "r at frame 4 of $frames did not give the picture of a fresh $((frames - 3))-frame run (mean difference ${1:-?})" nine

# The noise floor: the restarted view with another seed differs from it only by noise. Every
# change below restarts at frame 4 too, so it is compared with the restarted picture.
run seed $common --keys "4:r" --seed 7 --screenshot "$tmp/seed.png"
set -- $("$tmp/pngcheck" diff "$tmp/restart.png" "$tmp/seed.png" 2>/dev/null)
noise=${2:-0}
check "[ $rc -eq 0 ] && awk 'BEGIN { exit !($noise > 0) }'" "another seed gave the same picture (the seed is ignored?)" seed
echo "noise floor (another seed): block difference $noise"

# differs NAME WHAT KEYS: the picture after KEYS must differ from the restarted one by more
# than 3x the noise floor
differs() {
    name=$1 what=$2 keys=$3
    run "$name" $common --keys "$keys" --screenshot "$tmp/$name.png"
    check "[ $rc -eq 0 ]" "$what (--keys $keys): exit status $rc" "$name"
    check "grep -Eq 'key to new frame [0-9.]+ ms' '$tmp/$name.out'" "$what: no key-to-frame latency in the summary"
    set -- $("$tmp/pngcheck" diff "$tmp/restart.png" "$tmp/$name.png" 2>/dev/null)
    check "awk 'BEGIN { exit !(${2:-0} > 3 * $noise) }'" "$what (--keys $keys) did not change the picture: block difference ${2:-?}, noise floor $noise"
    echo "$what (--keys $keys): block difference ${2:-?} (noise floor $noise)"
}
differs g_up    "g 0.6 -> 0.9"        "4:w,4:w,4:w"
differs g_back  "g 0.6 -> -0.3"       "4:q,4:q,4:q,4:q,4:q,4:q,4:q,4:q,4:q"
differs dense   "density 0.3 -> 0.59" "4:x,4:x,4:x"
differs fogoff  "fog off"             "4:f"
differs drag    "mouse drag"          "4:drag:80,0"
grep 'frames/s' "$tmp/drag.out"
# chromatic fog (--density R,G,B): differs from the grey fog, and the density keys scale it
run chroma $common --density 0.1,0.3,0.9 --keys "4:r" --screenshot "$tmp/chroma.png"
set -- $("$tmp/pngcheck" diff "$tmp/restart.png" "$tmp/chroma.png" 2>/dev/null)
check "[ $rc -eq 0 ] && awk 'BEGIN { exit !(${2:-0} > 3 * $noise) }'" "--density 0.1,0.3,0.9 did not change the picture: block difference ${2:-?}, noise floor $noise" chroma
run chroma_dense $common --density 0.1,0.3,0.9 --keys "4:x,4:x,4:x" --screenshot "$tmp/chroma_dense.png"
set -- $("$tmp/pngcheck" diff "$tmp/chroma.png" "$tmp/chroma_dense.png" 2>/dev/null)
check "[ $rc -eq 0 ] && awk 'BEGIN { exit !(${2:-0} > 3 * $noise) }'" "chromatic fog, density up (x x x) did not change the picture: block difference ${2:-?}, noise floor $noise" chroma_dense
echo "chromatic fog: block difference from the grey fog, and after x x x: ${2:-?} (noise floor $noise)"

# A key at the last frame still shows: exposure down after the base picture's last batch.
run dark $common --keys "$frames:-,$frames:-" --screenshot "$tmp/dark.png"
set -- $("$tmp/pngcheck" stats "$tmp/dark.png" 2>/dev/null)
dark=${3:-0}
set -- $("$tmp/pngcheck" stats "$tmp/base.png" 2>/dev/null)
check "[ $rc -eq 0 ] && awk 'BEGIN { exit !($dark < 0.95 * ${3:-0}) }'" "exposure down at the last frame did not darken the picture ($dark vs ${3:-?})" dark

# ---- s saves PNG and PFM named after the settings; h prints the keys ----
mkdir "$tmp/saved"
run save $common --keys "3:w,3:w,3:w,$frames:s,$frames:h" --save-dir "$tmp/saved"
png=$(ls "$tmp/saved" | grep '_g0\.90_.*\.png$' | head -1)
pfm=$(ls "$tmp/saved" | grep '_g0\.90_.*\.pfm$' | head -1)
check "[ $rc -eq 0 ] && [ -n '$png' ] && [ -n '$pfm' ]" "s did not write a PNG and a PFM with g0.90 in the name (got: $(ls "$tmp/saved" | tr '\n' ' '))" save
[ -n "$png" ] && echo "s wrote $png and its .pfm"
check "[ -n '$png' ] && [ \"\$(head -c 2 '$tmp/saved/$pfm')\" = 'PF' ]" "the saved .pfm is not a colour PFM"
check "grep -q 'fog on / off' '$tmp/save.out'" "h did not print the key table"

# ---- the flags shared with fogrt (examples/cli_common.h): one parser, one meaning ----
src=$(dirname "$0")/..
parser_flags=$(grep -ho 'cli_is(&\{0,1\}A, "[^"]*")' "$src/examples/preview.c" "$src/examples/cli_common.h" | sed 's/.*"\(.*\)")/\1/' | sort -u | tr '\n' ' ')
help_flags=$("$preview" -h | sed -n 's/^  \(-[-a-zA-Z0-9]*\) .*/\1/p' | grep -v '^-$' | sort -u | tr '\n' ' ')
check "[ -n '$parser_flags' ] && [ '$parser_flags' = '$help_flags' ]" "preview -h lists [$help_flags], the parser takes [$parser_flags]"
run depthneg -m -1
check "[ $rc -eq 2 ] && grep -q -- '-m' '$tmp/depthneg.err'" "-m -1: exit $rc, expected 2 as in fogrt (the ] key gives unlimited depth)" depthneg
run misspelt --densty 0.5
check "[ $rc -eq 2 ] && grep -q 'did you mean --density?' '$tmp/misspelt.err'" "--densty: exit $rc, no suggestion" misspelt
run fogrtonly -s 4
check "[ $rc -eq 2 ] && grep -q 'does not apply to the preview' '$tmp/fogrtonly.err'" "-s: exit $rc, not said to be fogrt's" fogrtonly
cp "$tmp/base.png" "$tmp/image.obj"
run pngscene "$tmp/image.obj"
check "[ $rc -eq 2 ] && grep -q 'a PNG image, not a scene' '$tmp/pngscene.err'" "a PNG named .obj: exit $rc, not said to be a PNG" pngscene
# --exposure is stops, as in fogrt: 0 is the base picture, -1 darker, =value accepted
run ev0 $common --exposure=0 --screenshot "$tmp/ev0.png"
set -- $("$tmp/pngcheck" diff "$tmp/base.png" "$tmp/ev0.png" 2>/dev/null)
check "[ $rc -eq 0 ] && [ '${1:-x}' = '0.0000' ]" "--exposure=0 is not the default picture (mean difference ${1:-?})" ev0
run evm1 $common --exposure -1 --screenshot "$tmp/evm1.png"
set -- $("$tmp/pngcheck" stats "$tmp/evm1.png" 2>/dev/null)
evm1=${3:-0}
set -- $("$tmp/pngcheck" stats "$tmp/base.png" 2>/dev/null)
check "[ $rc -eq 0 ] && awk 'BEGIN { exit !($evm1 < 0.9 * ${3:-0} && $evm1 > 0.5 * ${3:-0}) }'" "--exposure -1 is not one stop darker through the sRGB curve ($evm1 vs ${3:-?})" evm1
OMP_NUM_THREADS=100000 "$preview" $common --screenshot "$tmp/omp.png" >"$tmp/omp.out" 2>"$tmp/omp.err"; rc=$?
check "[ $rc -eq 0 ] && grep -q 'OMP_NUM_THREADS=100000: using' '$tmp/omp.err'" "OMP_NUM_THREADS=100000: exit $rc" omp
OMP_STACKSIZE=16K "$preview" $common --screenshot "$tmp/stk.png" >"$tmp/stk.out" 2>"$tmp/stk.err"; rc=$?
check "[ $rc -eq 2 ] && grep -q 'OMP_STACKSIZE' '$tmp/stk.err'" "OMP_STACKSIZE=16K: exit $rc, expected 2 naming it" stk
# threads the system cannot start (stacks of 100000G): fewer threads with a warning, in the
# render thread too (which builds the scene, the roulette pilot's parallel region included)
OMP_STACKSIZE=100000G "$preview" $common --keys "4:f" --screenshot "$tmp/bigstk.png" >"$tmp/bigstk.out" 2>"$tmp/bigstk.err"; rc=$?
check "[ $rc -eq 0 ] && [ -s '$tmp/bigstk.png' ] && ! grep -q 'libgomp' '$tmp/bigstk.err'" "OMP_STACKSIZE=100000G: exit $rc, expected 0 with fewer threads" bigstk

# ---- --screenshot and s write as fogrt does: temporary file, checked writes, rename ----
ln -s /dev/full "$tmp/full.png"
run shotfull $common --screenshot "$tmp/full.png"
check "[ $rc -eq 1 ] && grep -q 'full.png' '$tmp/shotfull.err' && grep -q 'No space left' '$tmp/shotfull.err'" "--screenshot to /dev/full: exit $rc, expected 1 naming the file" shotfull
printf 'an old picture' >"$tmp/old.png"; cp "$tmp/old.png" "$tmp/old.orig"
( ulimit -f 8; "$preview" $common --screenshot "$tmp/old.png" >"$tmp/shotbig.out" 2>"$tmp/shotbig.err" ); rc=$?
check "[ $rc -eq 1 ] && grep -q 'old.png' '$tmp/shotbig.err' && cmp -s '$tmp/old.png' '$tmp/old.orig'" "--screenshot beyond ulimit -f: exit $rc, or the old file was damaged" shotbig
check "[ -z \"\$(ls -A '$tmp' | grep '\\.tmp-')\" ]" "--screenshot left a temporary file behind"
# a scripted save that fails (its directory does not exist) is exit status 1, naming the file
run savemissing $common --keys "$frames:s" --save-dir "$tmp/no/such/dir"
check "[ $rc -eq 1 ] && grep -q 'no/such/dir/fogrt-preview_.*\.pfm: cannot write' '$tmp/savemissing.err'" "s into a missing directory: exit $rc, expected 1 naming the file" savemissing
if [ "$(id -u)" -eq 0 ] && mkdir "$tmp/small" && mount -t tmpfs -o size=64k tmpfs "$tmp/small" 2>/dev/null; then
    # a real full disk: an old PNG on a 64 KB file system, the rest of it filled
    cp "$tmp/old.orig" "$tmp/small/shot.png"
    dd if=/dev/zero of="$tmp/small/fill" bs=4k 2>/dev/null
    run shotdisk $common --screenshot "$tmp/small/shot.png"
    check "[ $rc -eq 1 ] && grep -q 'shot.png' '$tmp/shotdisk.err' && cmp -s '$tmp/small/shot.png' '$tmp/old.orig'" "--screenshot on a full disk: exit $rc, or the old PNG was damaged" shotdisk
    check "[ -z \"\$(ls -A '$tmp/small' | grep tmp)\" ]" "--screenshot on a full disk left a temporary file"
    mkdir -p "$tmp/small2"
    run savedisk $common --keys "$frames:s" --save-dir "$tmp/small"
    check "[ $rc -eq 1 ] && grep -q 'No space left' '$tmp/savedisk.err' && [ -z \"\$(ls -A '$tmp/small' | grep -v '^fill\$\\|^shot.png\$')\" ]" "s on a full disk: exit $rc (expected 1), no message, or a partial file left" savedisk
    umount "$tmp/small"
else
    echo "test_preview.sh: full-disk screenshot skipped (needs root and a tmpfs mount)"
fi
cp tests/data/obj_polygons.obj "$tmp/scene.obj" 2>/dev/null || cp "$(dirname "$0")/data/obj_polygons.obj" "$tmp/scene.obj"
ln -s scene.obj "$tmp/scene_link.png"
run shotalias $common --screenshot "$tmp/scene_link.png" "$tmp/scene.obj"
check "[ $rc -eq 2 ] && grep -q 'same file' '$tmp/shotalias.err' && cmp -s '$tmp/scene.obj' \"\$(dirname \"$0\")/data/obj_polygons.obj\"" "--screenshot a symlink to the scene: exit $rc, expected 2 with the scene intact" shotalias

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
