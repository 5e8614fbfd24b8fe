# mk/compile.mk - `make check-compile`: fogrt.h compiles warning-free (-Werror) with gcc and
# clang (if installed) as C99, as C++11, without OpenMP, as FOGRT_STATIC, and with every
# combination of the FOGRT_NO_* strip macros. See tests/compile_check.sh.
# Also builds the README's examples/minimal.c as C++ ($(BUILD)/minimal_cxx; make test's check-docs builds it as C).
check-compile: $(BUILD)/minimal_cxx
	@sh tests/compile_check.sh

# The size of each region of fogrt.h's implementation (Part I, Part II's appendices, the API
# after both), in lines and code lines, then Part I's formatting rules checked (at most 2,600
# lines, none over 100 columns, one statement per line, at most 8 seams); check-compile runs
# the same check.
.PHONY: part-sizes
part-sizes:
	@sh tools/part_sizes.sh --check

# The headers' functions stay small: fogrt.h none over 60 lines or cyclomatic complexity 20,
# fogrt_load.h none over 100 lines (lizard, from PyPI into build/lint-venv when not on PATH).
.PHONY: check-limits
check-limits:
	@sh tools/check_limits.sh
