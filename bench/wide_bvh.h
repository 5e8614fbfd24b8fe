/* bench/wide_bvh.h - empty: the faster binned build drafted here (its section "9b") is now
   fogrt__bvh_build in chapter 9 of fogrt.h, and bench/wide_dev.c no longer includes this
   file. It stays only because docs/benchmarks.md still names it. */
