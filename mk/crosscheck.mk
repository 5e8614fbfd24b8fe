# mk/crosscheck.mk - fogrt against Mitsuba 3 on the same scenes (docs/validation.md).
#   make crosscheck                   all scenes, about 24 s per renderer per scene (about 7 min)
#   make crosscheck CROSSCHECK_ARGS=--quick                 a 1-minute smoke run (no measurement)
#   make crosscheck CROSSCHECK_ARGS="--scenes fog_iso,spot_fog"
#   make crosscheck CROSSCHECK_FOGRT=path/to/fogrt          another fogrt build
#   make crosscheck CROSSCHECK_ARGS="--scenes chroma_spot --mitsuba-long 300"   and Mitsuba alone
#                                     for 300 s more per scene, a longer estimate of its mean
# Optional, never part of `make test`. tests/crosscheck/crosscheck.py makes its own virtual
# environment ($(BUILD)/crosscheck-venv, `pip install mitsuba numpy`) and writes
# $(BUILD)/crosscheck/results.md, results.json and <scene>_side.png. Mitsuba's fast
# llvm_ad_rgb variant needs LLVM >= 16: Debian's libllvm19 is installed when we are root;
# without it the script falls back to the scalar_rgb variant and says so.
#   make bench-mitsuba                the same run, read as a benchmark (docs/benchmarks.md): it ends with
#                                     relMSE x CPU seconds of both renderers and their ratio
#   make bench-mitsuba MITSUBA_BASE=<commit>   also that commit's fogrt (built from its tree by
#                                     bench/base_build.sh), after this one on every scene of the
#                                     same run, and the two builds' equal-time ratio at the end
#   make chi2-mitsuba                 fogrt's direction samplers in Mitsuba's own chi-square
#                                     harness, Mitsuba's samplers beside them (docs/testing.md;
#                                     about 30 s; writes $(BUILD)/chi2-mitsuba/results.md)
.PHONY: crosscheck crosscheck-deps bench-mitsuba chi2-mitsuba
CROSSCHECK_ARGS ?=
CROSSCHECK_FOGRT ?= $(BUILD)/fogrt
CROSSCHECK_LLVM := /usr/lib/x86_64-linux-gnu/libLLVM.so.19.1

crosscheck-deps:
	@sh tools/need-package.sh libllvm19 $(CROSSCHECK_LLVM) || \
	  echo "crosscheck: no libllvm19: Mitsuba will use its slower scalar_rgb variant" >&2

crosscheck: $(CROSSCHECK_FOGRT) crosscheck-deps
	python3 tests/crosscheck/crosscheck.py --fogrt $(CROSSCHECK_FOGRT) --out $(BUILD)/crosscheck \
	  --venv $(BUILD)/crosscheck-venv $(CROSSCHECK_ARGS)

MITSUBA_BASE ?=
bench-mitsuba: $(CROSSCHECK_FOGRT) crosscheck-deps
	@base=""; if [ -n "$(MITSUBA_BASE)" ]; then base=$$(sh bench/base_build.sh $(MITSUBA_BASE) build/fogrt $(SHARED)) || exit 2; fi; \
	python3 tests/crosscheck/crosscheck.py --fogrt $(CROSSCHECK_FOGRT) --out $(BUILD)/crosscheck \
	  --venv $(BUILD)/crosscheck-venv $${base:+--fogrt-base $$base} $(CROSSCHECK_ARGS)

chi2-mitsuba: crosscheck-deps
	python3 tests/crosscheck/chi2_mitsuba.py --out $(BUILD)/chi2-mitsuba --venv $(BUILD)/crosscheck-venv --cc $(CC)
