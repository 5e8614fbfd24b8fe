#!/bin/sh
# test_cli.sh - the `fogrt` command line: bad input gives exit status 2 and one message naming
# the flag or file:line, without writing an image; good input renders and writes the image.
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
expect 2 "-m"           "zero depth"              -- -m 0 -f "$out"
expect 2 "-b"           "negative lens radius"    -- -b -0.1 -f "$out"
expect 2 "-d"           "zero focal distance"     -- -d 0 -f "$out"
expect 2 "-a"           "adaptive tolerance 0"    -- -a 8 0 -f "$out"
expect 2 "--albedo"     "albedo above 1"          -- --albedo 1.5 -f "$out"
expect 2 "--albedo"     "albedo with two parts"   -- --albedo 0.5,0.5 -f "$out"
expect 2 "--albedo"     "negative albedo channel" -- --albedo 0.5,-0.1,0.5 -f "$out"
expect 2 "--integrator" "unknown integrator"      -- --integrator bidir -f "$out"
expect 2 "--fresnel"    "unknown fresnel"         -- --fresnel fast -f "$out"
expect 2 "--bvh"        "unknown bvh"             -- --bvh kd -f "$out"
expect 2 "--seed"       "negative seed"           -- --seed -1 -f "$out"
expect 2 "--time"       "zero time"               -- --time 0 -f "$out"
expect 2 "--target-error" "negative target error" -- --target-error -1 -f "$out"
expect 2 "-f"           "unknown image type"      -- -f "$tmp/out.jpg"
expect 2 "-f"           "unwritable output"       -- -f "$tmp/no/such/dir/out.png"
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
for flag in -s -l -t -m -r -f -b -d -a -H -c -g -h --density --albedo --g --integrator --fresnel --bvh --seed --time --target-error --quiet; do
    check "grep -qF -- ' $flag ' '$tmp/out'" "-h does not document $flag"
done
defaults=$(grep -c 'default' "$tmp/out")
check "[ $defaults -ge 20 ]" "-h names a default for every flag (found $defaults)"

# ---- good runs: every output type, every scene type, the method flags ----
expect 0 "spp" "default scene to PNG with a summary line" -- -s 1 -r 32 24 -f "$tmp/a.png"
check "[ \"\$(head -c 4 '$tmp/a.png' | od -An -c | tr -d ' ')\" = '211PNG' ]" "a.png is not a PNG"
check "grep -q 'rel. error' '$tmp/err'" "the summary line has no error estimate"
expect 0 "" "quiet dae to PFM" -- --quiet -s 2 -r 40 30 -f "$tmp/b.pfm" tests/data/dae_area_light.dae
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
"$fogrt" --quiet -s 2 -r 20 16 --seed 3 -t 1 -f "$tmp/t1.pfm" tests/data/dae_area_light.dae
"$fogrt" --quiet -s 2 -r 20 16 --seed 3 -t 2 -f "$tmp/t2.pfm" tests/data/dae_area_light.dae
check "cmp -s '$tmp/t1.pfm' '$tmp/t2.pfm'" "the image depends on the thread count"

echo "test_cli.sh: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
