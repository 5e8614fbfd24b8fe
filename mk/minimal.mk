# mk/minimal.mk - fogrt on Part I of fogrt.h alone (FOGRT_MINIMAL: the paper's renderer).
#   make fogrt-minimal   builds the fogrt command on Part I alone as $(BUILD)/fogrt-minimal: the
#                        loaders and every flag of the paper's method work; a flag that needs
#                        Part II (--glow, --pixel-rates on, -e, --trace, --fog-bounds scene, ...)
#                        is refused with one line naming FOGRT_MINIMAL.
.PHONY: fogrt-minimal
fogrt-minimal: $(BUILD)/fogrt-minimal
$(BUILD)/fogrt-minimal: examples/fogrt_cli.c examples/fogrt_cli_trace.c examples/cli_common.h examples/stb_write.h fogrt.h fogrt_load.h | deps-stb deps-exr $(BUILD)
	$(QCC)$(CC) $(ALL_CFLAGS) -DFOGRT_MINIMAL $$([ -e $(TINYEXR_HEADER) ] && echo -DFOGRT_CLI_EXR) -o $@ examples/fogrt_cli.c \
	  examples/fogrt_cli_trace.c $$([ -e $(TINYEXR_HEADER) ] && echo -ltinyexr) $(LDLIBS)

# Under MINIMAL=1 make test runs the Unity programs only (mk/cli.mk added the CLI's suite).
ifeq ($(MINIMAL),1)
TEST_LOGS := $(filter-out %/test_cli.sh.log,$(TEST_LOGS))
endif
