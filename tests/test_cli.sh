#!/bin/sh
# test_cli.sh - the `fogrt` command line: bad input gives exit status 2 and one message naming
# the flag or file:line, without writing an image; good input renders and writes the image;
# then one block per feature: Ctrl-C/SIGTERM, atomic and
# checked writes, the free camera, exposure and JPG, CS184 framing, -m 0 / -o 0, the -a rate
# image, the progress line and --log/--reference, black scenes, ceilings and limits.
# Takes about 30 s (a 2-second interrupt, a 6-second progress log).
#
#   sh tests/test_cli.sh build/fogrt        (make cli-test; part of make test)
#
# Prints one line per failed check and a summary; exit status 1 if any check failed.

fogrt=${1:-build/fogrt}
case $fogrt in */*) ;; *) fogrt=./$fogrt ;; esac
[ -x "$fogrt" ] || { echo "test_cli.sh: $fogrt is not built"; exit 1; }
tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT
pass=0
fail=0

# expect STATUS WORD DESCRIPTION -- ARGS...: runs fogrt, checks the exit status, and that
# stderr contains WORD (skip with "").
expect() {
    want=$1 word=$2 what=$3
    shift 4
    "$fogrt" "$@" >"$tmp/out" 2>"$tmp/err"
    got=$?
    if [ "$got" -ne "$want" ]; then
        echo "FAIL: $what: exit status $got, expected $want (fogrt $*)"
        sed 's/^/    /' "$tmp/err" | head -5
        fail=$((fail + 1))
        return 1
    fi
    if [ -n "$word" ] && ! grep -qF -- "$word" "$tmp/err"; then
        echo "FAIL: $what: stderr does not mention '$word' (fogrt $*)"
        sed 's/^/    /' "$tmp/err" | head -5
        fail=$((fail + 1))
        return 1
    fi
    pass=$((pass + 1))
    return 0
}
# check CONDITION-COMMAND DESCRIPTION
check() {
    if eval "$1"; then pass=$((pass + 1)); else echo "FAIL: $2"; fail=$((fail + 1)); fi
}
# A failing run must print exactly one line and write no image.
one_line_no_image() {
    lines=$(wc -l <"$tmp/err")
    check "[ $lines -eq 1 ]" "$1: expected one error line, got $lines"
    check "[ ! -e '$tmp/never.png' ]" "$1: an image was written despite the error"
}

out="$tmp/never.png"
# ---- flags: values out of range, unknown flags, missing values (exit 2, the flag named) ----
expect 2 "--bogus"      "unknown flag"            -- --bogus -f "$out";                one_line_no_image "unknown flag"
expect 2 "-x"           "unknown short flag"      -- -x -f "$out";                     one_line_no_image "unknown short flag"
check "! grep -q 'did you mean' '$tmp/err'" "unknown short flag: -x gets a suggestion that shares no letter with it: $(cat "$tmp/err")"
expect 2 "did you mean --density?" "misspelt flag: a suggestion" -- --densty 0.5 -f "$out"
expect 2 "did you mean -s?" "a short flag with two dashes: a suggestion" -- --s 4 -f "$out"
expect 2 "--density"    "negative density"        -- --density -0.5 -f "$out";         one_line_no_image "negative density"
expect 2 "--density"    "non-numeric density"     -- --density fog -f "$out"
expect 2 "--g"          "|g| > 1 (--g)"           -- --g 1.5 -f "$out";                one_line_no_image "|g| > 1"
expect 2 "-g"           "|g| > 1 (-g)"            -- -g -1.01 -f "$out"
expect 2 "-r"           "zero width"              -- -r 0 360 -f "$out";               one_line_no_image "zero width"
expect 2 "-r"           "zero height"             -- -r 480 0 -f "$out"
expect 2 "-r"           "negative resolution"     -- -r -480 360 -f "$out"
expect 2 "-r"           "resolution beyond the flag range" -- -r 100000 100000 -f "$out"
expect 2 "-r 30000 30000" "resolution too large to allocate" -- -r 30000 30000 -s 1 -f "$out"; one_line_no_image "huge resolution"
expect 2 "-s"           "zero samples"            -- -s 0 -f "$out"
expect 2 "-s"           "missing value"           -- -f "$out" -s
expect 2 "-l"           "zero light samples"      -- -l 0 -f "$out"
expect 2 "-t"           "negative threads"        -- -t -2 -f "$out"
expect 2 "-m"           "negative depth"          -- -m -1 -f "$out"
expect 2 "-o"           "-o other than 0 or 1"    -- -o 2 -f "$out"
expect 2 "-b"           "negative lens radius"    -- -b -0.1 -f "$out"
expect 2 "-d"           "zero focal distance"     -- -d 0 -f "$out"
expect 2 "-a"           "adaptive tolerance 0"    -- -a 8 0 -f "$out"
expect 2 "--albedo"     "albedo above 1"          -- --albedo 1.5 -f "$out"
expect 2 "--albedo"     "albedo with two parts"   -- --albedo 0.5,0.5 -f "$out"
expect 2 "--albedo"     "negative albedo channel" -- --albedo 0.5,-0.1,0.5 -f "$out"
expect 2 "--integrator" "unknown integrator"      -- --integrator bidir -f "$out"
# appendix G's fog flags: two lobes, the phase function, emission
expect 2 "--g"          "two lobes, |G1| > 1"     -- --g 1.5,0,0.5 -f "$out";          one_line_no_image "two lobes, |G1| > 1"
expect 2 "--g"          "two lobes, W > 1"        -- --g 0.5,0.2,1.2 -f "$out"
expect 2 "--g"          "two lobes, W < 0"        -- --g 0.5,0.2,-0.1 -f "$out"
expect 2 "--g"          "two values for --g"      -- --g 0.5,0.2 -f "$out"
expect 2 "-g"           "two lobes, NaN G2 (-g)"  -- -g 0.5,nan,0.5 -f "$out"
expect 2 "--phase"      "unknown phase function"  -- --phase mie -f "$out";            one_line_no_image "unknown phase"
expect 2 "--phase"      "missing phase"           -- -f "$out" --phase
expect 2 "--phase"      "rayleigh with two lobes" -- --phase rayleigh --g 0.8,-0.4,0.7 -f "$out"; one_line_no_image "rayleigh with two lobes"
expect 2 "--emission"   "negative emission"       -- --emission -1 -f "$out";          one_line_no_image "negative emission"
expect 2 "--emission"   "emission with two parts" -- --emission 1,2 -f "$out"
expect 2 "--emission"   "infinite emission"       -- --emission 1,inf,1 -f "$out"
expect 2 "--emission"   "NaN emission"            -- --emission nan -f "$out"
expect 2 "--density"    "negative density channel" -- --density 0.1,-0.2,0.3 -f "$out"; one_line_no_image "negative density channel"
expect 2 "--density"    "density with two parts"  -- --density 0.1,0.2 -f "$out"
expect 2 "--density"    "infinite density channel" -- --density 0.1,inf,0.3 -f "$out"
expect 2 "--density"    "NaN density channel"     -- --density nan,0.2,0.3 -f "$out"
expect 2 "--fresnel"    "unknown fresnel"         -- --fresnel fast -f "$out"
expect 2 "--bvh"        "unknown bvh"             -- --bvh kd -f "$out"
expect 2 "--seed"       "negative seed"           -- --seed -1 -f "$out"
expect 2 "--time"       "zero time"               -- --time 0 -f "$out"
expect 2 "--target-error" "negative target error" -- --target-error -1 -f "$out"
expect 2 "-f"           "unknown image type"      -- -f "$tmp/out.gif"
expect 1 "no/such/dir/out.png" "output in a missing directory (before rendering)" -- -f "$tmp/no/such/dir/out.png"; one_line_no_image "missing output directory"
expect 2 "only one scene" "two scene files"       -- -f "$out" a.dae b.dae

# ---- scene files: missing, malformed, truncated, unknown type (exit 2, file:line named) ----
expect 2 "no_such.dae"  "missing scene file"      -- -f "$out" "$tmp/no_such.dae";    one_line_no_image "missing scene"
expect 2 "bad_index.dae:18:" "malformed .dae names file:line" -- -f "$out" tests/data/bad_index.dae; one_line_no_image "malformed dae"
expect 2 "bad_unclosed.dae:28:" "truncated .dae"  -- -f "$out" tests/data/bad_unclosed.dae
expect 2 "obj_bad_index.obj:6:" "malformed .obj" -- -f "$out" tests/data/obj_bad_index.obj
expect 2 "ply_truncated.ply:11:" "truncated .ply" -- -f "$out" tests/data/ply_truncated.ply
head -c 700 tests/data/dae_materials.dae >"$tmp/cut.dae"
expect 2 "cut.dae:"     "a .dae cut in the middle" -- -f "$out" "$tmp/cut.dae"
printf 'not a scene\n' >"$tmp/scene.txt"
expect 2 "unknown scene type" "unknown scene extension" -- -f "$out" "$tmp/scene.txt"
expect 2 "no_camera.txt" "missing -c file"        -- -f "$out" -c "$tmp/no_camera.txt"
printf '49 37 1.3\n0.1 100\n' >"$tmp/short.cam"
expect 2 "short.cam:2:" "malformed -c file"       -- -f "$out" -c "$tmp/short.cam"

# ---- help ----
expect 0 "" "help" -- -h
for flag in -s -l -t -m -o -r -f -b -d -a -H -c -g -h --density --albedo --g --phase --emission --medium --interface --integrator --fresnel --bvh --seed --time --target-error --quiet \
            --camera-pos --look-at --up --fov --cs184-framing --print-camera --exposure --log --reference --equiangular --mis --glow --footprint --expected-emission --lights; do
    check "grep -qF -- ' $flag ' '$tmp/out'" "-h does not document $flag"
done
defaults=$(grep -c 'default' "$tmp/out")
check "[ $defaults -ge 20 ]" "-h names a default for every flag (found $defaults)"

# ---- good runs: every output type, every scene type, the method flags ----
expect 0 "spp" "default scene to PNG with a summary line" -- -s 1 -r 32 24 -f "$tmp/a.png"
check "[ \"\$(head -c 4 '$tmp/a.png' | od -An -c | tr -d ' ')\" = '211PNG' ]" "a.png is not a PNG"
check "grep -q 'rel. error' '$tmp/err'" "the summary line has no error estimate"
expect 0 "" "quiet dae to PFM" -- --quiet -s 2 -r 40 30 -f "$tmp/b.pfm" tests/data/dae_mirror_node.dae
check "[ ! -s '$tmp/err' ]" "--quiet still printed something"
check "[ \"\$(head -c 2 '$tmp/b.pfm')\" = 'PF' ]" "b.pfm is not a PFM"
expect 0 "" "obj in the Cornell box to PPM" -- --quiet -s 1 -r 24 18 -f "$tmp/c.ppm" tests/data/obj_polygons.obj
check "[ \"\$(head -c 2 '$tmp/c.ppm')\" = 'P6' ]" "c.ppm is not a PPM"
expect 0 "" "ply, fog and method flags" -- --quiet -s 2 -r 24 18 -f "$tmp/d.png" --density 0.5 --albedo 0.8,0.9,1 --g -0.3 \
    --integrator direct --fresnel exact --bvh volume --seed 7 -t 1 -l 2 -m 3 -b 0.01 -d 3 tests/data/ply_ascii.ply
expect 0 "" "adaptive sampling, hemisphere sampling, paper's -g" -- --quiet -s 8 -a 4 0.2 -H -g 0.5 -r 24 18 -f "$tmp/e.png" tests/data/dae_point_spot.dae
expect 0 "" "time budget without -s" -- --quiet --time 0.3 -r 16 12 -f "$tmp/f.png"
expect 0 "" "target error" -- --quiet --target-error 0.5 -r 16 12 -f "$tmp/g.png"
expect 0 "" "camera file" -- --quiet -s 1 -r 16 12 -c tests/data/cam_settings.txt -f "$tmp/h.png"
for f in a.png b.pfm c.ppm d.png e.png f.png g.png h.png; do
    check "[ -s '$tmp/$f' ]" "$f was not written"
done
# the same seed gives the same image, on 1 or 2 threads
"$fogrt" --quiet -s 2 -r 20 16 --seed 3 -t 1 -f "$tmp/t1.pfm" tests/data/dae_mirror_node.dae
"$fogrt" --quiet -s 2 -r 20 16 --seed 3 -t 2 -f "$tmp/t2.pfm" tests/data/dae_mirror_node.dae
check "cmp -s '$tmp/t1.pfm' '$tmp/t2.pfm'" "the image depends on the thread count"

# ==== the fogrt command in real use: one block per feature ====
# pfm_stats FILE: "W H pixels_nonzero sum_r sum_g sum_b floats" of a PFM (od reads the floats).
pfm_stats() {
    hdr=$(head -n 3 "$1" | wc -c)
    dims=$(head -n 2 "$1" | tail -n 1)
    tail -c +$((hdr + 1)) "$1" | od -An -v -f | awk -v dims="$dims" '
        { for (i = 1; i <= NF; i++) { c = n % 3; s[c] += $i; if ($i != 0) nz[int(n / 3)] = 1; n++ } }
        END { k = 0; for (p in nz) k++; printf "%s %d %.9g %.9g %.9g %d\n", dims, k, s[0], s[1], s[2], n }'
}
# pfm_ok FILE W H: a PFM of that size with the whole pixel block
pfm_ok() {
    [ "$(head -c 2 "$1" 2>/dev/null)" = "PF" ] || return 1
    [ "$(head -n 2 "$1" | tail -n 1)" = "$2 $3" ] || return 1
    hdr=$(head -n 3 "$1" | wc -c)
    [ "$(wc -c <"$1")" -eq $((hdr + $2 * $3 * 12)) ]
}
# appendix G's fog flags render; a single --g and --phase hg are today's fog, bit for bit;
# emitting fog is brighter than the same fog without
expect 0 "" "two lobes, Rayleigh, emission" -- --quiet -s 2 -r 16 12 --g 0.8,-0.4,0.7 --emission 0.2,0.1,0.05 -f "$tmp/m1.pfm"
expect 0 "" "Rayleigh" -- --quiet -s 2 -r 16 12 --phase rayleigh --density 0.5 -f "$tmp/m2.pfm"
check "pfm_ok '$tmp/m1.pfm' 16 12 && pfm_ok '$tmp/m2.pfm' 16 12" "media: the images were not written"
"$fogrt" --quiet -s 2 -r 16 12 --seed 2 --g 0.6 -f "$tmp/m3.pfm"
"$fogrt" --quiet -s 2 -r 16 12 --seed 2 --g 0.6 --phase hg --emission 0 -f "$tmp/m4.pfm"
check "cmp -s '$tmp/m3.pfm' '$tmp/m4.pfm'" "media: --phase hg --emission 0 changed the image of --g 0.6"
"$fogrt" --quiet -s 2 -r 16 12 --seed 2 --g 0.6 --emission 0.5 -f "$tmp/m5.pfm"
check "[ \"\$(pfm_stats '$tmp/m5.pfm' | awk '{ print \$4 }')\" != \"\$(pfm_stats '$tmp/m3.pfm' | awk '{ print \$4 }')\" ] && awk -v a=\"\$(pfm_stats '$tmp/m5.pfm' | awk '{ print \$4 }')\" -v b=\"\$(pfm_stats '$tmp/m3.pfm' | awk '{ print \$4 }')\" 'BEGIN { exit !(a > b) }'" "media: --emission 0.5 did not brighten the image"
# chromatic fog: --density R,G,B renders and says so; three equal channels are grey fog, bit
# for bit
expect 0 "density 0.1,0.3,0.9" "chromatic fog" -- -s 2 -r 16 12 --density 0.1,0.3,0.9 -f "$tmp/c1.pfm"
check "pfm_ok '$tmp/c1.pfm' 16 12" "chromatic fog: the image was not written"
"$fogrt" --quiet -s 2 -r 16 12 --seed 3 --density 0.4 -f "$tmp/c2.pfm"
"$fogrt" --quiet -s 2 -r 16 12 --seed 3 --density 0.4,0.4,0.4 -f "$tmp/c3.pfm"
check "cmp -s '$tmp/c2.pfm' '$tmp/c3.pfm'" "chromatic fog: --density 0.4,0.4,0.4 is not --density 0.4 bit for bit"
"$fogrt" --quiet -s 2 -r 16 12 --seed 3 --density 0.4,0.4,0.41 -f "$tmp/c4.pfm"
check "! cmp -s '$tmp/c2.pfm' '$tmp/c4.pfm'" "chromatic fog: --density 0.4,0.4,0.41 rendered grey fog"
now() { date +%s.%N; }
# wait_rendering CSV: wait (up to 60 s) until the render's --log has its first batch row, so
# that a signal sent next lands in the render whatever the machine's speed (a sanitizer
# build takes a second to build the scene and run the roulette's pilot)
wait_rendering() {
    n=0
    while [ $n -lt 1200 ]; do
        [ -f "$1" ] && [ "$(wc -l <"$1")" -ge 2 ] && return 0
        sleep 0.05; n=$((n + 1))
    done
    return 1
}
fogrt_abs=$(cd "$(dirname "$fogrt")" && pwd)/$(basename "$fogrt")
lit=tests/data/dae_mirror_node.dae

# -- interrupt_256spp: SIGINT during a 256-spp render writes the image so far, exits 130 --
"$fogrt" -s 256 -r 320 240 -f "$tmp/int.pfm" --log "$tmp/int.csv" 2>"$tmp/int.err" &
pid=$!
wait_rendering "$tmp/int.csv"; sleep 0.5
t_sig=$(now)
kill -INT "$pid"
wait "$pid"
st=$?
t_end=$(now)
stop=$(echo "$t_end $t_sig" | awk '{ printf "%.2f", $1 - $2 }')
check "[ $st -eq 130 ]" "interrupt_256spp: exit status $st, expected 130"
check "pfm_ok '$tmp/int.pfm' 320 240" "interrupt_256spp: no complete 320x240 PFM was written"
check "grep -q 'interrupted: wrote' '$tmp/int.err'" "interrupt_256spp: the summary does not say interrupted"
check "tail -n 1 '$tmp/int.csv' | grep -q ',interrupted$'" "interrupt_256spp: the --log has no interrupted row"
check "awk 'BEGIN { exit !($stop < 2.5) }'" "interrupt_256spp: took $stop s to stop after SIGINT (limit 2.5 s)"
spp_int=$(grep -o '[0-9.]*/256 spp' "$tmp/int.err" | head -1)
set -- $(pfm_stats "$tmp/int.pfm")
check "[ $3 -gt 0 ]" "interrupt_256spp: the written image is black"
echo "test_cli.sh: interrupt_256spp: stopped ${stop} s after SIGINT, wrote int.pfm with ${spp_int:-?}, exit $st"
# -- interrupt_sigterm: the same for SIGTERM --
"$fogrt" -s 256 -r 160 120 -f "$tmp/term.pfm" --log "$tmp/term.csv" 2>"$tmp/term.err" &
pid=$!
wait_rendering "$tmp/term.csv"
kill -TERM "$pid"; wait "$pid"; st=$?
check "[ $st -eq 130 ] && pfm_ok '$tmp/term.pfm' 160 120" "interrupt_sigterm: exit $st or no image"
# -- interrupt_twice: a second Ctrl-C quits at once, leaving no temporary file --
mkdir -p "$tmp/twice"
"$fogrt" -s 256 -r 320 240 -f "$tmp/twice/x.png" 2>"$tmp/twice.err" &
pid=$!
sleep 1; kill -INT "$pid"; kill -INT "$pid"; wait "$pid"; st=$?
check "[ $st -eq 130 ]" "interrupt_twice: exit status $st, expected 130"
check "[ -z \"\$(ls -A '$tmp/twice' | grep tmp)\" ]" "interrupt_twice: a temporary file was left behind"

