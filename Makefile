# fogrt - build, run, test, bench.  `make run` renders the default scene, `make test` runs the tests.
CC      ?= cc
CXX     ?= c++
PREFIX  ?= /usr/local
OPENMP  ?= 1
WARN    := -std=c99 -Wall -Wextra -pedantic -Wshadow
CFLAGS  ?= -O2 -g
ifeq ($(OPENMP),1)
OMPFLAGS := -fopenmp
endif
ALL_CFLAGS = $(WARN) $(CFLAGS) $(OMPFLAGS) -I.
LDLIBS  += -lm
BUILD   ?= build
SHARED  ?= ../shared

# `make test SANITIZE=1`: the same tests under AddressSanitizer and UndefinedBehaviorSanitizer.
# -O2, not the sanitizers' minimum -O1: every access and operation the program performs is
# still checked, and the suite runs 3 times faster (the tests' renders call fogrt's small
# helpers millions of times; -O1 inlines few of them), for twice the compile time.
# -fno-var-tracking: a report's stack trace needs the line tables only, and tracking the
# variables' locations costs a quarter of the compile time.
ifeq ($(SANITIZE),1)
BUILD   := build-san
CFLAGS  := -O2 -g -fno-var-tracking -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=undefined
endif
# `make test MINIMAL=1`: the suite against Part I of fogrt.h alone (FOGRT_MINIMAL): the tests
# of Part II are skipped, one line each naming the macro (the CLI's suite, whose flags are
# the full build's, is left out: mk/minimal.mk; make fogrt-minimal builds that command).
ifeq ($(MINIMAL),1)
BUILD   := build-min
CFLAGS  += -DFOGRT_MINIMAL
endif

# fogrt's implementation, compiled once per build configuration (the flags above, into
# $(BUILD)) and linked into every test and tutorial program that uses the public API alone,
# instead of each compiling all of fogrt.h again (about 4 CPU seconds each at -O2).
FOGRT_IMPL_OBJ := $(BUILD)/fogrt_impl.o

# Unity: the real one when UNITY_DIR is given, else the small compatible runner in tests/runner.
ifdef UNITY_DIR
UNITY_INC := -I$(UNITY_DIR) -DUNITY_INCLUDE_DOUBLE
UNITY_SRC := $(UNITY_DIR)/unity.c
else
UNITY_INC := -Itests/runner
UNITY_SRC := tests/runner/unity.c
endif

# Quiet by default: "CC target" instead of the compiler's command line, one line per test
# program; `make V=1` (and `make test V=1`) shows the commands and every test's output.
V ?= 0
ifeq ($(V),1)
QCC :=
else
QCC  = @echo "  CC      $@";
endif
NPROC := $(shell nproc 2>/dev/null || echo 2)

.PHONY: all run test test-run bench install clean deps-stb check-compile FORCE
all: $(BUILD)/fogrt

# ---- tests: every tests/test_*.c is one Unity test program, run into $(BUILD)/tests/<name>.log ----
# (listed before mk/*.mk, which add their suites to TEST_LOGS: mk/cli.mk the CLI's)
TEST_SRCS := $(wildcard tests/test_*.c)
TEST_BINS := $(patsubst tests/%.c,$(BUILD)/tests/%,$(TEST_SRCS))
TEST_LOGS := $(addsuffix .log,$(TEST_BINS))

# ---- system packages: installed with apt-get when root, else one line naming the package ----
# A package already there leaves its deps-* target without a recipe, so no job: under -j, make
# starts a target whose prerequisites are still running only on its next pass over the goals,
# after every other target it can start (make test's first job, the fogrt command, would
# otherwise wait for every test program to be built).
STB_HEADER := /usr/include/stb/stb_image_write.h
.PHONY: deps-stb-install
deps-stb: $(if $(wildcard $(STB_HEADER)),,deps-stb-install)
deps-stb-install:
	@sh tools/need-package.sh libstb-dev $(STB_HEADER)

# ---- the command-line renderer and the default-scene example ----
$(BUILD):
	@mkdir -p $(BUILD)/tests

