# mk/docs.mk - make check-docs: what README.md and docs/ say, checked against the tree
# (tools/check_docs.sh): README's C code compiled and run as a user copies it, every field of
# the descriptions a user fills documented, the names, files and scene lists the docs cite
# present, no line numbers or counts in prose that move. Part of make test (about 10 CPU
# seconds, most of them compiling README's program), except under SANITIZE=1 and MINIMAL=1,
# whose builds it does not use.
.PHONY: check-docs
check-docs: deps-stb | $(BUILD)
	@sh tools/check_docs.sh '$(CC)' $(BUILD)

ifeq ($(SANITIZE)$(MINIMAL),)
$(BUILD)/tests/check_docs.log: FORCE | deps-stb $(BUILD)
	@OMP_WAIT_POLICY=$${OMP_WAIT_POLICY:-passive} sh tests/run_tests.sh --run $@ sh tools/check_docs.sh '$(CC)' $(BUILD)
TEST_LOGS += $(BUILD)/tests/check_docs.log
endif

# make check-regenerate: the committed outputs are what the code makes. make distributions and
# make tutorial write docs/distributions.md, docs/distributions/ and docs/tutorial/ from this
# tree at fixed seeds; run on a checkout without changes they must leave `git status
# --porcelain` empty (CI runs it; about a minute on two cores). make figures writes only under
# $(BUILD) (make figures-docs, run on purpose, rewrites docs/figures/).
.PHONY: check-regenerate
check-regenerate: | $(BUILD)
	@command -v git >/dev/null && git rev-parse --is-inside-work-tree >/dev/null 2>&1 || \
	  { echo "check-regenerate: not a git checkout: nothing to compare with"; exit 2; }
	@[ -z "$$(git status --porcelain)" ] || \
	  { echo "check-regenerate: the checkout has changes already (git status --porcelain): run it on a clean one"; exit 2; }
	@$(MAKE) --no-print-directory distributions >$(BUILD)/check-regenerate.log 2>&1 && \
	  $(MAKE) --no-print-directory tutorial >>$(BUILD)/check-regenerate.log 2>&1 || \
	  { tail -5 $(BUILD)/check-regenerate.log; echo "check-regenerate: make distributions or make tutorial failed ($(BUILD)/check-regenerate.log)"; exit 1; }
	@changed=$$(git status --porcelain); [ -z "$$changed" ] || \
	  { echo "check-regenerate: make distributions and make tutorial changed tracked files (regenerate and commit them):"; \
	    echo "$$changed" | sed 's/^/    /'; exit 1; }
	@echo "check-regenerate: make distributions and make tutorial leave every tracked file as it was"