# -- write_full_disk: PNG through a symlink to /dev/full: exit 1 naming the file, never "wrote" --
ln -s /dev/full "$tmp/full.png"
expect 1 "full.png" "write_full_disk: PNG to /dev/full" -- -s 1 -r 16 12 -f "$tmp/full.png"
check "grep -q 'No space left' '$tmp/err' && ! grep -q 'wrote' '$tmp/err'" "write_full_disk: no ENOSPC message, or it claims success"
ln -s /dev/full "$tmp/full.pfm"
expect 1 "full.pfm" "write_full_disk: PFM to /dev/full" -- --quiet -s 1 -r 16 12 -f "$tmp/full.pfm"
# -- side_file_lost: a --log that cannot be written (a full disk, a missing directory) costs
#    the log, not the image: a warning naming it, the image written, exit 1 --
ln -s /dev/full "$tmp/full.csv"
expect 1 "full.csv: write failed: No space left" "side_file_lost: --log to /dev/full" -- -s 2 -r 16 12 -f "$tmp/logfull.pfm" --log "$tmp/full.csv"
check "[ -s '$tmp/logfull.pfm' ] && grep -q 'wrote' '$tmp/err'" "side_file_lost: --log to /dev/full lost the image: $(cat "$tmp/err")"
expect 1 "no/dir/x.csv: cannot write" "side_file_lost: --log in a missing directory" -- -s 2 -r 16 12 -f "$tmp/logdir.pfm" --log "$tmp/no/dir/x.csv"
check "[ -s '$tmp/logdir.pfm' ]" "side_file_lost: --log in a missing directory lost the image"
expect 0 "" "side_file_lost: --log /dev/null is a log nobody keeps" -- --quiet -s 2 -r 16 12 -f "$tmp/lognull.pfm" --log /dev/null
# --print-camera and --trace print all the run makes: stdout closed or full is a failure
"$fogrt" --print-camera -r 32 24 >&- 2>"$tmp/err"; st=$?
check "[ $st -eq 1 ] && grep -q 'print-camera: stdout is closed' '$tmp/err'" "side_file_lost: --print-camera with stdout closed: exit $st: $(cat "$tmp/err")"
"$fogrt" --print-camera -r 32 24 >/dev/full 2>"$tmp/err"; st=$?
check "[ $st -eq 1 ] && grep -q 'print-camera: cannot write to stdout' '$tmp/err'" "side_file_lost: --print-camera to /dev/full: exit $st: $(cat "$tmp/err")"
"$fogrt" --trace 2,2 -r 32 24 >/dev/full 2>"$tmp/err"; st=$?
check "[ $st -eq 1 ] && grep -q 'trace: cannot write to stdout' '$tmp/err'" "side_file_lost: --trace to /dev/full: exit $st: $(cat "$tmp/err")"
# -- write_atomic: a failed write keeps the old image; a good one replaces it by rename --
"$fogrt" --quiet -s 1 -r 32 24 -f "$tmp/keep.pfm" "$lit"
cp "$tmp/keep.pfm" "$tmp/keep.orig"
( ulimit -f 4; "$fogrt" --quiet -s 1 -r 32 24 --seed 9 -f "$tmp/keep.pfm" "$lit" ) 2>"$tmp/efbig.err"
st=$?
check "[ $st -eq 1 ] && grep -q 'keep.pfm' '$tmp/efbig.err'" "write_atomic: a write beyond ulimit -f gave exit $st (expected 1 naming the file)"
check "cmp -s '$tmp/keep.pfm' '$tmp/keep.orig'" "write_atomic: the failed write damaged the existing image"
ino1=$(ls -i "$tmp/keep.pfm" | awk '{print $1}')
"$fogrt" --quiet -s 1 -r 32 24 --seed 9 -f "$tmp/keep.pfm" "$lit"
ino2=$(ls -i "$tmp/keep.pfm" | awk '{print $1}')
check "[ '$ino1' != '$ino2' ] && ! cmp -s '$tmp/keep.pfm' '$tmp/keep.orig'" "write_atomic: the image was not replaced by a new file"
check "[ -z \"\$(ls -A '$tmp' | grep '\\.tmp-')\" ]" "write_atomic: a temporary file was left behind"
if [ "$(id -u)" -ne 0 ]; then
    mkdir "$tmp/ro" && chmod 555 "$tmp/ro"
    expect 1 "ro/x.png" "write_no_permission" -- -s 1 -r 8 6 -f "$tmp/ro/x.png"
else
    echo "test_cli.sh: write_no_permission skipped (running as root, which may write anywhere)"
fi

