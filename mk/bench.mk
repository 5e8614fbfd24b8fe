# mk/bench.mk - benchmarks (docs/benchmarks.md).
#   make bench       BVH build time, bytes per triangle, closest-hit and shadow (any-hit)
#                    Mrays/s (1 and 2 threads) of the bunny, a 1M mesh and a fan of slivers,
#                    render samples/s and its 2T/1T; BENCH_ARGS=--quick for a short, noisy
#                    run, BENCH_ARGS=--fan for the fan alone
#   make bench-spot  the paper's spot-lit fog at equal time, this tree against the header of
#                    commit SPOT_BASE in the same run (default 7a4a5f3, the goal's reference)
#   make bench-shapes  a medium inside a shape under a spot lamp, relMSE x seconds against the
#                    header of commit SHAPES_BASE at equal time
#   make bench-base  make bench's figures against the header of commit BENCH_BASE, same run
#   make same-image  this tree's images against those of commit IMAGE_BASE (cmp, and means)
#   make callgrind   instructions a scene pays for features it does not use (fails above +1%)
#   make variance-sources  which samples carry an image's noise (VS_ARGS: scene and flags)
#
# What it compares against and reads:
#   - Embree 3 (rtcIntersect1, rtcOccluded1, its memory monitor), the yardstick of every ratio:
#     Debian's libembree-dev, installed by `make bench` with apt-get when root; otherwise it
#     stops with one line naming the package. `make bench BENCH_EMBREE=0` runs without it
#     (fogrt's figures alone, no ratios).
#   - the CS184 bunny: when fogrt_load.h declares fogrt_load_dae and $(SHARED) has CBbunny.dae
#     (otherwise bench.c uses a synthetic mesh of the same size).
.PHONY: bench bench-base callgrind bench-levers deps-embree bench-spot bench-shapes variance-sources same-image

BENCH_EMBREE        ?= 1
BENCH_EMBREE_HEADER := /usr/include/embree3/rtcore.h
BENCH_HAVE_LOAD     := $(and $(shell grep -l 'fogrt_load_dae' fogrt_load.h 2>/dev/null),$(wildcard $(SHARED)/scenes/cs184/CBbunny.dae))

BENCH_DEFS := -DFOGRT_SHARED_DIR='"$(SHARED)"' -DBENCH_CFLAGS='"$(strip $(CFLAGS) $(OMPFLAGS))"' \
              $(if $(BENCH_HAVE_LOAD),-DHAVE_FOGRT_LOAD)
BENCH_ARGS ?=
# Two programs, with and without Embree, so that switching BENCH_EMBREE rebuilds nothing stale.
BENCH_BIN := $(BUILD)/bench/$(if $(filter 1,$(BENCH_EMBREE)),fogrt_bench,fogrt_bench_alone)

deps-embree:
	@[ "$(BENCH_EMBREE)" != 1 ] || sh tools/need-package.sh libembree-dev $(BENCH_EMBREE_HEADER) \
	  "or run 'make bench BENCH_EMBREE=0' for fogrt's figures alone (Embree is make bench's yardstick)"

$(BUILD)/bench/fogrt_bench: bench/bench.c bench/bench_embree.c bench/fan.h fogrt.h $(wildcard fogrt_load.h) mk/bench.mk | deps-embree $(BUILD)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) $(BENCH_DEFS) -DHAVE_EMBREE -o $@ bench/bench.c bench/bench_embree.c -lembree3 $(LDLIBS)

$(BUILD)/bench/fogrt_bench_alone: bench/bench.c bench/fan.h fogrt.h $(wildcard fogrt_load.h) mk/bench.mk | $(BUILD)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) $(BENCH_DEFS) -o $@ bench/bench.c $(LDLIBS)

bench: $(BENCH_BIN)
	./$(BENCH_BIN) $(BENCH_ARGS)

# The fans of slivers as files (binary PLY, or one OBJ polygon): what fogrt's memory and time
# on them are measured with (docs/benchmarks.md, "Slivers").
$(BUILD)/bench/fan_mesh: bench/fan_mesh.c bench/fan.h | $(BUILD)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) -o $@ bench/fan_mesh.c $(LDLIBS)

