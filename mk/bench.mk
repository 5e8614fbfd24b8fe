# mk/bench.mk - benchmarks (docs/benchmarks.md).
#   make bench       BVH build time, bytes per triangle, closest-hit and shadow (any-hit)
#                    Mrays/s (1 and 2 threads), render samples/s and its 2T/1T;
#                    BENCH_ARGS=--quick for a short, noisy run
#   make callgrind   instruction cost of the fog code in a fog-free render (fails above +3%)
#
# Optional parts, switched on by what exists (nothing is installed by `make bench`):
#   - the CS184 bunny: when fogrt_load.h declares fogrt_load_dae and $(SHARED) has CBbunny.dae
#     (otherwise bench.c uses a synthetic mesh of the same size);
#   - Embree 3 for comparison (rtcIntersect1, rtcOccluded1, its memory monitor): when
#     /usr/include/embree3/rtcore.h exists (Debian/Ubuntu: apt-get install libembree-dev).
.PHONY: bench callgrind bench-levers

BENCH_EMBREE_HEADER := /usr/include/embree3/rtcore.h
BENCH_HAVE_EMBREE   := $(wildcard $(BENCH_EMBREE_HEADER))
BENCH_HAVE_LOAD     := $(and $(shell grep -l 'fogrt_load_dae' fogrt_load.h 2>/dev/null),$(wildcard $(SHARED)/scenes/cs184/CBbunny.dae))

BENCH_DEFS := -DFOGRT_SHARED_DIR='"$(SHARED)"' -DBENCH_CFLAGS='"$(strip $(CFLAGS) $(OMPFLAGS))"' \
              $(if $(BENCH_HAVE_LOAD),-DHAVE_FOGRT_LOAD) $(if $(BENCH_HAVE_EMBREE),-DHAVE_EMBREE)
BENCH_SRCS := bench/bench.c $(if $(BENCH_HAVE_EMBREE),bench/bench_embree.c)
BENCH_LIBS := $(if $(BENCH_HAVE_EMBREE),-lembree3)
BENCH_ARGS ?=

$(BUILD)/bench/fogrt_bench: $(BENCH_SRCS) fogrt.h $(wildcard fogrt_load.h) mk/bench.mk | $(BUILD)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) $(BENCH_DEFS) -o $@ $(BENCH_SRCS) $(BENCH_LIBS) $(LDLIBS)

bench: $(BUILD)/bench/fogrt_bench
	./$(BUILD)/bench/fogrt_bench $(BENCH_ARGS)

# No OpenMP here on purpose: one thread, a deterministic instruction count.
callgrind:
	CC='$(CC)' CFLAGS='$(CFLAGS)' BUILD='$(BUILD)' sh bench/callgrind.sh

# The estimator levers of docs/benchmarks.md in work, not wall time (one thread; the
# spot-lit part needs $(SHARED)/scenes; a few minutes): lights by power, the glow.
LEVERS_ARGS ?=
$(BUILD)/bench/levers: bench/levers.c fogrt.h $(wildcard fogrt_load.h) mk/bench.mk | $(BUILD)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) $(BENCH_DEFS) -o $@ bench/levers.c $(LDLIBS)

bench-levers: $(BUILD)/bench/levers
	./$(BUILD)/bench/levers $(LEVERS_ARGS)