# -- free_camera: --camera-pos/--look-at/--up/--fov override the scene's camera --
expect 0 "" "free_camera: print" -- --print-camera --camera-pos 0,1,3 --look-at 0,0.5,0 --up 0,1,0 --fov 60 -r 64 48 -b 0
check "grep -q 'position 0,1,3  look_at 0,0.5,0  up 0,1,0  fov 60.0000 x ' '$tmp/out'" "free_camera: --print-camera does not show the free camera: $(cat "$tmp/out")"
"$fogrt" --print-camera -r 32 24 >"$tmp/cam0" 2>/dev/null
pos=$(sed 's/.*position \([^ ]*\) .*/\1/' "$tmp/cam0")
look=$(sed 's/.*look_at \([^ ]*\) .*/\1/' "$tmp/cam0")
"$fogrt" --quiet -s 2 -r 32 24 -f "$tmp/cam_a.pfm"
"$fogrt" --quiet -s 2 -r 32 24 --camera-pos "$pos" --look-at "$look" -f "$tmp/cam_b.pfm"
"$fogrt" --quiet -s 2 -r 32 24 --camera-pos 0.5,0.7,0.9 --look-at 0,1.4,0 --fov 90 -f "$tmp/cam_c.pfm"
check "cmp -s '$tmp/cam_a.pfm' '$tmp/cam_b.pfm'" "free_camera: the scene's own camera given as flags ($pos, $look) renders differently"
check "! cmp -s '$tmp/cam_a.pfm' '$tmp/cam_c.pfm'" "free_camera: a camera inside the fog renders the same image"
expect 2 "--fov" "free_camera: fov 180" -- --fov 180 -f "$out"; one_line_no_image "fov 180"
expect 2 "--up" "free_camera: zero up" -- --up 0,0,0 -f "$out"
expect 2 "--camera-pos" "free_camera: two numbers" -- --camera-pos 1,2 -f "$out"
expect 2 "parallel" "free_camera: up along the view" -- --camera-pos 0,3,0 --look-at 0,0,0 --up 0,1,0 -f "$out"; one_line_no_image "up parallel"
expect 2 "-b" "camera_overflow: -b 3e38" -- -b 3e38 -f "$out"; one_line_no_image "-b 3e38"
check "grep -q 'lens radius' '$tmp/err'" "camera_overflow: -b 3e38 does not name the lens radius"
expect 2 "overflows float" "camera_overflow: eye 3e38, target -3e38" -- --camera-pos 3e38,0,0 --look-at -3e38,0,0 -f "$out"; one_line_no_image "eye-target overflow"

# -- exposure_jpg: --exposure scales PNG/JPG, never PFM; .jpg is a JPEG --
"$fogrt" --quiet -s 2 -r 32 24 -f "$tmp/e0.pfm"; "$fogrt" --quiet -s 2 -r 32 24 --exposure 2 -f "$tmp/e2.pfm"
"$fogrt" --quiet -s 2 -r 32 24 -f "$tmp/e0.ppm"; "$fogrt" --quiet -s 2 -r 32 24 --exposure 2 -f "$tmp/e2.ppm"
check "cmp -s '$tmp/e0.pfm' '$tmp/e2.pfm'" "exposure_jpg: --exposure changed the PFM"
check "! cmp -s '$tmp/e0.ppm' '$tmp/e2.ppm'" "exposure_jpg: --exposure did not change the 8-bit image"
expect 0 "" "exposure_jpg: JPG output" -- --quiet -s 1 -r 32 24 --exposure -1 -f "$tmp/e.jpg"
check "[ \"\$(head -c 3 '$tmp/e.jpg' | od -An -tx1 | tr -d ' ')\" = 'ffd8ff' ]" "exposure_jpg: e.jpg is not a JPEG"
expect 2 "--exposure" "exposure_jpg: 70 stops" -- --exposure 70 -f "$out"

# -- cs184_framing: CS184 keeps its 875-pixel focal length; fogrt's framing stays the default --
"$fogrt" --print-camera -r 800 600 >"$tmp/f800" 2>&1
"$fogrt" --print-camera -r 800 600 --cs184-framing >"$tmp/f800c" 2>&1
check "[ \"\$(sed 's/.*fov //' '$tmp/f800')\" = \"\$(sed 's/.*fov //' '$tmp/f800c')\" ]" "cs184_framing: 800x600 differs from fogrt's framing"
"$fogrt" --print-camera -r 400 300 >"$tmp/f400" 2>&1
"$fogrt" --print-camera -r 400 300 --cs184-framing >"$tmp/f400c" 2>&1
v800=$(sed 's/.* x \([0-9.]*\) deg.*/\1/' "$tmp/f800")
v400=$(sed 's/.* x \([0-9.]*\) deg.*/\1/' "$tmp/f400c")
v400f=$(sed 's/.* x \([0-9.]*\) deg.*/\1/' "$tmp/f400")
check "awk 'BEGIN { pi = atan2(0, -1); t = sin($v800 * pi / 360) / cos($v800 * pi / 360) / 2; v = 2 * atan2(t, 1) * 180 / pi; exit !(v - $v400 < 1e-3 && $v400 - v < 1e-3) }'" \
    "cs184_framing: 400x300 vertical fov $v400, expected half the 800x600 tangent of $v800"
check "[ '$v400f' = '$v800' ]" "cs184_framing: fogrt's own framing changed with the size ($v400f vs $v800)"
if [ -f ../shared/scenes/cs184/CBspheres.dae ]; then
    "$fogrt" --print-camera -r 480 360 --cs184-framing ../shared/scenes/cs184/CBspheres.dae >"$tmp/fcb" 2>&1
    check "grep -q 'fov 30.67[0-9]* x 23.2[45][0-9]* deg' '$tmp/fcb'" "cs184_framing: CBspheres at 480x360 is not CS184's 30.67 x 23.25 deg: $(cat "$tmp/fcb")"
else
    echo "test_cli.sh: cs184_framing on CBspheres.dae skipped (../shared/scenes/cs184 absent)"
fi
expect 2 "--cs184-framing" "cs184_framing: with --fov" -- --cs184-framing --fov 40 -f "$out"

# -- depth_m0_o0: -m 0 is emission only; -o 0 keeps only light that bounced exactly -m times --
"$fogrt" --quiet -s 4 -r 32 24 --seed 5 -m 0 -f "$tmp/m0.pfm"
"$fogrt" --quiet -s 4 -r 32 24 --seed 5 -m 1 -o 0 -f "$tmp/m1o0.pfm"
"$fogrt" --quiet -s 4 -r 32 24 --seed 5 -m 1 -f "$tmp/m1.pfm"
s0=$(pfm_stats "$tmp/m0.pfm"); s10=$(pfm_stats "$tmp/m1o0.pfm"); s1=$(pfm_stats "$tmp/m1.pfm")
check "echo '$s0 $s1' | awk '{ exit !(\$3 > 0 && \$3 < \$10 / 4) }'" "depth_m0_o0: -m 0 is not emission only (lit pixels: $s0 vs $s1)"
check "echo '$s0 $s10 $s1' | awk '{ for (c = 4; c <= 6; c++) { d = \$c + \$(c + 7) - \$(c + 14); if (d < 0) d = -d; if (d > 1e-3 * \$(c + 14) + 1e-6) exit 1 } }'" \
    "depth_m0_o0: (-m 0) + (-m 1 -o 0) != (-m 1): $s0 | $s10 | $s1"

# -- adaptive_rate: -a writes CS184's sampling-rate image <name>_rate.png --
expect 0 "_rate.png" "adaptive_rate: -a to PFM" -- -s 16 -a 4 0.2 -r 24 18 -f "$tmp/ad.pfm" "$lit"
check "[ \"\$(head -c 4 '$tmp/ad_rate.png' | od -An -c | tr -d ' ')\" = '211PNG' ]" "adaptive_rate: ad_rate.png is not a PNG"
check "[ \"\$(head -c 24 '$tmp/ad_rate.png' | tail -c 8 | od -An -tu1 | tr -s ' ')\" = ' 0 0 0 24 0 0 0 18' ]" "adaptive_rate: ad_rate.png is not 24x18"

# -- no_f_preview_note: without -f, one line says how to start the preview, and out.png is written --
mkdir "$tmp/nof"
( cd "$tmp/nof" && "$fogrt_abs" -s 1 -r 8 6 ) 2>"$tmp/nof.err"
check "grep -q 'make preview' '$tmp/nof.err' && grep -q 'build/preview' '$tmp/nof.err' && [ -s '$tmp/nof/out.png' ]" "no_f_preview_note: no preview note or no out.png"

# -- progress_log_lines: no \r without a terminal, a progress line every 5 s, the estimate
#    updated every batch (at most 3 s apart), spp as done/target; --log columns --
"$fogrt" --time 6 -r 96 72 --log "$tmp/p.csv" -f "$tmp/p.pfm" 2>"$tmp/p.err"
check "! grep -q \"\$(printf '\\r')\" '$tmp/p.err'" "progress_log_lines: a carriage return in a non-terminal log"
check "grep -Eq '^fogrt: .*spp [0-9]+ .*rel. error [0-9.]+%' '$tmp/p.err'" "progress_log_lines: no 5-second progress line with an integer spp: $(head -2 "$tmp/p.err")"
check "[ \"\$(head -n 1 '$tmp/p.csv')\" = 'seconds,spp,samples_per_second,est_rel_mse,est_rel_error,ref_rel_mse,ref_rmse,ref_ratio_r,ref_ratio_g,ref_ratio_b,event' ]" "progress_log_lines: bad --log header"
check "awk -F, 'NR > 1 { if (NR > 2 && \$1 - t > 3.0) exit 1; t = \$1; n++ } END { exit !(n >= 4 && t > 5) }' '$tmp/p.csv'" "progress_log_lines: --log rows more than 3 s apart or too few: $(wc -l <"$tmp/p.csv") lines"
check "! grep -qi 'nan' '$tmp/p.csv' && awk -F, 'NR == 2 && \$2 < 2 && \$4 != \"\" { exit 1 }' '$tmp/p.csv'" "log_no_nan: a --log row holds nan, or an estimate below 2 spp: $(sed -n 2p "$tmp/p.csv")"

# -- same_seed_same_image: with a seed and no time limit, the image and every --log column but
#    the times (seconds, samples_per_second) are functions of the inputs alone: the default
#    (pixel rates on) on 1 thread, on 2, and on 2 again; the comparison sees a different seed --
log_cols() { cut -d, -f2,4- "$1"; }
"$fogrt" -s 64 -r 64 48 -t 1 --seed 7 --log "$tmp/det1.csv" -f "$tmp/det1.pfm" 2>/dev/null
"$fogrt" -s 64 -r 64 48 -t 2 --seed 7 --log "$tmp/det2.csv" -f "$tmp/det2.pfm" 2>/dev/null
"$fogrt" -s 64 -r 64 48 -t 2 --seed 7 --log "$tmp/det3.csv" -f "$tmp/det3.pfm" 2>/dev/null
"$fogrt" -s 64 -r 64 48 -t 2 --seed 8 --log "$tmp/det4.csv" -f "$tmp/det4.pfm" 2>/dev/null
check "cmp -s '$tmp/det1.pfm' '$tmp/det2.pfm'" "same_seed_same_image: 1 and 2 threads give different images"
check "cmp -s '$tmp/det2.pfm' '$tmp/det3.pfm'" "same_seed_same_image: two runs on 2 threads give different images"
check "[ \"\$(log_cols '$tmp/det1.csv')\" = \"\$(log_cols '$tmp/det2.csv')\" ]" "same_seed_same_image: --log rows differ between 1 and 2 threads: $(log_cols "$tmp/det1.csv" | tr '\n' ' ') / $(log_cols "$tmp/det2.csv" | tr '\n' ' ')"
check "[ \"\$(log_cols '$tmp/det2.csv')\" = \"\$(log_cols '$tmp/det3.csv')\" ]" "same_seed_same_image: --log rows differ between two runs: $(log_cols "$tmp/det2.csv" | tr '\n' ' ') / $(log_cols "$tmp/det3.csv" | tr '\n' ' ')"
check "[ \$(wc -l <'$tmp/det1.csv') -ge 6 ]" "same_seed_same_image: too few --log rows to compare: $(wc -l <"$tmp/det1.csv")"
check "! cmp -s '$tmp/det3.pfm' '$tmp/det4.pfm' && [ \"\$(log_cols '$tmp/det3.csv')\" != \"\$(log_cols '$tmp/det4.csv')\" ]" "same_seed_same_image: --seed 8 gives the same image or log as --seed 7 (the comparison sees nothing)"
# a run whose batches are capped by the samples per batch (1 spp at 160x120 with -l 4)
"$fogrt" -s 3 -r 160 120 -l 4 -t 1 --seed 3 --log "$tmp/det5.csv" -f "$tmp/det5.pfm" 2>/dev/null
"$fogrt" -s 3 -r 160 120 -l 4 -t 2 --seed 3 --log "$tmp/det6.csv" -f "$tmp/det6.pfm" 2>/dev/null
check "cmp -s '$tmp/det5.pfm' '$tmp/det6.pfm' && [ \"\$(log_cols '$tmp/det5.csv')\" = \"\$(log_cols '$tmp/det6.csv')\" ]" "same_seed_same_image: -r 160 120 -l 4 differs between 1 and 2 threads: $(log_cols "$tmp/det5.csv" | tr '\n' ' ') / $(log_cols "$tmp/det6.csv" | tr '\n' ' ')"
if command -v script >/dev/null 2>&1; then
    # --time: long enough for the terminal's 0.25 s progress tick on any machine (-s 64 took 0.22 s on a fast one)
    script -qec "$fogrt_abs --time 1.5 -r 64 48 -f $tmp/tty.pfm" /dev/null >"$tmp/tty.out" 2>&1
    check "grep -q \"\$(printf '\\r')fogrt:\" '$tmp/tty.out'" "progress_log_lines: no \\r progress line on a terminal"
