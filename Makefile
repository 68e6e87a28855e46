# cumulo build: `make` builds everything, `make demo` renders the default scene, `make check` runs every test.
# Each part of the tree adds its own targets through an included fragment (*.mk) so that modules stay independent.

CC      ?= cc
B       := build
WERROR  ?= -Werror
OPT     ?= -O2
CFLAGS_COMMON := -std=c99 -D_POSIX_C_SOURCE=200809L -Wall -Wextra -Wpedantic $(WERROR) $(OPT) -g \
                 -Isrc -I$(B)/gen -MMD -MP
LDLIBS_COMMON := -lm -lpthread

# pkg-config is used for every library; a missing one is reported by `make deps-check`.
PKG := pkg-config
pc_cflags = $(shell $(PKG) --cflags $(1) 2>/dev/null)
pc_libs   = $(shell $(PKG) --libs $(1) 2>/dev/null)

# The environment every test and render runs in: software GL, reproducible thread count.
TEST_ENV := LIBGL_ALWAYS_SOFTWARE=1 GALLIUM_DRIVER=llvmpipe LP_NUM_THREADS=2 MESA_DEBUG=silent \
            EGL_LOG_LEVEL=fatal

PREFIX ?= /usr/local

# Filled by the fragments below.
ALL_BINS    :=
CHECK_TESTS :=

.PHONY: all check demo deps deps-check bench sweep stress clean install
all:

include mk/deps.mk
include platform/platform.mk
include src/engine.mk
include tools/mie/mie.mk
include tools/slab/slab.mk
include tools/pathtrace/pathtrace.mk
include tests/tests.mk
include tests/vm/vm.mk
include mk/sweep.mk

all: $(ALL_BINS)

# The README's test command: builds everything, runs every test binary, prints "N passed, N failed".
check: deps-check all $(CHECK_TESTS)
	@$(TEST_ENV) sh tests/run_tests.sh $(CHECK_TESTS)

demo: deps-check $(B)/cumulo
	@$(TEST_ENV) $(B)/cumulo render scenes/cumulus.scene -o $(B)/demo.png
	@echo "demo: wrote $(B)/demo.png"

clean:
	rm -rf $(B)

install: all
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/share/cumulo/scenes $(DESTDIR)$(PREFIX)/share/cumulo/data
	install -m 755 $(ALL_BINS) $(DESTDIR)$(PREFIX)/bin/
	install -m 644 scenes/*.scene $(DESTDIR)$(PREFIX)/share/cumulo/scenes/
	-install -m 644 data/* $(DESTDIR)$(PREFIX)/share/cumulo/data/

# dependency files of our own objects (build/vm holds a kernel tree with its own *.d, which are not ours)
-include $(shell find $(B) -path $(B)/vm -prune -o -type f -name '*.d' -print 2>/dev/null)