-include mk/*.mk

run: deps-stb $(BUILD)/render_default
	./$(BUILD)/render_default fog.png fog.pfm

$(BUILD)/render_default: examples/render_default.c fogrt.h | $(BUILD)
	$(QCC)$(CC) $(ALL_CFLAGS) -o $@ examples/render_default.c $(LDLIBS)

# ---- the README's program: make test's check-docs (mk/docs.mk) compiles and runs it as the
# README shows it, which is examples/minimal.c; `make build/minimal` builds the file itself ...
$(BUILD)/minimal: examples/minimal.c fogrt.h | $(BUILD)
	$(QCC)$(CC) $(ALL_CFLAGS) -o $@ examples/minimal.c $(LDLIBS)
# ... and as C++, as the README says it compiles (in make check-compile, with the other C++ builds)
$(BUILD)/minimal_cxx: examples/minimal.c fogrt.h | $(BUILD)
	$(QCC)$(CXX) -std=c++11 -Wall -Wextra -pedantic -Wshadow $(CFLAGS) $(OMPFLAGS) -I. -x c++ -o $@ examples/minimal.c $(LDLIBS)

# ---- tests ----
# Under SANITIZE=1 the test programs run reduced variants of their heaviest statistical loops
# (SAN_REDUCED in tests/test_util.h); the plain make test runs them at full size.
TEST_DEFS := $(if $(filter 1,$(SANITIZE)),-DFOGRT_TESTS_SANITIZE)
# unity.c (ours or the real one) is compiled once for every test program.
UNITY_OBJ := $(BUILD)/tests/unity$(if $(UNITY_DIR),_real).o
$(UNITY_OBJ): $(UNITY_SRC) | $(BUILD)
	$(QCC)$(CC) $(ALL_CFLAGS) $(UNITY_INC) -c -o $@ $(UNITY_SRC)

$(BUILD)/tests/%: tests/%.c fogrt.h $(wildcard fogrt_*.h) $(wildcard tests/*.h) $(UNITY_OBJ) | $(BUILD)
	$(QCC)$(CC) $(ALL_CFLAGS) $(UNITY_INC) $(TEST_DEFS) -DFOGRT_SHARED_DIR='"$(SHARED)"' -o $@ $< $(UNITY_OBJ) $(LDLIBS)

# A test program that uses the public API only says so by defining FOGRT_IMPLEMENTATION under
# #ifndef FOGRT_TESTS_SHARED_IMPL: it is linked with $(FOGRT_IMPL_OBJ). Programs that call
# fogrt__ internals, read the scene's struct or build fogrt.h with macros of their own
# (test_trace: FOGRT_TRACE) keep their own copy: fogrt__ functions are static, and their
# types and macros live in the implementation.
TEST_SHARED_IMPL := $(patsubst tests/%.c,$(BUILD)/tests/%,$(shell grep -l '^\#ifndef FOGRT_TESTS_SHARED_IMPL' $(TEST_SRCS)))
TEST_IMPL_OBJ := $(FOGRT_IMPL_OBJ)
$(FOGRT_IMPL_OBJ): fogrt.h | $(BUILD)
	@printf '#define FOGRT_IMPLEMENTATION\n#include "fogrt.h"\n' >$(BUILD)/fogrt_impl.c
	$(QCC)$(CC) $(ALL_CFLAGS) -c -o $@ $(BUILD)/fogrt_impl.c
$(TEST_SHARED_IMPL): $(BUILD)/tests/%: tests/%.c fogrt.h $(wildcard tests/*.h) $(UNITY_OBJ) $(TEST_IMPL_OBJ) | $(BUILD)
	$(QCC)$(CC) $(ALL_CFLAGS) $(UNITY_INC) $(TEST_DEFS) -DFOGRT_TESTS_SHARED_IMPL -DFOGRT_SHARED_DIR='"$(SHARED)"' -o $@ $< \
	  $(TEST_IMPL_OBJ) $(UNITY_OBJ) $(LDLIBS)

# Under SANITIZE=1 the programs that run for a few CPU seconds only are built at -O1: -O2
# would add more to their compile time than it takes off their run (test_bvh with its two
# bvh_paths objects: 57 against 22 CPU s to compile, 2 against 6 s to run).
SAN_O1_PROGRAMS := test_api test_bvh test_load test_sampling test_trace
ifeq ($(SANITIZE),1)
$(patsubst %,$(BUILD)/tests/%,$(SAN_O1_PROGRAMS)) $(BVH_PATHS_OBJS): private CFLAGS := $(patsubst -O2,-O1,$(CFLAGS))
endif

# Each program runs as soon as it is built, as many at a time as make runs jobs; its output
# goes to its log (run_tests.sh --run never fails, so one failing program stops nothing).
# Idle OpenMP threads sleep instead of spinning on a core that the program beside them needs.
$(addsuffix .log,$(TEST_BINS)): %.log: % FORCE
	@OMP_WAIT_POLICY=$${OMP_WAIT_POLICY:-passive} sh tests/run_tests.sh --run $@ $<

# The slowest programs start first (names from timing make test and make test SANITIZE=1,
# UNITY_CPU_TIMES=1 for the tests inside them; absent names are ignored), so that the others
# fill the remaining cores around them. test_cli.sh also waits on clocks (an interrupt, a
# progress log), which the programs beside it use.
TEST_FIRST := $(foreach t,test_cli.sh test_extremes test_render test_coursework test_furnace test_chroma test_convergence test_media test_scene,$(filter $(BUILD)/tests/$(t).log,$(TEST_LOGS)))

# `make test` runs itself again with -j<cores> unless a -j was given, builds and runs the
# programs in parallel, then reports them in a fixed order: one line each (the output of
# failing ones in full; V=1: everything), and last "N passed, M failed, K skipped".
# unity.o first, on its own: every program waits for it, and make would otherwise start them
# in whatever order they become ready instead of the slowest first.
test: deps-stb
	@case " $(MAKEFLAGS) " in *" -j"*) j= ;; *) j=-j$(NPROC) ;; esac; \
	  $(MAKE) -s --no-print-directory $(UNITY_OBJ) && $(MAKE) --no-print-directory $$j test-run

test-run: $(TEST_FIRST) $(filter-out $(TEST_FIRST),$(TEST_LOGS)) $(EXTRA_TEST_DEPS)
	@sh tests/run_tests.sh --report $(if $(filter 1,$(V)),-v) $(TEST_LOGS)

FORCE:

install: $(BUILD)/fogrt
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/include
	install -m 755 $(BUILD)/fogrt $(DESTDIR)$(PREFIX)/bin/fogrt
	install -m 644 fogrt.h fogrt_load.h $(DESTDIR)$(PREFIX)/include/

clean:
	rm -rf build build-san fog.png fog.pfm