fi

# -- black_na: a scene nothing can light warns once and reports the error as n/a --
expect 0 "no light" "black_na: a scene without lights" -- -s 2 -r 16 12 -f "$tmp/blk.pfm" tests/data/dae_minimal_yup.dae
check "[ \"\$(grep -c warning '$tmp/err')\" -eq 1 ] && grep -q 'rel. error n/a' '$tmp/err' && ! grep -q '0.00%' '$tmp/err'" "black_na: not one warning and n/a: $(cat "$tmp/err")"
expect 0 "every pixel is black" "black_na: lit, but the camera sees nothing lit" -- -s 2 -r 16 12 -f "$tmp/blk2.pfm" tests/data/dae_area_light.dae
check "grep -q 'rel. error n/a' '$tmp/err'" "black_na: an all-black image reports a number"

# -- log_reference: --log rows with the measured error; bad references refused (exit 2) --
"$fogrt" --quiet -s 64 -r 24 18 --seed 1 -f "$tmp/ref.pfm" "$lit"
expect 0 "measured" "log_reference: --reference" -- -s 8 -r 24 18 --seed 2 --reference "$tmp/ref.pfm" --log "$tmp/r.csv" -f "$tmp/r.pfm" "$lit"
check "awk -F, 'NR > 1 && \$6 != \"\" && \$8 > 0.7 && \$8 < 1.4 { ok++ } END { exit !(ok >= 2) }' '$tmp/r.csv'" "log_reference: no measured rel. MSE or mean ratio in the --log rows"
check "awk -F, 'NR > 1 { last = \$6 } END { exit !(last > 0 && last < 1) }' '$tmp/r.csv'" "log_reference: implausible measured rel. MSE"
expect 2 "is 24x18, the render is 32x24" "log_reference: another size" -- -s 1 -r 32 24 --reference "$tmp/ref.pfm" -f "$out"; one_line_no_image "reference size"
printf 'PF\n24 18\n-1.0\nshort' >"$tmp/bad_ref.pfm"
expect 2 "bad_ref.pfm" "log_reference: a truncated PFM" -- -s 1 -r 24 18 --reference "$tmp/bad_ref.pfm" -f "$out"; one_line_no_image "truncated reference"
printf 'P6\n24 18\n255\n' >"$tmp/ppm_ref.pfm"
expect 2 "not an RGB PFM" "log_reference: not a PFM" -- -s 1 -r 24 18 --reference "$tmp/ppm_ref.pfm" -f "$out"
mkfifo "$tmp/ref_fifo.pfm"
expect 2 "a FIFO" "log_reference: a FIFO" -- -s 1 -r 24 18 --reference "$tmp/ref_fifo.pfm" -f "$out"

# -- estimator_switches: --equiangular and --mis change the estimator, not the meaning --
"$fogrt" --quiet -s 2 -r 32 24 --seed 4 -f "$tmp/eq1.pfm"
"$fogrt" --quiet -s 2 -r 32 24 --seed 4 --equiangular off -f "$tmp/eq0.pfm"
"$fogrt" --quiet -s 2 -r 32 24 --seed 4 --mis off -f "$tmp/mis0.pfm"
check "! cmp -s '$tmp/eq1.pfm' '$tmp/eq0.pfm'" "estimator_switches: --equiangular off changed nothing on the spot light in fog"
check "! cmp -s '$tmp/eq1.pfm' '$tmp/mis0.pfm'" "estimator_switches: --mis off changed nothing"
expect 2 "--equiangular" "estimator_switches: bad value" -- --equiangular yes -f "$out"
expect 2 "--mis" "estimator_switches: bad value" -- --mis 1 -f "$out"
"$fogrt" --quiet -s 2 -r 32 24 --seed 4 --glow off -f "$tmp/glow0.pfm"
check "! cmp -s '$tmp/eq1.pfm' '$tmp/glow0.pfm'" "estimator_switches: --glow off changed nothing on the spot light in fog"
expect 2 "--glow" "estimator_switches: bad value" -- --glow maybe -f "$out"
"$fogrt" --quiet -s 2 -r 32 24 --seed 4 --footprint off -f "$tmp/fp0.pfm"
check "! cmp -s '$tmp/eq1.pfm' '$tmp/fp0.pfm'" "estimator_switches: --footprint off changed nothing on the spot light over the floor"
expect 2 "--footprint" "estimator_switches: bad value" -- --footprint maybe -f "$out"
"$fogrt" --quiet -s 2 -r 32 24 --seed 4 --expected-emission off -f "$tmp/expect0.pfm"
check "! cmp -s '$tmp/eq1.pfm' '$tmp/expect0.pfm'" "estimator_switches: --expected-emission off changed nothing on the area lamp seen through fog"
expect 2 "--expected-emission" "estimator_switches: bad value" -- --expected-emission sometimes -f "$out"
"$fogrt" --quiet -s 2 -r 32 24 --seed 4 --lights power -f "$tmp/power.pfm"
check "! cmp -s '$tmp/eq1.pfm' '$tmp/power.pfm'" "estimator_switches: --lights power changed nothing in the default scene (two lights)"
expect 2 "--lights" "estimator_switches: bad value" -- --lights some -f "$out"

# -- target_error_ceiling: --target-error that can never be met stops at the stated ceiling;
#    one below float's precision is refused at once (it ran to the hour's ceiling), and a
#    black scene, whose estimate never exists, stops after its first batch --
expect 0 "not reached" "target_error_ceiling: --target-error 1e-6 without -s" -- -r 2 2 --target-error 1e-6 -f "$tmp/te.pfm"
check "grep -q '65536 spp' '$tmp/err'" "target_error_ceiling: the ceiling is not stated: $(cat "$tmp/err")"
t_te=$(now)
expect 2 "--target-error" "target_error_floor: --target-error 1e-30" -- --target-error 1e-30 -f "$out"; one_line_no_image "target_error_floor"
expect 2 "--target-error" "target_error_floor: --target-error 1e-7 (below FLT_EPSILON)" -- -r 32 24 --target-error 1e-7 -f "$out"
check "awk -v a=$t_te -v b=$(now) 'BEGIN { exit !(b - a < 5) }'" "target_error_floor: the refusals took more than 5 s"
expect 0 "cannot be reached" "target_error_black: --target-error on a scene nothing lights" -- -r 320 240 --target-error 0.1 -f "$tmp/teb.pfm" tests/data/dae_minimal_yup.dae
check "grep -q 'stopped at 1 spp' '$tmp/err'" "target_error_black: did not stop after the first batch: $(cat "$tmp/err")"
sed 's|<radiance>3 3 3</radiance>|<radiance>1e20 1e20 1e20</radiance>|' tests/data/dae_area_with_emitter.dae >"$tmp/hot.dae"
expect 0 "not reached" "target_error_ceiling: emission 1e20, --target-error 1e-6" -- -r 4 3 --target-error 1e-6 -f "$tmp/hot.pfm" "$tmp/hot.dae"
sed 's|<radiance>3 3 3</radiance>|<radiance>3e38 3e38 3e38</radiance>|' tests/data/dae_area_with_emitter.dae >"$tmp/hot38.dae"
expect 0 "" "target_error_ceiling: emission 3e38" -- -s 4 -r 16 12 -f "$tmp/hot38.pfm" "$tmp/hot38.dae"
check "! grep -Eqi 'nan|inf' '$tmp/err' && ! pfm_stats '$tmp/hot38.pfm' | grep -Eqi 'nan|inf'" "target_error_ceiling: emission 3e38 gives a non-finite image or summary: $(cat "$tmp/err")"
check "grep -q '65536 spp' '$tmp/out' 2>/dev/null || \"$fogrt\" -h | grep -q '65536 spp'" "target_error_ceiling: -h does not state the ceiling"

# -- fifo_inputs: FIFOs are refused at once (stat before open), never block --
mkfifo "$tmp/f.dae"
t_a=$(now)
expect 2 "a FIFO" "fifo_inputs: a FIFO as the scene" -- -f "$out" "$tmp/f.dae"; one_line_no_image "fifo scene"
check "awk 'BEGIN { exit !($(now) - $t_a < 2) }'" "fifo_inputs: the FIFO refusal took over 2 s"
mkfifo "$tmp/fifo_out.png"
expect 1 "a FIFO" "fifo_inputs: a FIFO as -f" -- -s 1 -r 8 6 -f "$tmp/fifo_out.png"

# -- limits: -t 600 is capped with a note; -r 11585 11585 refused before allocating --
expect 0 "using" "limits: -t 600" -- -t 600 -s 1 -r 8 6 -f "$tmp/t600.pfm"
check "grep -q 'at most 4 per processor' '$tmp/err'" "limits: -t 600 does not say why it was capped"
# (AddressSanitizer reserves terabytes of address space, so under a ulimit -v it cannot even
# start: a sanitizer build runs the same refusal without the limit)
if nm "$fogrt" 2>/dev/null | grep -q __asan_init; then
    "$fogrt" -r 11585 11585 -f "$tmp/huge.png" 2>"$tmp/huge.err"
else
    ( ulimit -v 300000; "$fogrt" -r 11585 11585 -f "$tmp/huge.png" ) 2>"$tmp/huge.err"
fi
st=$?
check "[ $st -eq 2 ] && [ \"\$(wc -l <'$tmp/huge.err')\" -eq 1 ] && grep -q 'above the limit of 2.0 GiB' '$tmp/huge.err'" "limits: -r 11585 11585 under a 300 MB ulimit: exit $st, $(cat "$tmp/huge.err")"
check "[ ! -e '$tmp/huge.png' ]" "limits: -r 11585 11585 wrote an image"

# -- readme_examples: the README's fogrt examples name files that exist from a clean clone --
if [ -d ../shared/scenes ]; then
    for f in $(sed -n '/^## The `fogrt` command/,/^## /p' README.md | grep -o '\.\./shared/[^ ]*\.\(dae\|ply\|obj\)' | sort -u); do
        check "[ -f '$f' ]" "readme_examples: README names $f, which does not exist"
    done
else
    echo "test_cli.sh: readme_examples skipped (../shared/scenes absent)"
fi
# ==== end of the fogrt command in real use ====

