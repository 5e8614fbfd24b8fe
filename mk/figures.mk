# mk/figures.mk - the paper's experiments with numbers.
#   make figures    writes $(BUILD)/figures/*.png and *.svg and $(BUILD)/figures/experiments.md
#                   (about 10 minutes on 2 cores); uses $(SHARED)/scenes/cs184/CBbunny_upSpot.dae
#                   when present (else those panels are skipped with a message)
#   make figures FIGURES_ARGS=--quick          a quarter of the samples (a smoke run)
#   make figures FIGURES_ARGS="--only fig4"    one experiment (fig2 fig3 fig4 equiangular bvh fresnel)
#   make figures-docs  the same run with its images in docs/figures/ (committed: the PNGs are
#                   the same on every run of one build, their captions hold no times; the
#                   equiangular plot's times vary) and its report, which holds CPU times, in
#                   $(BUILD)/experiments.md. Run it on purpose after a change that alters the
#                   images, and commit them.
.PHONY: figures figures-docs
FIGURES_ARGS ?=
FIGURES_OUT  ?= $(BUILD)/figures
FIGURES_DOC  ?= $(FIGURES_OUT)/experiments.md

$(BUILD)/bin/figures: examples/figures.c examples/svgplot.h examples/plotfont.h fogrt.h fogrt_load.h mk/figures.mk | deps-stb $(BUILD)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) -Iexamples -o $@ examples/figures.c $(LDLIBS)

figures: $(BUILD)/bin/figures
	@mkdir -p $(FIGURES_OUT)
	@# a full run starts clean; --only (a part) writes its report to $(BUILD)/experiments-partial.md
	@case "$(FIGURES_ARGS)" in *--only*) ;; *) rm -f $(FIGURES_OUT)/fig*.png $(FIGURES_OUT)/fig*.svg $(FIGURES_OUT)/beyond_*.png $(FIGURES_OUT)/beyond_*.svg ;; esac
	./$(BUILD)/bin/figures --out $(FIGURES_OUT) --shared $(SHARED) \
	  --doc $$(case "$(FIGURES_ARGS)" in *--only*) echo $(BUILD)/experiments-partial.md ;; *) echo $(FIGURES_DOC) ;; esac) $(FIGURES_ARGS)

figures-docs:
	@$(MAKE) --no-print-directory figures FIGURES_OUT=docs/figures FIGURES_DOC=$(BUILD)/experiments.md
