# mk/tutorial.mk - the numbered tutorial examples (examples/tutorial/NN_*.c, docs/tutorial.md).
#   make tutorial          builds every example into $(BUILD)/tutorial/, runs them one after
#                          the other (never in parallel: they use every core), and writes
#                          their images to docs/tutorial/NN_*.png and what they printed to
#                          $(BUILD)/tutorial/output.txt. The images carry only numbers that
#                          every run of one build repeats (fixed seeds: samples per pixel and
#                          errors), so a second run leaves git status clean; the transcript
#                          holds the times too, which vary, so it stays in $(BUILD).
#   make tutorial-build    only builds them.
# Each example runs alone too: ./$(BUILD)/tutorial/06_hg_phase out.png 128
.PHONY: tutorial tutorial-build

TUTORIAL_SRCS := $(sort $(wildcard examples/tutorial/[0-9][0-9]_*.c))
TUTORIAL_BINS := $(patsubst examples/tutorial/%.c,$(BUILD)/tutorial/%,$(TUTORIAL_SRCS))
TUTORIAL_OUT  ?= docs/tutorial

# Each example defines FOGRT_IMPLEMENTATION, so that it builds alone; here it is compiled with
# fogrt.h's implementation guard (FOGRT_IMPLEMENTATION_INCLUDED) already set, which leaves the
# implementation out, and linked with the one build of it the tests share ($(FOGRT_IMPL_OBJ)):
# the examples use the public API alone.
$(BUILD)/tutorial/%: examples/tutorial/%.c examples/tutorial/tutorial.h examples/plotfont.h fogrt.h $(FOGRT_IMPL_OBJ) | deps-stb $(BUILD)
	@mkdir -p $(BUILD)/tutorial
	$(QCC)$(CC) $(ALL_CFLAGS) -DFOGRT_IMPLEMENTATION_INCLUDED -Iexamples/tutorial -o $@ $< $(FOGRT_IMPL_OBJ) $(LDLIBS)

tutorial-build: $(TUTORIAL_BINS)

# One shell, so the transcript and the total time cover every example in order; the first
# example that fails stops the run with its exit status.
tutorial: $(TUTORIAL_BINS)
	@mkdir -p $(TUTORIAL_OUT)
	@start=$$(date +%s); : > $(BUILD)/tutorial/output.txt; \
	for bin in $(TUTORIAL_BINS); do \
	  name=$$(basename $$bin); \
	  echo "== $$name" | tee -a $(BUILD)/tutorial/output.txt; \
	  ./$$bin $(TUTORIAL_OUT)/$$name.png > $(BUILD)/tutorial/$$name.log 2>&1; status=$$?; \
	  tee -a $(BUILD)/tutorial/output.txt < $(BUILD)/tutorial/$$name.log; \
	  [ $$status = 0 ] || { echo "tutorial: $$name failed (exit $$status)" >&2; exit $$status; }; \
	done; \
	echo "== all examples: $$(( $$(date +%s) - start )) s" | tee -a $(BUILD)/tutorial/output.txt; \
	echo "tutorial: images in $(TUTORIAL_OUT)/, transcript in $(BUILD)/tutorial/output.txt"