# ==== loader refusals (fogrt_load.h): exit 2, exactly one stderr line naming the file ====
# refused NAME WORD DESCRIPTION -- ARGS...: like expect 2, and stderr is one line naming NAME
refused() {
    name=$1 word=$2 what=$3
    shift 4
    expect 2 "$word" "$what" -- "$@" || return 1
    check "[ \"\$(wc -l <'$tmp/err')\" -eq 1 ] && grep -qF -- '$name' '$tmp/err'" "$what: not one line naming $name"
}
mkfifo "$tmp/pipe.obj" "$tmp/pipe.cam"
# a FIFO blocks in open without O_NONBLOCK: run under a watchdog so a regression fails, not hangs
( sleep 10; kill $$ 2>/dev/null ) & watchdog=$!
refused "pipe.obj" "a FIFO, not a regular file" "a FIFO as the scene" -- -f "$out" "$tmp/pipe.obj"
refused "pipe.cam" "a FIFO, not a regular file" "a FIFO as -c" -- -f "$out" -c "$tmp/pipe.cam"
kill "$watchdog" 2>/dev/null
ln -s /dev/zero "$tmp/zero.ply"
refused "zero.ply" "character device" "/dev/zero as the scene" -- -f "$out" "$tmp/zero.ply"
dd if=/dev/null of="$tmp/sparse.obj" bs=1 seek=1610612736 2>/dev/null
refused "sparse.obj" "1610612736 bytes, more than the limit of 1073741824 bytes (1 GiB" "a 1.5 GiB sparse file" -- -f "$out" "$tmp/sparse.obj"
rm -f "$tmp/sparse.obj"
refused "ply_huge_count.ply:11:" "file too short" "a PLY declaring 4e9 vertices in 130 bytes" -- -f "$out" tests/data/ply_huge_count.ply
refused "bad_far_vertex.dae:11:" "beyond fogrt's limit of 1e30" "a vertex beyond 1e30" -- -f "$out" tests/data/bad_far_vertex.dae
refused "bad_far_node.dae:25:" "beyond fogrt's limit of 1e30" "a node moving vertices beyond 1e30" -- -f "$out" tests/data/bad_far_node.dae
refused "obj_random.obj:1:" "not an OBJ mesh" "random bytes named .obj" -- -f "$out" tests/data/obj_random.obj
printf '49 37 1.3 0.1 100\n3e38 0 0 -3e38 0 0\n1 0 4 2 20\n1 0 0 0 1 0 0 0 1\n800 600 875\n' >"$tmp/far.cam"
refused "far.cam:2:" "overflows a float" "a -c file whose eye-target distance overflows" -- -f "$out" -c "$tmp/far.cam"
printf '49 37 1.3 0.1 100\n0 0 1 0 0 0\n1 0 4 2 20\n1 0 0 0 1 0 0 0 1\n800 1e9 1\n' >"$tmp/wide.cam"
refused "wide.cam:5:" "less than 180" "a -c file with a 180-degree field of view" -- -f "$out" -c "$tmp/wide.cam"
expect 0 "" "a PLY with 1e300 in a skipped property" -- --quiet -s 1 -r 16 12 -f "$tmp/skip.ppm" tests/data/ply_skipped_huge.ply
expect 0 "" "an OBJ with a byte-order mark and CR line endings" -- --quiet -s 1 -r 16 12 -f "$tmp/cr.ppm" tests/data/obj_cr.obj
# FOGRT_NO_GLASS: a glass material is refused in one line naming the file and the material
if ${CC:-cc} -std=c99 -O0 -DFOGRT_NO_GLASS -I. -o "$tmp/fogrt_noglass" examples/fogrt_cli.c examples/fogrt_cli_trace.c -lm 2>"$tmp/cc.err"; then
    fogrt_full=$fogrt fogrt=$tmp/fogrt_noglass
    refused "dae_materials.dae:" "material 'm0' is glass/refraction" "glass without glass support" -- -f "$out" tests/data/dae_materials.dae
    fogrt=$fogrt_full
else
    echo "test_cli.sh: FOGRT_NO_GLASS build of the CLI failed, glass check skipped: $(head -1 "$tmp/cc.err")"
fi
# ==== end of the loader refusals ====

# ==== fog bounds, environment maps, the path trace ====
# --fog-bounds: refused unless six numbers with min < max; a box of fog around the default
# scene's middle renders, and is darker than no fog where it stands
expect 2 "--fog-bounds" "fog bounds with min > max" -- --fog-bounds 1,0,0,0,1,1 -f "$out"; one_line_no_image "fog bounds with min > max"
expect 2 "--fog-bounds" "fog bounds with five numbers" -- --fog-bounds 0,0,0,1,1 -f "$out"
expect 0 "" "a bounded fog box" -- --quiet -s 2 -r 24 18 --density 2 --fog-bounds -0.5,0,-0.5,0.5,1,0.5 -f "$tmp/box.pfm"
check "pfm_ok '$tmp/box.pfm' 24 18" "the bounded-fog render is not a 24x18 PFM"
# -e: an environment map (PFM here: one fogrt writes itself), read and used as the light of
# an empty .dae scene; missing, unknown and malformed maps are refused in one line
expect 0 "" "a PFM to use as an environment map" -- --quiet -s 1 -r 16 8 -f "$tmp/env.pfm"
expect 0 "" "a .dae lit by the environment map" -- --quiet -s 2 -r 24 18 -e "$tmp/env.pfm" -f "$tmp/lit.pfm" tests/data/dae_minimal_yup.dae
check "[ \"\$(pfm_stats '$tmp/lit.pfm' | awk '{print (\$3 > 0) ? 1 : 0}')\" = 1 ]" "the environment map lit nothing"
expect 2 "-e" "a missing environment map" -- -e "$tmp/none.pfm" -f "$out";      one_line_no_image "a missing environment map"
printf 'hello' >"$tmp/env.txt"
expect 2 "unknown environment map type" "an environment map of unknown type" -- -e "$tmp/env.txt" -f "$out"
printf 'PF\n4 4\n-1.0\n' >"$tmp/short.pfm"
expect 2 "short.pfm" "a truncated environment map" -- -e "$tmp/short.pfm" -f "$out"; one_line_no_image "a truncated environment map"
# a Radiance .hdr map (written here with python3 when it is installed: flat RGBE scanlines)
if command -v python3 >/dev/null 2>&1; then
    python3 -c '
