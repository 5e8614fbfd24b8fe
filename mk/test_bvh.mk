# mk/test_bvh.mk - test_bvh links two more builds of fogrt.h, tests/bvh_paths.c compiled with
# FOGRT_WBVH_NO_SIMD and with FOGRT_NO_WIDE_BVH: its test_split_paths_agree compares their
# trees (Part I's scalar binned split) node for node with its own (the split in SSE lanes).
# The Makefile's rule for tests builds it; these lines add the two objects to its link.
BVH_PATHS_OBJS := $(BUILD)/tests/bvh_paths_nosimd.o $(BUILD)/tests/bvh_paths_nowide.o

$(BUILD)/tests/bvh_paths_nosimd.o: tests/bvh_paths.c fogrt.h | $(BUILD)
	$(QCC)$(CC) $(ALL_CFLAGS) -DFOGRT_WBVH_NO_SIMD -DBVH_PATHS_NAME=bvh_paths_nosimd -c -o $@ $<
$(BUILD)/tests/bvh_paths_nowide.o: tests/bvh_paths.c fogrt.h | $(BUILD)
	$(QCC)$(CC) $(ALL_CFLAGS) -DFOGRT_NO_WIDE_BVH -DBVH_PATHS_NAME=bvh_paths_nowide -c -o $@ $<

$(BUILD)/tests/test_bvh: $(BVH_PATHS_OBJS)
$(BUILD)/tests/test_bvh: LDLIBS += $(BVH_PATHS_OBJS)
