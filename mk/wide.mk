# mk/wide.mk - `make wide-dev`: the wide BVH's development harness (bench/wide_dev.c, for
# chapter 10b of fogrt.h): checks the wide traversal against fogrt__traverse on
# the CS184 bunny, random soups and the 1M-triangle mesh, then times binary vs wide (and
# Embree 3 when /usr/include/embree3/rtcore.h exists) on one thread.
#   WIDE_ARGS=--check-only | --speed-only | --no-big | --reps N | --rays N
# No OpenMP: every figure is one thread.
.PHONY: wide-dev

WIDE_HAVE_EMBREE := $(wildcard /usr/include/embree3/rtcore.h)
WIDE_ARGS ?=
WIDE_DEFS := -DFOGRT_SHARED_DIR='"$(SHARED)"' $(if $(WIDE_HAVE_EMBREE),-DHAVE_EMBREE)
WIDE_LIBS := $(if $(WIDE_HAVE_EMBREE),-lembree3)

$(BUILD)/bench/wide_dev: bench/wide_dev.c fogrt.h fogrt_load.h mk/wide.mk | $(BUILD)
	@mkdir -p $(@D)
	$(CC) $(WARN) $(CFLAGS) -I. $(WIDE_DEFS) -o $@ bench/wide_dev.c $(WIDE_LIBS) $(LDLIBS)

wide-dev: $(BUILD)/bench/wide_dev
	./$(BUILD)/bench/wide_dev $(WIDE_ARGS)

# `make wide-paths`: every SIMD path of the wide BVH built warning-free (-Werror) and checked
# with wide_dev --check-only --no-big (the wide traversal against the binary one): the
# default (SSE, and AVX2 chosen at run time where the processor has it, then also checked
# against SSE bit for bit), FOGRT_WBVH_NO_AVX2, FOGRT_WBVH_NO_SIMD (plain C99) and -mavx2
# (AVX2 at compile time, where the compiler and the processor have it).
WIDE_PATHS := default: noavx2:-DFOGRT_WBVH_NO_AVX2 nosimd:-DFOGRT_WBVH_NO_SIMD avx2:-mavx2
.PHONY: wide-paths
wide-paths: | $(BUILD)
	@mkdir -p $(BUILD)/bench
	@set -e; for p in $(WIDE_PATHS); do \
	    name=$${p%%:*}; flags=$${p#*:}; \
	    if [ $$name = avx2 ] && ! grep -qw avx2 /proc/cpuinfo 2>/dev/null; then echo "skip  $$name (no AVX2 here)"; continue; fi; \
	    $(CC) $(WARN) -Werror $(CFLAGS) $$flags -I. $(WIDE_DEFS) -o $(BUILD)/bench/wide_dev_$$name bench/wide_dev.c $(WIDE_LIBS) $(LDLIBS); \
	    out=$(BUILD)/bench/wide_dev_$$name.txt; \
	    ./$(BUILD)/bench/wide_dev_$$name --check-only --no-big >$$out 2>&1 || { cat $$out; echo "FAIL  $$name"; exit 1; }; \
	    printf '%-8s ' $$name; sed -n '1p;$$p' $$out | tr '\n' ' '; echo; \
	done