import sys
w, h = 16, 8
out = open(sys.argv[1], "wb")
out.write(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (h, w))
for j in range(h):
    for i in range(w):
        out.write(bytes([128, 160, 200, 129]) if j < h // 2 else bytes([64, 48, 32, 128]))
' "$tmp/sky.hdr"
    expect 0 "" "a .dae lit by a .hdr environment map" -- --quiet -s 2 -r 24 18 -e "$tmp/sky.hdr" -f "$tmp/lit_hdr.pfm" tests/data/dae_minimal_yup.dae
    check "[ \"\$(pfm_stats '$tmp/lit_hdr.pfm' | awk '{print (\$3 > 0) ? 1 : 0}')\" = 1 ]" "the .hdr environment map lit nothing"
else
    echo "test_cli.sh: .hdr environment map skipped (no python3 to write one)"
fi
# --trace: the events of one pixel sample in Algorithm 1's order, ending with its radiance
expect 0 "" "--trace of one pixel sample" -- --trace 12,9,1 -r 24 18 --seed 3
cp "$tmp/out" "$tmp/trace.txt"
check "grep -q 'free flight (eq. 6)' '$tmp/trace.txt' && grep -q '^= sample radiance' '$tmp/trace.txt' && grep -q '^camera ray' '$tmp/trace.txt'" \
    "--trace does not print the camera ray, the free flight and the sample radiance"
check "[ ! -e out.png ] || [ out.png -ot '$tmp/trace.txt' ]" "--trace wrote an image"
expect 2 "--trace" "--trace outside the image" -- --trace 30,2 -r 24 18 -f "$out"; one_line_no_image "--trace outside the image"
if [ -f ../shared/scenes/cs184/bunny.dae ]; then
    # the shared bunny.dae is lit by CS184's <ambient> sky: with fog and no bounds the fog
    # fills the box of the geometry (said in one line), and the bunny shows in haze
    expect 0 "fills the box of the geometry" "bunny.dae --density 0.3" -- -s 2 -r 32 24 --density 0.3 -f "$tmp/haze.pfm" ../shared/scenes/cs184/bunny.dae
    check "[ \"\$(pfm_stats '$tmp/haze.pfm' | awk '{print (\$3 > 0) ? 1 : 0}')\" = 1 ]" "bunny.dae in haze is black"
else
    echo "test_cli.sh: bunny.dae in haze skipped (../shared/scenes/cs184 absent)"
fi
# ==== end of fog bounds, environment maps, the path trace ====

# ==== hostile runs: aliasing, closed streams, threads, values,
#      environment maps, stopping ====
# -- alias_*: no output may be (or resolve to) an input or another output: exit 2 naming
#    both, before rendering, every file as it was --
mkdir "$tmp/al"
cp tests/data/obj_polygons.obj "$tmp/al/scene.obj"
cp tests/data/cam_settings.txt "$tmp/al/cam.txt"
"$fogrt" --quiet -s 1 -r 16 12 -f "$tmp/al/ref.pfm"
"$fogrt" --quiet -s 1 -r 16 8 -f "$tmp/al/env.pfm"
for f in scene.obj cam.txt ref.pfm env.pfm; do cp "$tmp/al/$f" "$tmp/al/$f.orig"; done
# unchanged F...: every named file is byte for byte its copy from before the run
unchanged() { for f in "$@"; do cmp -s "$tmp/al/$f" "$tmp/al/$f.orig" || return 1; done; }
expect 2 "--reference" "alias_reference: -f REF --reference REF" -- -s 1 -r 16 12 -f "$tmp/al/ref.pfm" --reference "$tmp/al/ref.pfm"
check "grep -q -- '-f .*ref.pfm' '$tmp/err' && [ \$(wc -l <'$tmp/err') -eq 1 ] && unchanged ref.pfm" "alias_reference: not one line naming both, or the reference changed"
expect 2 "-e" "alias_env: -e ENV -f ENV" -- -s 1 -r 16 12 -e "$tmp/al/env.pfm" -f "$tmp/al/env.pfm"
check "unchanged env.pfm" "alias_env: the environment map changed"
ln -s cam.txt "$tmp/al/camlink.png"
expect 2 "-c" "alias_camera_symlink: -f a symlink to the -c file" -- -s 1 -r 16 12 -c "$tmp/al/cam.txt" -f "$tmp/al/camlink.png"
check "unchanged cam.txt" "alias_camera_symlink: the camera file changed"
ln -s scene.obj "$tmp/al/out_link.ppm"
expect 2 "scene.obj" "alias_scene_symlink: -f a symlink to the scene" -- -s 1 -r 16 12 -f "$tmp/al/out_link.ppm" "$tmp/al/scene.obj"
ln "$tmp/al/scene.obj" "$tmp/al/hard.pfm"
expect 2 "scene.obj" "alias_scene_hardlink: -f a hard link to the scene" -- -s 1 -r 16 12 -f "$tmp/al/hard.pfm" "$tmp/al/scene.obj"
check "unchanged scene.obj" "alias_scene: the scene file changed"
cp "$tmp/al/cam.txt" "$tmp/al/ad_rate.png"; cp "$tmp/al/cam.txt" "$tmp/al/ad_rate.png.orig"
expect 2 "rate image" "alias_rate_image: -a's rate image is the -c file" -- -s 4 -a 2 0.5 -r 16 12 -c "$tmp/al/ad_rate.png" -f "$tmp/al/ad.pfm"
check "unchanged ad_rate.png && [ ! -e '$tmp/al/ad.pfm' ]" "alias_rate_image: the camera file changed or an image was written"
expect 2 "--log" "alias_log_scene: --log the scene" -- -s 1 -r 16 12 --log "$tmp/al/scene.obj" -f "$tmp/al/x.pfm" "$tmp/al/scene.obj"
check "unchanged scene.obj" "alias_log_scene: the scene file changed"
expect 2 "two outputs" "alias_log_output: --log OUT -f OUT" -- -s 1 -r 16 12 --log "$tmp/al/o.pfm" -f "$tmp/al/o.pfm"
check "[ ! -e '$tmp/al/o.pfm' ]" "alias_log_output: a file was written"
ln -s new.pfm "$tmp/al/dangling.csv"
expect 2 "two outputs" "alias_dangling_link: --log a dangling link to the -f file" -- -s 1 -r 16 12 --log "$tmp/al/dangling.csv" -f "$tmp/al/new.pfm"
# --log appends only to a fogrt log, which is created at the start
printf 'my notes\n' >"$tmp/al/notes.csv"; cp "$tmp/al/notes.csv" "$tmp/al/notes.csv.orig"
expect 2 "not a fogrt log" "log_not_a_log: --log a file that is not a fogrt log" -- -s 1 -r 16 12 --log "$tmp/al/notes.csv" -f "$tmp/al/n.pfm"
check "unchanged notes.csv" "log_not_a_log: the file was changed"
expect 2 "bad_index.dae" "log_created_at_start: a new --log, then a scene that fails to load" -- -s 1 -r 16 12 --log "$tmp/al/start.csv" -f "$tmp/al/s.pfm" tests/data/bad_index.dae
check "[ \"\$(cat '$tmp/al/start.csv')\" = 'seconds,spp,samples_per_second,est_rel_mse,est_rel_error,ref_rel_mse,ref_rmse,ref_ratio_r,ref_ratio_g,ref_ratio_b,event' ]" "log_created_at_start: the log was not created with its header at the start"
"$fogrt" --quiet -s 2 -r 16 12 --log "$tmp/al/start.csv" -f "$tmp/al/s.pfm"
"$fogrt" --quiet -s 2 -r 16 12 --log "$tmp/al/start.csv" -f "$tmp/al/s.pfm"
check "[ \$(grep -c '^seconds,' '$tmp/al/start.csv') -eq 1 ] && [ \$(grep -c ',final$\\|,batch$' '$tmp/al/start.csv') -ge 2 ]" "log_append: a fogrt log was not appended to (one header, rows of two runs)"

# -- closed_streams: with 0-2 closed the image is still the image and the summary never in
#    the log; a reader of stderr that goes away (SIGPIPE) does not kill the run --
"$fogrt" -s 2 -r 16 12 -f "$tmp/cs.pfm" --log "$tmp/cs.csv" 2>&-
st=$?
check "[ $st -eq 0 ] && pfm_ok '$tmp/cs.pfm' 16 12" "closed_stderr: exit $st or no 16x12 PFM"
check "! grep -q 'fogrt' '$tmp/cs.csv' && ! grep -q 'fogrt' '$tmp/cs.pfm'" "closed_stderr: messages landed in the log or the image"
"$fogrt" -s 2 -r 16 12 -f "$tmp/cs3.pfm" <&- >&- 2>&-
st=$?
check "[ $st -eq 0 ] && pfm_ok '$tmp/cs3.pfm' 16 12" "closed_all_three: exit $st or no 16x12 PFM"
( "$fogrt" -s 4 -r 32 24 -f "$tmp/pipe.pfm" 2>&1 >/dev/null; echo $? >"$tmp/pipe.st" ) | true
check "[ \"\$(cat '$tmp/pipe.st')\" = 0 ] && pfm_ok '$tmp/pipe.pfm' 32 24" "sigpipe_stderr: a closed stderr pipe gave exit $(cat "$tmp/pipe.st") or no image"

# -- threads: OMP_NUM_THREADS=100000 is capped (said where -h says), too small a stack is
#    refused, and threads the system cannot start are fewer threads, not a crash --
OMP_NUM_THREADS=100000 "$fogrt" -s 1 -r 16 12 -f "$tmp/omp.pfm" 2>"$tmp/omp.err"
st=$?
check "[ $st -eq 0 ] && grep -q 'OMP_NUM_THREADS=100000: using' '$tmp/omp.err' && pfm_ok '$tmp/omp.pfm' 16 12" "threads_omp_100000: exit $st: $(head -2 "$tmp/omp.err")"
cap=$(sed -n 's/.*and at most \([0-9]*\)).*/\1/p' "$tmp/omp.err" | head -1)
check "[ -n '$cap' ] && \"$fogrt\" -h | grep -q 'at most $cap;'" "threads_cap_in_help: -h does not state the thread cap (${cap:-?})"
OMP_STACKSIZE=16K "$fogrt" -s 1 -r 16 12 -f "$tmp/stk.pfm" 2>"$tmp/stk.err"
st=$?
check "[ $st -eq 2 ] && grep -q 'OMP_STACKSIZE=16K' '$tmp/stk.err' && [ ! -e '$tmp/stk.pfm' ]" "threads_small_stack: OMP_STACKSIZE=16K gave exit $st: $(cat "$tmp/stk.err")"
if ! nm "$fogrt" 2>/dev/null | grep -q __asan_init; then    # (AddressSanitizer needs more stack itself)
    ( ulimit -s 64; "$fogrt" -s 1 -r 16 12 -f "$tmp/ulim.pfm" ) 2>"$tmp/ulim.err"
    st=$?
    check "[ $st -eq 2 ] && grep -q 'ulimit -s' '$tmp/ulim.err'" "threads_small_stack_limit: ulimit -s 64 gave exit $st: $(cat "$tmp/ulim.err")"
fi
OMP_STACKSIZE=1M "$fogrt" --quiet -s 1 -r 16 12 -t 2 -f "$tmp/stk1m.pfm"
check "[ $? -eq 0 ]" "threads_stack_1M: OMP_STACKSIZE=1M was refused"
if ! nm "$fogrt" 2>/dev/null | grep -q __asan_init; then
    ( ulimit -v 1500000; OMP_STACKSIZE=512M "$fogrt" -t 8 -s 1 -r 16 12 -f "$tmp/few.pfm" ) 2>"$tmp/few.err"
    st=$?
    check "[ $st -eq 0 ] && pfm_ok '$tmp/few.pfm' 16 12" "threads_fallback: 8 threads of 512 MB stack under a 1.5 GB limit: exit $st: $(head -2 "$tmp/few.err")"
    grep 'could start only' "$tmp/few.err" | sed 's/^/test_cli.sh: threads_fallback: /'
fi

# -- extreme_values: a tiny up vector is normalised; --trace indices past their range refused --
"$fogrt" --quiet -s 2 -r 24 18 --seed 2 --camera-pos 0,1,3 --look-at 0,0.7,0 --up 0,1,0 -f "$tmp/up1.pfm"
"$fogrt" --quiet -s 2 -r 24 18 --seed 2 --camera-pos 0,1,3 --look-at 0,0.7,0 --up 0,1e-30,0 -f "$tmp/up30.pfm"
check "cmp -s '$tmp/up1.pfm' '$tmp/up30.pfm'" "up_tiny: --up 0,1e-30,0 renders differently from --up 0,1,0"
"$fogrt" --quiet -s 2 -r 24 18 --seed 2 --camera-pos 0,1,3 --look-at 0,0.7,0 --up 0,7e37,0 -f "$tmp/up37.pfm"
check "cmp -s '$tmp/up1.pfm' '$tmp/up37.pfm'" "up_huge: --up 0,7e37,0 renders differently from --up 0,1,0"
expect 2 "--trace" "trace_index_past_2^32" -- --trace 4294967296,0 -r 24 18
expect 2 "--trace" "trace_sample_past_2^32" -- --trace 1,1,4294967296 -r 24 18
expect 2 "--trace" "trace_negative" -- --trace 1,-1 -r 24 18
expect 0 "" "trace_last_sample" -- --trace 1,1,4294967295 -r 24 18

# -- env_maps: the declared size checked against the file before allocating; truncated maps
#    refused naming the file, in one line --
printf '#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8192 +X 8192\n' >"$tmp/big.hdr"
/usr/bin/time -f '%M' -o "$tmp/big.kb" "$fogrt" -s 1 -r 16 12 -e "$tmp/big.hdr" -f "$out" 2>"$tmp/err" || true
check "grep -q 'big.hdr: the file is too short' '$tmp/err' && [ \$(wc -l <'$tmp/err') -eq 1 ]" "env_hdr_declared_huge: $(cat "$tmp/err")"
[ -s "$tmp/big.kb" ] && echo "test_cli.sh: env_hdr_declared_huge: a $(wc -c <"$tmp/big.hdr")-byte .hdr declaring 8192x8192 refused with $(tail -1 "$tmp/big.kb") KB peak memory"
check "[ ! -s '$tmp/big.kb' ] || [ \$(tail -1 '$tmp/big.kb') -lt 200000 ]" "env_hdr_declared_huge: the refusal took $(tail -1 "$tmp/big.kb" 2>/dev/null) KB"
{ printf '#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 16\n'; i=0; while [ $i -lt 16 ]; do printf '\200\240\310\201'; i=$((i + 1)); done; } >"$tmp/row.hdr"
refused "row.hdr" "" "env_hdr_one_row_of_four" -- -s 1 -r 16 12 -e "$tmp/row.hdr" -f "$out"
check "grep -q 'truncated\\|too short' '$tmp/err'" "env_hdr_one_row_of_four: does not say truncated: $(cat "$tmp/err")"
printf 'PF\n32768 32768\n-1.0\n01234567890123456' >"$tmp/big.pfm"
refused "big.pfm" "too short" "env_pfm_declared_huge" -- -s 1 -r 16 12 -e "$tmp/big.pfm" -f "$out"
/usr/bin/time -f '%M' -o "$tmp/bigpfm.kb" "$fogrt" -s 1 -r 16 12 -e "$tmp/big.pfm" -f "$out" 2>/dev/null || true
[ -s "$tmp/bigpfm.kb" ] && echo "test_cli.sh: env_pfm_declared_huge: a $(wc -c <"$tmp/big.pfm")-byte .pfm declaring 32768x32768 refused with $(tail -1 "$tmp/bigpfm.kb") KB peak memory"
if "$fogrt" -h | grep -q '\.exr'; then
    "$fogrt" --quiet -s 1 -r 16 8 -f "$tmp/env.exr"
    head -c 200 "$tmp/env.exr" >"$tmp/cut.exr"
    refused "cut.exr" "" "env_exr_truncated" -- -s 1 -r 16 12 -e "$tmp/cut.exr" -f "$out"
    printf 'v/1\001garbage' >"$tmp/junk.exr"
    refused "junk.exr" "" "env_exr_junk" -- -s 1 -r 16 12 -e "$tmp/junk.exr" -f "$out"
    if command -v python3 >/dev/null 2>&1; then
        # the 16x8 map's header made to declare 4096x4096 (its windows patched)
        python3 - "$tmp/env.exr" "$tmp/huge.exr" <<'PY'
import sys, struct
d = bytearray(open(sys.argv[1], 'rb').read())
for name in (b'dataWindow\0box2i\0', b'displayWindow\0box2i\0'):
    i = d.find(name) + len(name) + 4
    d[i:i + 16] = struct.pack('<4i', 0, 0, 4095, 4095)
open(sys.argv[2], 'wb').write(d)
PY
        /usr/bin/time -f '%M' -o "$tmp/huge.kb" "$fogrt" -s 1 -r 16 12 -e "$tmp/huge.exr" -f "$out" 2>"$tmp/err" || true
        check "grep -q 'huge.exr: the file is too short' '$tmp/err' && [ \$(wc -l <'$tmp/err') -eq 1 ]" "env_exr_declared_huge: $(cat "$tmp/err")"
        [ -s "$tmp/huge.kb" ] && echo "test_cli.sh: env_exr_declared_huge: a $(wc -c <"$tmp/huge.exr")-byte .exr declaring 4096x4096 refused with $(tail -1 "$tmp/huge.kb") KB peak memory"
    fi
fi

# -- stopping: SIGTERM, SIGINT and SIGHUP stop every long loop within about a second; SIGHUP
#    leaves no temporary file --
# sample_tau FILE: from fogrt's messages in FILE, the time one sample took on one thread in
# that run: seconds x threads / samples (empty when no sample was written). The time a render
# takes to stop is measured in it: a busy machine, or a sanitizer build, makes it longer.
sample_tau() {
    sed -n 's/.*(\([0-9]*\)x\([0-9]*\)): \([0-9.e+-]*\)\/[0-9]* spp in \([0-9.]*\) s .*/\1 \2 \3 \4/p' "$1" | tail -1 |
        awk -v n="$(sed -n 's/.*, \([0-9]*\) threads\{0,1\}).*/\1/p' "$1" | head -1)" \
            '$1 * $2 * $3 > 0 && n > 0 { printf "%.3f", $4 * n / ($1 * $2 * $3) }'
}
# stop_latency NAME SIGNAL LIMIT ARGS...: starts a render, signals it a second after its
# header line (the render has begun, whatever the build's speed), prints and checks. LIMIT
# "tau": the render must stop within 3 tau + 0.5 s (sample_tau), for samples of a second.
stop_latency() {
    name=$1 sig=$2 limit=$3
    shift 3
    "$fogrt" "$@" 2>"$tmp/$name.err" &
    pid=$!
    n=0
    while [ $n -lt 1200 ] && ! grep -q '^fogrt: rendering' "$tmp/$name.err" 2>/dev/null; do sleep 0.05; n=$((n + 1)); done
    sleep 1
    t_sig=$(now); kill -"$sig" "$pid"; wait "$pid"; st=$?; t_end=$(now)
    lat=$(echo "$t_end $t_sig" | awk '{ printf "%.2f", $1 - $2 }')
    if [ "$limit" = tau ]; then
        tau=$(sample_tau "$tmp/$name.err")
        limit=$(awk -v t="${tau:-0}" 'BEGIN { printf "%.2f", 3 * t + 0.5 }')
        [ -n "$tau" ] || limit=0
    fi
    echo "test_cli.sh: $name: stopped $lat s after SIG$sig (exit $st; limit $limit s)"
    check "[ $st -eq 130 ] && awk 'BEGIN { exit !($lat < $limit) }'" "$name: exit $st, $lat s after SIG$sig (limit $limit s): $(cat "$tmp/$name.err")"
}
mkdir "$tmp/hup"
stop_latency stop_adaptive TERM 1.5 -a 1 1e-6 -s 100000 -r 16 12 -f "$tmp/hup/a.pfm"
stop_latency stop_sighup HUP 1.5 -s 100000 -r 64 48 -f "$tmp/hup/h.pfm"
check "pfm_ok '$tmp/hup/h.pfm' 64 48 && [ -z \"\$(ls -A '$tmp/hup' | grep tmp)\" ]" "stop_sighup: no image, or a temporary file left behind"
# -l 65536: a row of 200 pixels takes a minute; the render checks the flag before every sample,
# so it stops once each thread has finished the sample it is in (about 0.1 s)
stop_latency stop_light_samples TERM tau -l 65536 -s 1 -r 200 150 -f "$tmp/hup/l.pfm"
check "pfm_ok '$tmp/hup/l.pfm' 200 150" "stop_light_samples: no 200x150 image written"
# --time stops a first pass slower than the whole limit (-l 65536: about a minute per spp
# here): a timer cancels the batch within a sample and the image so far is written (exit 0).
# Each thread finishes the sample it is in, so the time past the limit is measured in the
# run's own sample time tau = seconds x threads / samples (about 0.1 s; several times that
# under sanitizers on a busy machine): at most 3 tau + 0.5 s. A check per row instead of per
# sample would overrun by 200 tau, a check per pass by the whole pass.
"$fogrt" --time 1 -l 65536 -s 1 -r 200 150 -f "$tmp/hup/t.pfm" 2>"$tmp/time_first.err"; st=$?
secs=$(sed -n 's/.* spp in \([0-9.]*\) s .*/\1/p' "$tmp/time_first.err")
tau=$(sample_tau "$tmp/time_first.err")
echo "test_cli.sh: time_first_pass: stopped after ${secs:-?} s of a 1 s limit, a sample taking ${tau:-?} s on one thread (exit $st)"
check "[ $st -eq 0 ] && pfm_ok '$tmp/hup/t.pfm' 200 150 && [ -n '$tau' ] && awk 'BEGIN { exit !($secs - 1 <= 3 * $tau + 0.5) }'" "time_first_pass: exit $st after ${secs:-?} s, tau ${tau:-?} s: $(cat "$tmp/time_first.err")"
# a signal while the scene loads and builds (nothing rendered yet) quits at once: a fan of
# 300000 slivers takes seconds to build (the roulette pilot)
awk 'BEGIN { n = 300000; print "v 0 0.5 0"; for (i = 0; i <= n; i++) { a = 6.283185307 * i / n; printf "v %f 0.5 %f\n", 0.4 * cos(a), 0.4 * sin(a) }
             for (i = 0; i < n; i++) printf "f 1 %d %d\n", i + 2, i + 3 }' >"$tmp/fan.obj"
