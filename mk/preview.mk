# mk/preview.mk - the interactive GLFW preview (examples/preview.c) and its test under Xvfb.
#   make preview        builds $(BUILD)/preview (GLFW 3 through pkg-config: Debian libglfw3-dev)
#   make test-preview   runs tests/test_preview.sh: the preview scripted under Xvfb with Mesa's
#                       software OpenGL (Debian xvfb, xauth, libgl1-mesa-dri)
# Packages are installed with apt-get when run as root, else one line names the package.
# Neither target is part of `all`, `run` or `test`: those never need GLFW or a display.
.PHONY: preview test-preview deps-glfw deps-xvfb

deps-glfw:
	@sh tools/need-package.sh pkg-config /usr/bin/pkg-config
	@sh tools/need-package.sh libglfw3-dev /usr/include/GLFW/glfw3.h

deps-xvfb:
	@sh tools/need-package.sh xvfb /usr/bin/xvfb-run
	@sh tools/need-package.sh xauth /usr/bin/xauth
	@sh tools/need-package.sh libgl1-mesa-dri /usr/share/doc/libgl1-mesa-dri/copyright

preview: $(BUILD)/preview

# pkg-config runs when the rule runs (after deps-glfw), never when the Makefile is read.
$(BUILD)/preview: examples/preview.c examples/cli_common.h fogrt.h fogrt_load.h mk/preview.mk | deps-stb deps-glfw $(BUILD)
	$(CC) $(ALL_CFLAGS) -pthread $$(pkg-config --cflags glfw3) -o $@ examples/preview.c \
	  $$(pkg-config --libs glfw3) $$(pkg-config --libs gl 2>/dev/null || echo -lGL) -pthread $(LDLIBS)

test-preview: $(BUILD)/preview | deps-xvfb
	@CC='$(CC)' BUILD='$(BUILD)' sh tests/test_preview.sh $(BUILD)/preview
