# mk/coursework.mk - the coursework kit (examples/coursework/, docs/coursework.md).
#   make check-step STEP=N               judges examples/coursework/stepN_*.c (the skeleton
#                                        a student fills in); SRC=path/to/their.c judges
#                                        another file. One line per check; the pictures go
#                                        to $(BUILD)/coursework/. Exit status 1 if a check fails.
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

check-step:
	@[ -n "$(filter $(COURSEWORK_STEPS),$(STEP))" ] || { echo "usage: make check-step STEP=N [SRC=path/to/your.c]  (steps: $(COURSEWORK_STEPS))"; exit 2; }
	@$(MAKE) --no-print-directory $(BUILD)/coursework/check_step$(STEP).o
	@src="$(if $(SRC),$(SRC),$(wildcard $(CW_DIR)/step$(STEP)_*.c))"; \
	[ -n "$$src" ] && [ -f "$$src" ] || { echo "check-step: no source for step $(STEP) (SRC=$(SRC))"; exit 2; }; \
	$(CC) $(ALL_CFLAGS) -I$(CW_DIR) -o $(BUILD)/coursework/step$(STEP) $(BUILD)/coursework/check_step$(STEP).o "$$src" $(LDLIBS) \
	  || { echo "check-step: $$src does not compile against examples/coursework/coursework.h"; exit 2; }; \
	OMP_WAIT_POLICY=$${OMP_WAIT_POLICY:-passive} $(CW_TIMEOUT) ./$(BUILD)/coursework/step$(STEP) $(BUILD)/coursework

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
