# mk/coursework.mk - the coursework kit (examples/coursework/, docs/coursework.md).
#   make check-step STEP=N               judges examples/coursework/stepN_*.c (the skeleton
#                                        a student fills in); SRC=path/to/their.c judges
#                                        another file; SEED=K redraws every sampled check
#                                        (the verdicts the kit gives use 0). One line per
#                                        check; the pictures go to $(BUILD)/coursework/.
#                                        Exit status 0: every check passed; 1: a check
#                                        failed; 2: the file does not compile (or no STEP).
#   make coursework-solutions            runs every step's checks on the reference solutions
#                                        (examples/coursework/solutions/) and prints one table.
# Steps 6-8 render with fogrt_render on every OpenMP thread; idle threads sleep instead of
# spinning (OMP_WAIT_POLICY=passive), so the CPU time a check reports is the work it did.
# The checker (examples/coursework/check_step.c with fogrt's implementation) is compiled once
# per step into an object; the student's file is compiled and linked with it on every run.
.PHONY: check-step coursework-solutions
COURSEWORK_STEPS := 1 2 3 4 5 6 7 8 9
CW_DIR := examples/coursework
# A student's endless loop stops after two minutes (a step's checks take at most a few seconds).
CW_TIMEOUT := $(shell command -v timeout >/dev/null 2>&1 && echo timeout 120)
CW_DEPS := $(CW_DIR)/check_step.c $(CW_DIR)/check.h $(CW_DIR)/coursework.h fogrt.h tests/stats.h examples/plotfont.h examples/stb_write.h

$(BUILD)/coursework/check_step%.o: $(CW_DEPS) | deps-stb $(BUILD)
	@mkdir -p $(BUILD)/coursework
	$(CC) $(ALL_CFLAGS) -DCW_STEP=$* -I$(CW_DIR) -c -o $@ $(CW_DIR)/check_step.c

# make exits with 2 whenever a recipe fails, whatever the recipe's status, so a failed check
# and a file that does not compile could not be told apart by a recipe. `make check-step`
# therefore judges while the makefile is read: the build and the checker run in $(shell),
# their lines go to the terminal on stderr as they come, and the status decides how make
# ends: 0 runs an empty recipe, 1 turns on -q (make then exits with 1 for the phony goal
# without running anything), 2 lets the recipe fail.
ifeq ($(MAKECMDGOALS),check-step)
CW_PASS_VARS := $(foreach v,CC CFLAGS BUILD OPENMP SANITIZE MINIMAL,$(if $(filter command line,$(origin $(v))),'$(v)=$($(v))'))
CW_SRC := $(if $(SRC),$(SRC),$(wildcard $(CW_DIR)/step$(STEP)_*.c))
CW_STATUS := $(strip $(shell ( \
  exec >&2; \
  [ -n "$(filter $(COURSEWORK_STEPS),$(STEP))" ] || { echo "usage: make check-step STEP=N [SRC=path/to/your.c] [SEED=K]  (steps: $(COURSEWORK_STEPS))"; exit 2; }; \
  [ -n "$(CW_SRC)" ] && [ -f "$(CW_SRC)" ] || { echo "check-step: no source for step $(STEP) (SRC=$(SRC))"; exit 2; }; \
  $(MAKE) --no-print-directory $(CW_PASS_VARS) $(BUILD)/coursework/check_step$(STEP).o || exit 2; \
  $(CC) $(ALL_CFLAGS) -I$(CW_DIR) -o $(BUILD)/coursework/step$(STEP) $(BUILD)/coursework/check_step$(STEP).o "$(CW_SRC)" $(LDLIBS) \
    || { echo "check-step: $(CW_SRC) does not compile against examples/coursework/coursework.h"; exit 2; }; \
  CW_SOURCE="$(CW_SRC)" OMP_WAIT_POLICY=$${OMP_WAIT_POLICY:-passive} $(CW_TIMEOUT) ./$(BUILD)/coursework/step$(STEP) \
    $(BUILD)/coursework $(SEED) || exit 1 \
  ); echo $$?))
ifeq ($(CW_STATUS),1)
MAKEFLAGS += -q
endif
endif

check-step:
	@[ "$(CW_STATUS)" = 0 ] || exit 2

coursework-solutions: $(foreach s,$(COURSEWORK_STEPS),$(BUILD)/coursework/check_step$(s).o)
	@mkdir -p $(BUILD)/coursework/solutions
	@status=0; printf '%-6s %-74s %-8s %s\n' step "what" checks time; \
	for s in $(COURSEWORK_STEPS); do \
	  src=$$(ls $(CW_DIR)/solutions/step$${s}_*.c); \
	  $(CC) $(ALL_CFLAGS) -I$(CW_DIR) -o $(BUILD)/coursework/solution$$s $(BUILD)/coursework/check_step$$s.o $$src $(LDLIBS) || exit 1; \
	  OMP_WAIT_POLICY=$${OMP_WAIT_POLICY:-passive} ./$(BUILD)/coursework/solution$$s $(BUILD)/coursework/solutions > $(BUILD)/coursework/solution$$s.log 2>&1 || status=1; \
	  title=$$(sed -n '1s/^step [0-9]*: //p' $(BUILD)/coursework/solution$$s.log); \
	  summary=$$(sed -n 's/^step [0-9]*: \([0-9]*\) of \([0-9]*\) checks passed in \([0-9.]*\) s.*/\1\/\2 \3/p' $(BUILD)/coursework/solution$$s.log); \
	  printf '%-6s %-74s %-8s %s s\n' $$s "$$title" $${summary% *} $${summary#* }; \
	done; \
	[ $$status = 0 ] && echo "every check passed (logs: $(BUILD)/coursework/solution*.log, pictures: $(BUILD)/coursework/solutions/)" \
	  || { echo "coursework-solutions: a reference failed a check; see $(BUILD)/coursework/solution*.log"; exit 1; }

# tests/test_coursework.c includes the checker, the reference solutions, the skeletons and the
# wrong solutions: rebuild it when any of them changes.
$(BUILD)/tests/test_coursework: $(CW_DIR)/check.h $(CW_DIR)/coursework.h $(wildcard $(CW_DIR)/step*.c) \
  $(wildcard $(CW_DIR)/solutions/*.c) $(wildcard tests/coursework/wrong/*.c) examples/plotfont.h