# The spot-lit fog at equal time against SPOT_BASE's header, rebuilt from git history into
# build/bench-base/<commit> (bench/spot_goal.sh): about a minute per run, SPOT_RUNS runs.
# SPOT_BASE: any commit (e.g. HEAD~1). The goal, under SPOT_GOAL percent at the time the base
# takes for 128 spp, was set against SPOT_GOAL_REF and is judged against it only.
SPOT_RUNS ?= 2
SPOT_BASE ?= 7a4a5f3
SPOT_GOAL ?= 25
SPOT_GOAL_REF ?= 7a4a5f3
bench-spot: $(BUILD)/fogrt
	sh bench/spot_goal.sh $(BUILD)/fogrt $(SHARED) $(SPOT_RUNS) $(SPOT_BASE) $(SPOT_GOAL) $(SPOT_GOAL_REF)

# A lamp-lit scene with a medium inside a shape (the spot-lit bunny as a fog volume in fog),
# relMSE against a reference x seconds, this tree against SHAPES_BASE's header at equal time
# (bench/shapes_gain.sh): SHAPES_SECONDS per render, SHAPES_RUNS runs, after a 4096-spp
# reference (a few minutes, made once per build).
SHAPES_BASE ?= HEAD~1
SHAPES_SECONDS ?= 10
SHAPES_RUNS ?= 3
bench-shapes: $(BUILD)/fogrt
	sh bench/shapes_gain.sh $(BUILD)/fogrt $(SHARED) $(SHAPES_BASE) $(SHAPES_SECONDS) $(SHAPES_RUNS)

# make bench's figures, this tree against the header of commit BENCH_BASE in the same run:
# both bench programs alternately, BENCH_RUNS rounds, each figure's median ratio
# (bench/same_run.sh; about two minutes a round, BENCH_ARGS=--quick for a short one).
BENCH_BASE ?= HEAD~1
BENCH_RUNS ?= 3
bench-base:
	sh bench/same_run.sh $(BENCH_BASE) $(BENCH_RUNS) "$(BENCH_ARGS)" $(SHARED)

# This tree's images against those of the header of commit IMAGE_BASE, at fixed seeds
# (bench/same_image.sh): identical with per-pixel rates off, channel means within 0.1% with the
# default settings; the default scene and the spot-lit bunny. About a minute after the build.
IMAGE_BASE ?= HEAD~1
same-image: $(BUILD)/fogrt
	sh bench/same_image.sh $(IMAGE_BASE) $(SHARED)

# No OpenMP here on purpose: one thread, a deterministic instruction count.
callgrind:
	CC='$(CC)' CFLAGS='$(CFLAGS)' BUILD='$(BUILD)' sh bench/callgrind.sh

# Estimator levers in work, not wall time (bench/levers.c; one thread; the spot-lit part
# needs $(SHARED)/scenes; about 6 minutes): lights by power, the glow, expected emission.
LEVERS_ARGS ?=
# (one rule for the single-file bench programs that read scenes: levers, variance_sources)
$(BUILD)/bench/levers $(BUILD)/bench/variance_sources: $(BUILD)/bench/%: bench/%.c fogrt.h $(wildcard fogrt_load.h) mk/bench.mk | $(BUILD)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) $(BENCH_DEFS) -o $@ $< $(LDLIBS)

bench-levers: $(BUILD)/bench/levers
	./$(BUILD)/bench/levers $(LEVERS_ARGS)

# Which samples carry the noise: every sample of a small render through fogrt_trace_path,
# the noise split by brightness, source, bounce and throughput (bench/variance_sources.c).
# VS_ARGS: e.g. '$(SHARED)/scenes/cs184/CBbunny_upSpot.dae --density 0.5 --g 0.6';
# default: the embedded default scene, 120 x 90, 64 spp (seconds on two cores).
VS_ARGS ?=

variance-sources: $(BUILD)/bench/variance_sources
	./$(BUILD)/bench/variance_sources $(VS_ARGS)

# CS184's CBspheres with two rough metals (appendix I) as CS184 writes them, clear and in fog
# (tools/microfacet_demo.sh; build/microfacet/, about a minute).
.PHONY: microfacet-demo
microfacet-demo: $(BUILD)/fogrt
	sh tools/microfacet_demo.sh $(BUILD)/fogrt $(SHARED)
