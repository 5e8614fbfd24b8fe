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
