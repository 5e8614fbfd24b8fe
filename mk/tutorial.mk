# mk/tutorial.mk - the numbered tutorial examples (examples/tutorial/NN_*.c, docs/tutorial.md).
#   make tutorial          builds every example into $(BUILD)/tutorial/, runs them one after
#                          the other (never in parallel: they use every core), and writes
#                          their images to docs/tutorial/NN_*.png and what they printed to
#                          docs/tutorial/output.txt (the numbers docs/tutorial.md quotes).
#   make tutorial-build    only builds them.
# Each example runs alone too: ./$(BUILD)/tutorial/06_hg_phase out.png 128
.PHONY: tutorial tutorial-build

TUTORIAL_SRCS := $(sort $(wildcard examples/tutorial/[0-9][0-9]_*.c))
TUTORIAL_BINS := $(patsubst examples/tutorial/%.c,$(BUILD)/tutorial/%,$(TUTORIAL_SRCS))
TUTORIAL_OUT  ?= docs/tutorial

$(BUILD)/tutorial/%: examples/tutorial/%.c examples/tutorial/tutorial.h fogrt.h | deps-stb $(BUILD)
	@mkdir -p $(BUILD)/tutorial
	$(CC) $(ALL_CFLAGS) -Iexamples/tutorial -o $@ $< $(LDLIBS)

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
	cp $(BUILD)/tutorial/output.txt $(TUTORIAL_OUT)/output.txt