"$fogrt" -s 1 -r 8 6 -f "$tmp/hup/fan.pfm" "$tmp/fan.obj" 2>"$tmp/fan.err" &
pid=$!
sleep 0.1    # parsing 12 MB of OBJ alone takes longer
t_sig=$(now); kill -TERM "$pid"; wait "$pid"; st=$?; t_end=$(now)
lat=$(echo "$t_end $t_sig" | awk '{ printf "%.2f", $1 - $2 }')
echo "test_cli.sh: stop_while_loading: stopped $lat s after SIGTERM (exit $st)"
check "[ $st -eq 130 ] && grep -q 'before rendering' '$tmp/fan.err' && awk 'BEGIN { exit !($lat < 1.0) }' && [ ! -e '$tmp/hup/fan.pfm' ]" "stop_while_loading: exit $st, $lat s: $(cat "$tmp/fan.err")"
# ==== end of hostile runs, second round ====

# -- media_in_objects (appendix H): --medium NAME gives the fog flags after it to the object
#    NAME; --interface makes its surface an interface; names are checked against the scene --
# cube OBJ: a closed cube (object "cube", group "box"); two_cubes: two closed cubes, both in a
# group "box"; sheet: an open quad
cube_faces() {   # cube_faces FIRST: the 6 faces of the cube whose 8 vertices start at FIRST
    a=$1
    echo "f $a $((a + 3)) $((a + 2)) $((a + 1))"; echo "f $((a + 4)) $((a + 5)) $((a + 6)) $((a + 7))"
    echo "f $a $((a + 1)) $((a + 5)) $((a + 4))"; echo "f $((a + 1)) $((a + 2)) $((a + 6)) $((a + 5))"
    echo "f $((a + 2)) $((a + 3)) $((a + 7)) $((a + 6))"; echo "f $((a + 3)) $a $((a + 4)) $((a + 7))"
}
{ echo "o cube"; echo "g box"; for p in "0 0 0" "1 0 0" "1 0 1" "0 0 1" "0 1 0" "1 1 0" "1 1 1" "0 1 1"; do echo "v $p"; done; cube_faces 1; } >"$tmp/cube.obj"
{ for p in "0 0 0" "1 0 0" "1 0 1" "0 0 1" "0 1 0" "1 1 0" "1 1 1" "0 1 1"; do echo "v $p"; done
  for p in "2 0 0" "3 0 0" "3 0 1" "2 0 1" "2 1 0" "3 1 0" "3 1 1" "2 1 1"; do echo "v $p"; done
  echo "o left"; echo "g box"; cube_faces 1; echo "o right"; echo "g box"; cube_faces 9; } >"$tmp/two_cubes.obj"
printf 'v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\no sheet\nf 1 2 3 4\n' >"$tmp/sheet.obj"
mio="--quiet -s 2 -r 24 18 --seed 5"
expect 0 "" "media_in_objects: an interface cube holding fog" -- $mio --medium cube --interface --density 3 --albedo 0.5 -f "$tmp/mo_fog.pfm" "$tmp/cube.obj"
"$fogrt" $mio -f "$tmp/mo_plain.pfm" "$tmp/cube.obj"
check "pfm_ok '$tmp/mo_fog.pfm' 24 18 && ! cmp -s '$tmp/mo_fog.pfm' '$tmp/mo_plain.pfm'" "media_in_objects: --medium cube --interface --density 3 renders as the plain cube"
expect 0 "" "media_in_objects: by group name" -- $mio --medium box --interface --density 3 --albedo 0.5 -f "$tmp/mo_group.pfm" "$tmp/cube.obj"
check "cmp -s '$tmp/mo_fog.pfm' '$tmp/mo_group.pfm'" "media_in_objects: the group name box did not name the object cube"
# the fog flags before --medium are the world's, those after it the object's: without world
# fog the world's albedo changes nothing, the object's does; the header says which is which
expect 0 "no fog; media in objects: cube (interface, density 2)" "media_in_objects: the header names the world's fog and the object's" -- \
    -s 2 -r 24 18 --seed 5 --density 0 --medium cube --interface --density 2 -f "$tmp/mo_a.pfm" "$tmp/cube.obj"
"$fogrt" $mio --density 0 --albedo 0.2 --g -0.5 --medium cube --interface --density 2 -f "$tmp/mo_b.pfm" "$tmp/cube.obj"
"$fogrt" $mio --density 0 --medium cube --interface --density 2 --albedo 0.2 --g -0.5 -f "$tmp/mo_c.pfm" "$tmp/cube.obj"
"$fogrt" $mio --medium cube --interface --density 2 -f "$tmp/mo_d.pfm" "$tmp/cube.obj"
check "cmp -s '$tmp/mo_a.pfm' '$tmp/mo_b.pfm'" "media_in_objects: --albedo/--g before --medium changed the object's medium"
check "! cmp -s '$tmp/mo_a.pfm' '$tmp/mo_c.pfm'" "media_in_objects: --albedo/--g after --medium did not reach the object's medium"
check "! cmp -s '$tmp/mo_a.pfm' '$tmp/mo_d.pfm'" "media_in_objects: --density 0 before --medium did not clear the world's fog"
# refusals: one line naming the flag, exit 2, no image
refused "--medium nothere" "has no object (o), material (usemtl) or group (g) named nothere" "media_in_objects: an unknown name" -- --medium nothere --density 1 -f "$out" "$tmp/cube.obj"
check "grep -q 'object (o) names: cube; group (g) names: box' '$tmp/err' && [ ! -e '$out' ]" "media_in_objects: the unknown name's message does not list the scene's names: $(cat "$tmp/err")"
refused "--medium nothere" "node names: a, b, c; material names: red, green; geometry names: quad" "media_in_objects: an unknown name in a .dae" -- --medium nothere --density 1 -f "$out" tests/data/dae_instances.dae
refused "--medium box" "2 objects of $tmp/two_cubes.obj share the group (g) name box" "media_in_objects: a name two objects share" -- --medium box --density 1 -f "$out" "$tmp/two_cubes.obj"
check "grep -q '(object (o) left).*(object (o) right)' '$tmp/err'" "media_in_objects: the shared name's message does not list both objects: $(cat "$tmp/err")"
refused "--medium red" "share the material name red: mesh 0 (node a, geometry quad), mesh 2 (node c, geometry quad)" "media_in_objects: a material two nodes share" -- --medium red --density 1 -f "$out" tests/data/dae_instances.dae
expect 0 "" "media_in_objects: the node name comes first" -- $mio --medium left --density 1 -f "$tmp/mo_left.pfm" "$tmp/two_cubes.obj"
refused "--medium sheet" "open edge" "media_in_objects: a medium in an open mesh (the build's refusal)" -- --medium sheet --density 1 -f "$out" "$tmp/sheet.obj"
refused "--medium x" "the default scene has no named objects" "media_in_objects: names in the default scene" -- --medium x --density 1 -f "$out"
refused "--interface" "must follow --medium NAME" "media_in_objects: --interface alone" -- --interface -f "$out" "$tmp/cube.obj"
refused "--medium cube" "no fog flag" "media_in_objects: --medium with nothing after it" -- --medium cube -f "$out" "$tmp/cube.obj"
refused "--medium cube" "need --density" "media_in_objects: fog flags without --density" -- --medium cube --albedo 0.5 -f "$out" "$tmp/cube.obj"
refused "--medium box" "names the same object as --medium cube" "media_in_objects: two names of one object" -- --medium cube --density 1 --medium box --density 2 -f "$out" "$tmp/cube.obj"
refused "--phase" "rayleigh cannot be combined" "media_in_objects: a medium's own flags are checked" -- --medium cube --density 1 --phase rayleigh --g 0.5,0.1,0.5 -f "$out" "$tmp/cube.obj"
# the world's fog in a box and a medium in an object together: the box's fog changes the image
expect 0 "" "media_in_objects: with the world's fog in a box" -- $mio --fog-bounds -1,-1,-1,2,2,2 --density 0.5 --medium cube --interface --density 3 -f "$tmp/mo_box.pfm" "$tmp/cube.obj"
check "pfm_ok '$tmp/mo_box.pfm' 24 18 && ! cmp -s '$tmp/mo_box.pfm' '$tmp/mo_fog.pfm'" "media_in_objects: the world's fog in a box left the image as without it"
# a medium inside an opaque object cannot be seen: one warning saying what to do
expect 0 "cannot be seen: its surface is opaque" "media_in_objects: a medium in an opaque object is told" -- $mio --medium cube --density 3 -f "$tmp/mo_opaque.pfm" "$tmp/cube.obj"
check "grep -qF -- '--interface' '$tmp/err'" "media_in_objects: the warning on an opaque object does not name --interface"
# the CS184 example: smoke in the glass sphere (node Sphere1; both spheres share geometry Sphere1)
if [ -f ../shared/scenes/cs184/CBspheres.dae ]; then
    cbs=../shared/scenes/cs184/CBspheres.dae
    expect 0 "Sphere1 (density 2)" "media_in_objects: smoke in CBspheres' glass sphere" -- -s 4 -r 32 24 --seed 1 --medium Sphere1 --density 2 --albedo 0.9 --g 0.5 -f "$tmp/mo_cb.pfm" "$cbs"
    "$fogrt" --quiet -s 4 -r 32 24 --seed 1 -f "$tmp/mo_cb0.pfm" "$cbs"
    check "pfm_ok '$tmp/mo_cb.pfm' 32 24 && ! cmp -s '$tmp/mo_cb.pfm' '$tmp/mo_cb0.pfm'" "media_in_objects: the smoke-filled sphere renders as the empty one"
    "$fogrt" --quiet -s 4 -r 32 24 --seed 1 --medium refract --density 2 --albedo 0.9 --g 0.5 -f "$tmp/mo_cb1.pfm" "$cbs"
    check "cmp -s '$tmp/mo_cb.pfm' '$tmp/mo_cb1.pfm'" "media_in_objects: the material name refract does not name the node Sphere1"
