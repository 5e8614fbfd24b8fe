# mk/convergence.mk - error against render time for several estimators (docs/benchmarks.md).
#   make convergence     renders the default scene with 6 estimator configurations on a spp
#                        ladder, measures each against one reference, and writes the data
#                        $(BUILD)/convergence/default.csv and its plot default.svg (about 2 CPU
#                        minutes: 1 to 4 minutes, by load)
#   make convergence CONVERGENCE_ARGS="--scene $(SHARED)/scenes/cs184/CBbunny_upSpot.dae"
#   make convergence CONVERGENCE_ARGS="--reference REF.pfm --size 320 240 --seconds 60"
#   make convergence-png  draws every $(BUILD)/convergence/<scene>.svg again from its .csv
#                        (no rendering: `convergence --replot`; `make convergence` runs first
#                        only when there is no data yet) and screenshots it with headless
#                        chromium (Debian chromium, installed when root) into <scene>.png
# The reference (a long path NEE+MIS render) is cached in $(BUILD)/convergence/ as
# <scene>_<W>x<H>_ref.pfm with its per-pixel variance in <scene>_<W>x<H>_ref_var.pfm; it is
# rendered again when fogrt.h is newer than it. See examples/convergence.c.
.PHONY: convergence convergence-png
CONVERGENCE_ARGS ?=
CONVERGENCE_DIR  := $(BUILD)/convergence

$(BUILD)/bin/convergence: examples/convergence.c examples/svgplot.h examples/plotfont.h fogrt.h fogrt_load.h mk/convergence.mk | $(BUILD)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) -Iexamples -o $@ examples/convergence.c $(LDLIBS)

convergence: $(BUILD)/bin/convergence
	@mkdir -p $(CONVERGENCE_DIR)
	@find $(CONVERGENCE_DIR) -name '*_ref*.pfm' ! -newer fogrt.h -exec rm -f {} + 2>/dev/null || true
	./$(BUILD)/bin/convergence --out $(CONVERGENCE_DIR) $(CONVERGENCE_ARGS)

convergence-png: $(BUILD)/bin/convergence
	@ls $(CONVERGENCE_DIR)/*.csv >/dev/null 2>&1 || $(MAKE) --no-print-directory convergence
	@sh tools/need-package.sh chromium /usr/bin/chromium
	@for csv in $(CONVERGENCE_DIR)/*.csv; do \
	  ./$(BUILD)/bin/convergence --replot "$$csv" >/dev/null || exit 1; \
	  f="$${csv%.csv}.svg"; \
	  chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --screenshot="$${f%.svg}.png" \
	    --window-size=$$(sed -n 's/.*<svg[^>]* width="\([0-9]*\)" height="\([0-9]*\)".*/\1,\2/p' "$$f") \
	    "file://$$(cd "$$(dirname "$$f")" && pwd)/$$(basename "$$f")" >/dev/null 2>&1 && echo "wrote $${f%.svg}.png"; \
	done
