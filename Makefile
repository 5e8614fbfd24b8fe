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
ifeq ($(SANITIZE),1)
BUILD   := build-san
CFLAGS  := -O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=undefined
endif

# Unity: the real one when UNITY_DIR is given, else the small compatible runner in tests/runner.
ifdef UNITY_DIR
UNITY_INC := -I$(UNITY_DIR) -DUNITY_INCLUDE_DOUBLE
UNITY_SRC := $(UNITY_DIR)/unity.c
else
UNITY_INC := -Itests/runner
UNITY_SRC := tests/runner/unity.c
endif

.PHONY: all run test bench install clean deps-stb check-compile
all: $(BUILD)/fogrt

# ---- system packages: installed with apt-get when root, else one line naming the package ----
STB_HEADER := /usr/include/stb/stb_image_write.h
deps-stb:
	@sh tools/need-package.sh libstb-dev $(STB_HEADER)

# ---- the command-line renderer and the default-scene example ----
$(BUILD):
	@mkdir -p $(BUILD)/tests

-include mk/*.mk

run: deps-stb $(BUILD)/render_default
	./$(BUILD)/render_default fog.png fog.pfm

$(BUILD)/render_default: examples/render_default.c fogrt.h | $(BUILD)
	$(CC) $(ALL_CFLAGS) -o $@ examples/render_default.c $(LDLIBS)

# ---- the README's program must keep compiling ----
$(BUILD)/minimal: examples/minimal.c fogrt.h | $(BUILD)
	$(CC) $(ALL_CFLAGS) -o $@ examples/minimal.c $(LDLIBS)
EXTRA_TEST_DEPS += $(BUILD)/minimal
# ... as C++ too, as the README says it does
$(BUILD)/minimal_cxx: examples/minimal.c fogrt.h | $(BUILD)
	$(CXX) -std=c++11 -Wall -Wextra -pedantic -Wshadow $(CFLAGS) $(OMPFLAGS) -I. -x c++ -o $@ examples/minimal.c $(LDLIBS)
EXTRA_TEST_DEPS += $(BUILD)/minimal_cxx

# ---- tests: every tests/test_*.c is one Unity test program ----
TEST_SRCS := $(wildcard tests/test_*.c)
TEST_BINS := $(patsubst tests/%.c,$(BUILD)/tests/%,$(TEST_SRCS))

$(BUILD)/tests/%: tests/%.c fogrt.h $(wildcard fogrt_*.h) $(wildcard tests/*.h) $(UNITY_SRC) | $(BUILD)
	$(CC) $(ALL_CFLAGS) $(UNITY_INC) -DFOGRT_SHARED_DIR='"$(SHARED)"' -o $@ $< $(UNITY_SRC) $(LDLIBS)

test: deps-stb $(TEST_BINS) $(EXTRA_TEST_DEPS)
	@sh tests/run_tests.sh $(TEST_BINS)

install: $(BUILD)/fogrt
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/include
	install -m 755 $(BUILD)/fogrt $(DESTDIR)$(PREFIX)/bin/fogrt
	install -m 644 fogrt.h fogrt_load.h $(DESTDIR)$(PREFIX)/include/

clean:
	rm -rf build build-san fog.png fog.pfm
