# mk/cli.mk - the `fogrt` command-line renderer, its shell test, and libFuzzer targets for
# the scene loaders in fogrt_load.h.
#   make                 builds $(BUILD)/fogrt (the top Makefile's `all`)
#   make cli-test        runs tests/test_cli.sh against $(BUILD)/fogrt (also part of `make test`)
#   make fuzz            fuzzes the .dae, .obj and .ply parsers, FUZZ_SECONDS each (default 600)
#   make fuzz-dae ...    one parser

# OpenEXR environment maps (-e map.exr) through Debian's libtinyexr-dev: installed when root,
# otherwise the CLI is built without them and says so when given a .exr (.hdr and .pfm work).
TINYEXR_HEADER := /usr/include/tinyexr.h
# Under SANITIZE=1: stb_image_write's JPEG encoder (Debian's libstb-dev, not ours) shifts a
# signed int past its range, which UBSan would abort on; the rest of UBSan stays on.
CLI_SANITIZE := $(if $(filter 1,$(SANITIZE)),-fno-sanitize=shift)
$(BUILD)/fogrt: examples/fogrt_cli.c examples/fogrt_cli_trace.c examples/cli_common.h examples/stb_write.h fogrt.h fogrt_load.h | deps-stb deps-exr $(BUILD)
	$(QCC)$(CC) $(ALL_CFLAGS) $(CLI_SANITIZE) $$([ -e $(TINYEXR_HEADER) ] && echo -DFOGRT_CLI_EXR) -o $@ examples/fogrt_cli.c \
	  examples/fogrt_cli_trace.c $$([ -e $(TINYEXR_HEADER) ] && echo -ltinyexr) $(LDLIBS)

# (no recipe, so no job, when it is there: see deps-stb in the Makefile)
.PHONY: deps-exr deps-exr-install
deps-exr: $(if $(wildcard $(TINYEXR_HEADER)),,deps-exr-install)
deps-exr-install:
	@sh tools/need-package.sh libtinyexr-dev $(TINYEXR_HEADER) 2>/dev/null || \
	  echo "fogrt: libtinyexr-dev not installed: building the fogrt command without OpenEXR (-e .exr) support"

.PHONY: cli-test fuzz fuzz-dae fuzz-obj fuzz-ply fuzz-build fuzz-deps
cli-test: $(BUILD)/fogrt
	@sh tests/test_cli.sh $(BUILD)/fogrt
# In make test: run beside the Unity programs, its "test_cli.sh: N passed, M failed" counted
# in the final line.
$(BUILD)/tests/test_cli.sh.log: $(BUILD)/fogrt FORCE
	@OMP_WAIT_POLICY=$${OMP_WAIT_POLICY:-passive} sh tests/run_tests.sh --run $@ sh tests/test_cli.sh $(BUILD)/fogrt
TEST_LOGS += $(BUILD)/tests/test_cli.sh.log

# ---- fuzzing (clang + libFuzzer, from Debian: clang and libclang-rt-*-dev) ----
FUZZ_SECONDS ?= 600
FUZZ_CC      ?= clang
FUZZ_DIR     := $(BUILD)/fuzz
FUZZ_DEFS    ?=
FUZZ_CFLAGS  := -std=c99 -g -O1 -fno-omit-frame-pointer -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined $(FUZZ_DEFS) -I.

fuzz-deps:
	@sh tools/need-package.sh clang /usr/bin/clang
	@[ -e "$$($(FUZZ_CC) --print-runtime-dir 2>/dev/null)/libclang_rt.fuzzer-x86_64.a" ] || \
	  sh tools/need-package.sh libclang-rt-$$($(FUZZ_CC) -dumpversion | cut -d. -f1)-dev \
	    "$$($(FUZZ_CC) --print-runtime-dir)/libclang_rt.fuzzer-x86_64.a"

$(FUZZ_DIR)/fuzz_%: tests/fuzz/fuzz_%.c tests/fuzz/fuzz_common.h fogrt.h fogrt_load.h | fuzz-deps $(BUILD)
	@mkdir -p $(FUZZ_DIR)
	$(FUZZ_CC) $(FUZZ_CFLAGS) -o $@ $< -lm

fuzz-build: $(FUZZ_DIR)/fuzz_dae $(FUZZ_DIR)/fuzz_obj $(FUZZ_DIR)/fuzz_ply

# The seed corpus in tests/fuzz/corpus_<fmt> is read-only; new inputs go to $(FUZZ_DIR)/corpus_<fmt>,
# crashes to $(FUZZ_DIR)/crash-<fmt>-*. Fixed crashes belong in tests/fuzz/regress/ (replayed by
# tests/test_load.c).
define FOGRT_FUZZ_RUN
fuzz-$(1): $$(FUZZ_DIR)/fuzz_$(1)
	@mkdir -p $$(FUZZ_DIR)/corpus_$(1)
	$$(FUZZ_DIR)/fuzz_$(1) $$(FUZZ_DIR)/corpus_$(1) tests/fuzz/corpus_$(1) \
	  $$(if $$(wildcard tests/fuzz/$(1).dict),-dict=tests/fuzz/$(1).dict) \
	  -max_total_time=$$(FUZZ_SECONDS) -max_len=65536 -timeout=10 -rss_limit_mb=2048 \
	  -print_final_stats=1 -artifact_prefix=$$(FUZZ_DIR)/crash-$(1)-
endef
$(foreach f,dae obj ply,$(eval $(call FOGRT_FUZZ_RUN,$(f))))

fuzz: fuzz-dae fuzz-obj fuzz-ply
