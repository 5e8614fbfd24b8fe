#!/bin/sh
# bench/ab/build.sh OLD_HEADER NEW_HEADER: builds build/ab/ab, a same-run A/B of two versions
# of fogrt.h (each compiled whole, FOGRT_STATIC, in a file of its own) and Embree 3, on
# bench.c's ray sets (random, bounce, shadow) of the CS184 bunny and the 1M mesh, one thread.
# Run from the repository root, e.g.
#   mkdir -p build/ab/old && git show main:fogrt.h > build/ab/old/fogrt.h
#   sh bench/ab/build.sh $PWD/build/ab/old/fogrt.h $PWD/fogrt.h && build/ab/ab --reps 15
# ab times CPU time of its thread (AB_WALL=1: wall time), passes rotating old / new / Embree,
# and prints medians and the medians of same-run ratios, and how many answers differ
# between old and new (t and primitive). --mesh bunny|big, --set 1|2|3, --only old|new|emb
# (for callgrind: sh bench/ab/instructions.sh new prints instructions per ray), --side N
# (the primary rays are N x N, default 512), AB_BUILD=1 also times the two builds.
# OLDF / NEWF in the environment: extra flags for one side (e.g. NEWF=-DFOGRT_WBVH_NO_AVX2).
set -e
OLD=$1 NEW=$2; shift 2; OLDF=${OLDF:-}; NEWF=${NEWF:-}
D=build/ab
mkdir -p $D
cc -std=c99 -O2 -g "$@" $OLDF -DFOGRT_AB_HEADER="\"$OLD\"" -DAB_SIDE=old -c -o $D/old.o bench/ab/side.c
cc -std=c99 -O2 -g "$@" $NEWF -DFOGRT_AB_HEADER="\"$NEW\"" -DAB_SIDE=new -c -o $D/new.o bench/ab/side.c
cc -std=c99 -O2 -g -fopenmp -I. -DFOGRT_SHARED_DIR='"../shared"' -DHAVE_FOGRT_LOAD -DHAVE_EMBREE -c -o $D/main.o bench/ab/main.c
cc -std=c99 -O2 -g -fopenmp -c -o $D/emb.o bench/bench_embree.c
cc -fopenmp -o $D/ab $D/main.o $D/old.o $D/new.o $D/emb.o -lembree3 -lm
