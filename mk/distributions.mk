# mk/distributions.mk - the suite's distribution checks as pictures (docs/distributions.md).
#   make distributions        builds tests/distributions.c (it reuses tests/stats.h), runs it,
#                             and writes docs/distributions/*.png and the results section of
#                             docs/distributions.md (between its BEGIN/END generated markers).
#   make distributions-check  the same checks, written under $(BUILD)/distributions-check/
#                             instead (docs/ untouched): for CI. Both fail (exit 1) when a
#                             positive check is rejected or a negative control is not.
# Fixed seeds: the same build writes the same images and numbers, so a second run on an
# unchanged tree leaves git status clean (alpha' follows the suite's test count, so adding a
# statistical test changes every caption: run it again then). Takes a few seconds.
.PHONY: distributions distributions-check
DISTRIBUTIONS_OUT ?= docs/distributions

$(BUILD)/distributions: tests/distributions.c tests/stats.h examples/plotfont.h fogrt.h | deps-stb $(BUILD)
	$(CC) $(ALL_CFLAGS) -Itests -o $@ tests/distributions.c $(LDLIBS)

distributions: $(BUILD)/distributions
	@mkdir -p $(DISTRIBUTIONS_OUT)
	./$(BUILD)/distributions $(DISTRIBUTIONS_OUT) docs/distributions.md

distributions-check: $(BUILD)/distributions
	@mkdir -p $(BUILD)/distributions-check
	@cp docs/distributions.md $(BUILD)/distributions-check/distributions.md
	./$(BUILD)/distributions $(BUILD)/distributions-check $(BUILD)/distributions-check/distributions.md
