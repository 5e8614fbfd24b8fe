# mk/convergence.mk - error against render time for several estimators (issue 11, point 3).
#   make convergence     renders the default scene with 6 estimator configurations on a spp
#                        ladder, measures each against one reference, and writes
#                        $(BUILD)/convergence/default.csv and default.svg (about 2 CPU minutes: 1 to 4 minutes, by load)
#   make convergence CONVERGENCE_ARGS="--scene $(SHARED)/scenes/cs184/CBbunny_upSpot.dae"
#   make convergence CONVERGENCE_ARGS="--reference REF.pfm --size 320 240 --seconds 60"
#   make convergence-png  also screenshots the SVG with headless chromium (Debian chromium,
#                        installed when root) into $(BUILD)/convergence/<scene>.png
# The reference (a long path NEE+MIS render) is cached in $(BUILD)/convergence/ as
# <scene>_<W>x<H>_ref.pfm with its per-pixel variance in <scene>_<W>x<H>_ref_var.pfm; it is
# rendered again when fogrt.h is newer than it. See examples/convergence.c.
.PHONY: convergence convergence-png
CONVERGENCE_ARGS ?=
CONVERGENCE_DIR  := $(BUILD)/convergence

$(BUILD)/bin/convergence: examples/convergence.c examples/svgplot.h fogrt.h fogrt_load.h mk/convergence.mk | $(BUILD)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) -Iexamples -o $@ examples/convergence.c $(LDLIBS)

convergence: $(BUILD)/bin/convergence
	@mkdir -p $(CONVERGENCE_DIR)
	@find $(CONVERGENCE_DIR) -name '*_ref*.pfm' ! -newer fogrt.h -exec rm -f {} + 2>/dev/null || true
	./$(BUILD)/bin/convergence --out $(CONVERGENCE_DIR) $(CONVERGENCE_ARGS)

convergence-png: convergence
	@sh tools/need-package.sh chromium /usr/bin/chromium
	@for f in $(CONVERGENCE_DIR)/*.svg; do \
	  chromium --headless --no-sandbox --disable-gpu --screenshot="$${f%.svg}.png" --window-size=900,650 \
	    "file://$$(cd "$$(dirname "$$f")" && pwd)/$$(basename "$$f")" >/dev/null 2>&1 && echo "wrote $${f%.svg}.png"; \
	done