else
    echo "test_cli.sh: media_in_objects on CBspheres.dae skipped (../shared/scenes/cs184 absent)"
fi

# ==== what a new user trips over: the fog's extent, -h, one meaning per flag,
#      EXR output, friendlier parsing, the README's examples ====
# -- flags_listed: the flags the parser takes, the flags -h lists and the README's table agree --
parser_flags=$(grep -ho 'cli_is(&\{0,1\}A, "[^"]*")' examples/fogrt_cli.c examples/cli_common.h | sed 's/.*"\(.*\)")/\1/' | sort -u | tr '\n' ' ')
help_flags=$("$fogrt" -h | sed -n 's/^  \(-[-a-zA-Z0-9]*\).*/\1/p' | sort -u | tr '\n' ' ')
readme_flags=$(sed -n '/^| flag | default | meaning |/,/^$/p' README.md | sed 's/\\|/\//g' | awk -F'|' 'NR > 2 { print $2 }' | grep -o '`-[-a-zA-Z0-9]*' | tr -d '`' | sort -u | tr '\n' ' ')
check "[ -n '$parser_flags' ] && [ '$parser_flags' = '$help_flags' ]" "flags_listed: the parser takes [$parser_flags], -h lists [$help_flags]"
check "[ '$parser_flags' = '$readme_flags' ]" "flags_listed: the parser takes [$parser_flags], README's table lists [$readme_flags]"
"$fogrt" -h >"$tmp/help.txt"
undefaulted=$(awk '/^  -/ { if (flag != "" && !ok) print flag; flag = $1; ok = /default/ || /this help/ || /the same as -h/; next }
                   /^    / && flag != "" { if (/default/) ok = 1; next }
                   { if (flag != "" && !ok) print flag; flag = "" }
                   END { if (flag != "" && !ok) print flag }' "$tmp/help.txt" | tr '\n' ' ')
check "[ -z '$undefaulted' ]" "flags_listed: -h gives no default for: $undefaulted"
check "grep -q -- '--exposure EV.*stops' '$tmp/help.txt'" "flags_listed: -h does not say --exposure is in stops"

# -- fog_bounds: all, scene or a box; the header and the summary say where the fog is --
expect 0 "everywhere" "fog_bounds_all: the header says the fog is everywhere" -- -s 2 -r 24 18 --density 0.5 --fog-bounds all -f "$tmp/fb_all.pfm" "$lit"
check "[ \$(grep -c 'everywhere' '$tmp/err') -eq 2 ]" "fog_bounds_all: not in both the header and the summary: $(cat "$tmp/err")"
expect 0 "in the box" "fog_bounds_scene: the header says the box" -- -s 2 -r 24 18 --density 0.5 --fog-bounds scene -f "$tmp/fb_scene.pfm" "$lit"
check "grep -q '^fogrt: rendering .*in the box' '$tmp/err' && grep -q '^fogrt: wrote .*in the box' '$tmp/err'" "fog_bounds_scene: not in both the header and the summary: $(cat "$tmp/err")"
check "! cmp -s '$tmp/fb_all.pfm' '$tmp/fb_scene.pfm'" "fog_bounds_scene: the same image as fog everywhere"
expect 0 "" "fog_bounds_default_is_all" -- --quiet -s 2 -r 24 18 --density 0.5 -f "$tmp/fb_def.pfm" "$lit"
check "cmp -s '$tmp/fb_all.pfm' '$tmp/fb_def.pfm'" "fog_bounds_default_is_all: the default differs from --fog-bounds all"
expect 0 "no fog" "fog_bounds_no_fog: a .dae without --density says so" -- -s 1 -r 16 12 -f "$tmp/fb_none.pfm" "$lit"
expect 2 "--fog-bounds" "fog_bounds_bad_word" -- --fog-bounds room -f "$out"
check "grep -q 'all, scene' '$tmp/err'" "fog_bounds_bad_word: the message does not name all and scene"

# -- exr_output: -f out.exr is the PFM's floats exactly (read back with tinyexr) --
if "$fogrt" -h | grep -q '\.exr'; then
    expect 0 "" "exr_output: write an EXR" -- --quiet -s 2 -r 24 18 --seed 3 -f "$tmp/rt.exr" "$lit"
    "$fogrt" --quiet -s 2 -r 24 18 --seed 3 -f "$tmp/rt.pfm" "$lit"
    cat >"$tmp/exrcmp.c" <<'CEOF'
/* exrcmp A.exr B.pfm: exit 0 when the EXR's RGB floats equal the PFM's (rows from the top) */
#include <tinyexr.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
int main(int argc, char **argv)
{
    float *rgba = NULL, *pfm;
    const char *err = NULL;
    int w, h, pw, ph, x, y, c, bad = 0;
    char line[64];
    FILE *f;
    if (argc != 3 || LoadEXR(&rgba, &w, &h, argv[1], &err) != 0) { fprintf(stderr, "exrcmp: cannot read %s\n", argc > 1 ? argv[1] : "?"); return 2; }
    f = fopen(argv[2], "rb");
    if (!f || !fgets(line, sizeof line, f) || !fgets(line, sizeof line, f) || sscanf(line, "%d %d", &pw, &ph) != 2 || !fgets(line, sizeof line, f)) return 2;
    if (pw != w || ph != h) { fprintf(stderr, "exrcmp: %dx%d against %dx%d\n", w, h, pw, ph); return 1; }
    pfm = (float *)malloc(sizeof(float) * 3 * (size_t)w * (size_t)h);
    if (!pfm || fread(pfm, sizeof(float) * 3, (size_t)w * (size_t)h, f) != (size_t)w * (size_t)h) return 2;
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x)
            for (c = 0; c < 3; ++c)
                if (rgba[4 * ((size_t)y * w + x) + c] != pfm[3 * ((size_t)(h - 1 - y) * w + x) + c]) bad++;
    printf("%d of %d values differ\n", bad, 3 * w * h);
    return bad != 0;
}
CEOF
    if ${CC:-cc} -O1 -o "$tmp/exrcmp" "$tmp/exrcmp.c" -ltinyexr 2>"$tmp/cc.err"; then
        check "'$tmp/exrcmp' '$tmp/rt.exr' '$tmp/rt.pfm' >/dev/null" "exr_output: the EXR's floats are not the PFM's: $("$tmp/exrcmp" "$tmp/rt.exr" "$tmp/rt.pfm" 2>&1)"
    else
        echo "test_cli.sh: exr_output round trip skipped (cannot build a tinyexr reader: $(head -1 "$tmp/cc.err"))"
    fi
    expect 0 "" "exr_output: an EXR fogrt wrote is an environment map" -- --quiet -s 1 -r 16 12 -e "$tmp/rt.exr" -f "$tmp/rt_env.pfm" tests/data/dae_minimal_yup.dae
else
    echo "test_cli.sh: exr_output skipped (fogrt built without libtinyexr-dev)"
fi

# -- friendly_parsing: --flag=value, "did you mean", files of the wrong kind --
"$fogrt" --quiet -s 2 -r 16 12 --seed 4 --density 0.5 -f "$tmp/eq_a.pfm"
"$fogrt" --quiet -s 2 -r 16 12 --seed=4 --density=0.5 -f "$tmp/eq_b.pfm"
check "cmp -s '$tmp/eq_a.pfm' '$tmp/eq_b.pfm'" "flag_equals: --seed=4 --density=0.5 renders differently from --seed 4 --density 0.5"
expect 2 "takes no value" "flag_equals: --quiet=yes" -- --quiet=yes -f "$out"
expect 2 "--density" "flag_equals: --density= (empty)" -- --density= -f "$out"
expect 2 "did you mean --density?" "did_you_mean: --densty" -- --densty 0.5 -f "$out"; one_line_no_image "did you mean"
expect 2 "did you mean --fog-bounds?" "did_you_mean: --fog-bound" -- --fog-bound all -f "$out"
expect 2 "did you mean --exposure?" "did_you_mean: -exposure" -- -exposure 1 -f "$out"
expect 2 "--bogus" "did_you_mean: nothing near --bogus" -- --bogus -f "$out"
check "! grep -q 'did you mean' '$tmp/err'" "did_you_mean: --bogus got a suggestion: $(cat "$tmp/err")"
cp docs/fog.png "$tmp/picture.png"; cp docs/fog.png "$tmp/picture.obj"
refused "picture.png" "a PNG image, not a scene: fogrt reads .dae, .obj, .ply" "wrong_kind: a PNG as the scene" -- -f "$out" "$tmp/picture.png"
refused "picture.obj" "a PNG image, not a scene: fogrt reads .dae, .obj, .ply" "wrong_kind: a PNG named .obj" -- -f "$out" "$tmp/picture.obj"
refused "fogrt" "an executable (ELF), not a CS184 camera settings file" "wrong_kind: -c with an executable" -- -f "$out" -c "$fogrt_abs"
printf '\001\002\033[31m\377\376\300 1 2\n' >"$tmp/bytes.cam"
expect 2 "bytes.cam" "wrong_kind: -c with raw bytes" -- -f "$out" -c "$tmp/bytes.cam"
check "! LC_ALL=C grep -q '[^[:print:]]' '$tmp/err'" "wrong_kind: -c printed raw bytes: $(od -c "$tmp/err" | head -3)"

# -- unresolved_names: a reference the loader cannot resolve is a warning naming the file, the
#    line, the name and the node holding it --
sed 's|target="#m1"|target="#nosuch"|; s|<instance_geometry url="#tri"><bind_material><technique_common><instance_material symbol="m" target="#m2"/>|<instance_geometry url="#notri"><bind_material><technique_common><instance_material symbol="m" target="#m2"/>|' \
  tests/data/dae_materials.dae >"$tmp/unres.dae"
# (the lines the warnings must name: where the two broken references stand in the file)
l_mat=$(grep -n 'target="#nosuch"' "$tmp/unres.dae" | head -1 | cut -d: -f1)
l_geo=$(grep -n 'url="#notri"' "$tmp/unres.dae" | head -1 | cut -d: -f1)
expect 0 "unres.dae:$l_mat: warning: <instance_material> target \"#nosuch\" in <node> \"n1\": not found: grey 0.5" "unresolved_names: instance_material" -- -s 1 -r 8 6 -f "$tmp/unres.pfm" "$tmp/unres.dae"
check "grep -qF 'unres.dae:$l_geo: warning: <instance_geometry> url \"#notri\" in <node> \"n2\": not found: skipped' '$tmp/err'" "unresolved_names: instance_geometry: $(grep warning "$tmp/err")"
# -- readme_timing: every fogrt example in the README says how long it takes --
untimed=$(sed -n '/^## The `fogrt` command/,/^## /p' README.md | grep '^build/fogrt' | grep -v '[0-9] s\b\|[0-9] s)\|minutes\|--time [0-9]' | head -3)
check "[ -z \"\$untimed\" ]" "readme_timing: README examples without their time: $untimed"
# ==== end of the new-user checks ====

echo "test_cli.sh: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
