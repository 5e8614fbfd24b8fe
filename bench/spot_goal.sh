#!/bin/sh
# bench/spot_goal.sh FOGRT SHARED [RUNS] [BASE] [GOAL] [GOAL_REF]: the paper's spot-lit fog, this tree
# against the header of any commit BASE, in the same run (`make bench-spot` runs this).
#
# The scene is `fogrt --density 0.5 --g 0.6 -r 480 360 CBbunny_upSpot.dae`. A time budget is
# a property of a machine, so the script builds BASE's own fogrt from the repository's
# history (bench/base_build.sh: git archive, BASE's own Makefile, into build/bench-base/<commit>) and then, RUNS
# times (default 2), alternating:
#   1. BASE's fogrt with -s 128, whose render time is the budget T;
#   2. FOGRT (this tree's build) with -s 4096 --time T: as many samples as fit in T.
# Both print the error estimate of fogrt_image_error (the relative RMS error of the image).
# Each row gives both errors and the variance ratio at equal time, (base error / this
# error)^2, which does not depend on the machine's speed within a run. The last lines give
# its mean over the runs and, against GOAL_REF, whether this tree ended under GOAL percent
# (default 25) in every run. RUNS=0 only builds.
#
# BASE: any commit, tag or branch (default HEAD~1). The goal (under GOAL percent at the time
# BASE takes for 128 spp) is judged only when BASE is GOAL_REF, the commit it was set against
# (default: BASE itself; `make bench-spot` passes the project's reference, SPOT_GOAL_REF).
# Needs git history (a clone, not an exported tarball) and the CS184 scenes in SHARED.
set -e
FOGRT=$1 SHARED=$2 RUNS=${3:-2} BASE=${4:-HEAD~1} GOAL=${5:-25} GOAL_REF=${6:-${4:-HEAD~1}}
if [ -z "$FOGRT" ] || [ -z "$SHARED" ]; then
    echo "usage: sh bench/spot_goal.sh FOGRT SHARED [RUNS] [BASE] [GOAL] [GOAL_REF]" >&2
    exit 2
fi
SCENE=$SHARED/scenes/cs184/CBbunny_upSpot.dae
case $SCENE in /*) ;; *) SCENE=$PWD/$SCENE ;; esac
if [ ! -f "$SCENE" ]; then
    echo "spot-goal: $SCENE not found (the CS184 scenes live in SHARED=$SHARED): nothing measured" >&2
    exit 2
fi
BASE_FOGRT=$(sh bench/base_build.sh "$BASE" build/fogrt "$SHARED")
OUT=${BASE_FOGRT%/build/fogrt}
if [ "$RUNS" -lt 1 ]; then
    echo "spot-goal: $BASE's fogrt is built; RUNS=$RUNS, nothing measured"
    exit 0
fi
err() { sed -n 's/.*rel\. error \([0-9.]*\)%.*/\1/p' | tail -1; }
spp() { sed -n 's/.*: \([0-9.]*\)\/[0-9]* spp in \([0-9.]*\) s.*/\1 \2/p' | tail -1; }
ok=1
ratios=""
i=1
printf '%-4s | %-28s | %-20s | %s\n' run "$BASE, -s 128" "this tree, --time T" "variance ratio"
while [ "$i" -le "$RUNS" ]; do
    old=$("$OUT/build/fogrt" --density 0.5 --g 0.6 -s 128 -r 480 360 -f "$OUT/base.png" "$SCENE" 2>&1)
    T=$(printf '%s\n' "$old" | spp | awk '{print $2}')
    new=$("$FOGRT" --density 0.5 --g 0.6 -s 4096 -r 480 360 --time "$T" -f "$OUT/new.png" "$SCENE" 2>&1)
    e_old=$(printf '%s\n' "$old" | err); e_new=$(printf '%s\n' "$new" | err)
    n_new=$(printf '%s\n' "$new" | spp | awk '{print $1}')
    ratio=$(awk -v a="$e_old" -v b="$e_new" 'BEGIN { if (b > 0) printf "%.2f", (a / b) ^ 2; else print "n/a" }')
    printf '%-4s | T = %6s s, %6s%%          | %5s spp, %6s%% | %sx\n' "$i" "$T" "$e_old" "$n_new" "$e_new" "$ratio"
    ratios="$ratios $ratio"
    awk -v e="$e_new" -v g="$GOAL" 'BEGIN { exit !(e < g) }' || ok=0
    i=$((i + 1))
done
echo "$ratios" | awk '{ for (i = 1; i <= NF; ++i) if ($i != "n/a") { s += $i; n++ } }
    END { if (n) printf "spot-goal: variance ratio at equal time, mean of %d runs: %.3f (above 1: this tree is better)\n", n, s / n }'
# The goal is set against its reference commit's time; against another base only the ratio means anything.
if [ "$(git rev-parse -q --verify "$BASE^{commit}")" != "$(git rev-parse -q --verify "$GOAL_REF^{commit}")" ]; then
    echo "spot-goal: (the goal, under $GOAL% at $GOAL_REF's time for 128 spp, is judged against $GOAL_REF only)"
elif [ "$ok" = 1 ]; then echo "spot-goal: under $GOAL% in every run: met on this machine"
else echo "spot-goal: NOT met on this machine (the goal: under $GOAL% at the time $BASE takes for 128 spp)"; fi
