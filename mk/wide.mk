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
