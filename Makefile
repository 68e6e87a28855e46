# cumulo build: `make` builds the library, the programs and the tools; `make demo` renders the default scene;
# `make check` runs every test; `make install` / `make uninstall` (PREFIX, LIBDIR, DESTDIR).
#
# Configuration is a dependency (git's GIT-CFLAGS, kmscube's meson features): every invocation first makes sure the
# packages are there (mk/deps.mk), then runs ./configure, which rewrites $(B)/config.mk, $(B)/gen/config.h and
# $(B)/gen/lib/paths.h only when their content changes. make re-reads a changed config.mk before building anything,
# and the objects that read a changed header, or whose flags changed, are rebuilt. Each part of the tree adds its
# targets through its own fragment (*.mk).

, := ,
CC      ?= cc
AR      ?= ar
B       ?= build
WERROR  ?= -Werror
OPT     ?= -O2
PKG_CONFIG ?= pkg-config
export PKG_CONFIG

# What ./configure is asked for; `yes` makes a missing back end a configure-time error, `no` leaves it out.
PREFIX     ?= /usr/local
LIBDIR     ?= $(PREFIX)/lib
DATADIR    ?= $(PREFIX)/share
MANDIR     ?= $(DATADIR)/man
SYSCONFDIR ?= $(if $(filter /usr,$(PREFIX)),/etc,$(PREFIX)/etc)
WITH_DRM     ?= auto
WITH_X11     ?= auto
WITH_WAYLAND ?= auto
WITH_GPIO    ?= auto
WITH_OSMESA  ?= auto

VERSION := $(shell cat VERSION)
SOVERSION := 0

CFLAGS_BASE := -std=c99 -D_POSIX_C_SOURCE=200809L -Wall -Wextra -Wpedantic $(WERROR) $(OPT) -g -MMD -MP $(CFLAGS)

# The environment every test and render runs in: software GL, reproducible thread count, the source tree's tables.
TEST_ENV := LIBGL_ALWAYS_SOFTWARE=1 GALLIUM_DRIVER=llvmpipe LP_NUM_THREADS=2 MESA_DEBUG=silent \
            EGL_LOG_LEVEL=fatal CUMULO_DATA_DIR=$(CURDIR)/data B=$(B)

# Filled by the fragments below.
ALL_BINS    :=
CHECK_TESTS :=

.PHONY: all check demo clean install uninstall sweep stress help sky-strip bench-sky FORCE
all:

# Goals that need no configuration (and so install nothing and probe nothing).
NO_CONFIG_GOALS := clean sanitize deps deps-test deps-vm deps-fuzz deps-plots deps-all uninstall help
CONFIGURED := $(if $(MAKECMDGOALS),$(filter-out $(NO_CONFIG_GOALS),$(MAKECMDGOALS)),all)

include mk/deps.mk
include mk/sanitize.mk

ifneq ($(CONFIGURED),)
CONFIGURE_ARGS := --builddir=$(B) --prefix=$(PREFIX) --libdir=$(LIBDIR) --datadir=$(DATADIR) --mandir=$(MANDIR) \
                  --sysconfdir=$(SYSCONFDIR) --with-drm=$(WITH_DRM) --with-x11=$(WITH_X11) \
                  --with-wayland=$(WITH_WAYLAND) --with-gpio=$(WITH_GPIO) --with-osmesa=$(WITH_OSMESA)
# Always run: the packages first (a no-op when they are there), then configure (replaces files only on change).
$(B)/config.mk: FORCE
	@$(DEPS_ENSURE_BUILD)
	@$(if $(filter check stress vmcheck test-%,$(MAKECMDGOALS)),$(DEPS_ENSURE_TEST))
	@$(if $(filter fuzz fuzz-%,$(MAKECMDGOALS)),$(DEPS_ENSURE_FUZZ))
	@sh ./configure --quiet $(CONFIGURE_ARGS)
include $(B)/config.mk
endif

# Flags files: one per component, rewritten only when the flags change, so objects depend on their flags.
# $(eval $(call flags_rule,NAME,FLAGS)): build/flags/NAME holds FLAGS; objects of that part depend on it.
define flags_rule
$(B)/flags/$(1): FORCE
	@mkdir -p $$(@D); printf '%s\n' '$$(subst ','"'"',$(2))' >$$@.tmp; \
	  if cmp -s $$@.tmp $$@; then rm -f $$@.tmp; else mv -f $$@.tmp $$@; fi
endef

include src/lib.mk
include platform/platform.mk
include app/app.mk
include tools/mie/mie.mk
include tools/slab/slab.mk
include tools/pathtrace/pathtrace.mk
include tools/keys/keys.mk
include tests/tests.mk
include tests/fuzz/fuzz.mk
include tests/vm/vm.mk
include tools/sweep/sweep.mk
include examples/examples.mk
include mk/install.mk

all: $(ALL_BINS)

# The README's test command: builds everything, runs every test, prints "N passed, N failed, N skipped".
check: all $(CHECK_TESTS_RUN)
	@$(TEST_ENV) sh tests/run_tests.sh $(CHECK_TESTS_RUN)

demo: $(B)/cumulo
	@$(TEST_ENV) $(B)/cumulo render scenes/cumulus.scene -o $(B)/demo.png
	@echo "demo: wrote $(B)/demo.png"

# The README's strip of a kiosk day (scenes/kiosk_day.scene at 05:30, 09:30, 13:30 and 17:30 UTC).
sky-strip: $(B)/cumulo
	@i=0; for t in 7200 21600 36000 50400; do \
	  $(TEST_ENV) $(B)/cumulo render scenes/kiosk_day.scene -o docs/sky_strip_$$i.png --size 320x192 --time $$t || exit 1; \
	  i=$$((i + 1)); done

# What a field of clouds costs (README "Performance"): tools/bench/living_sky.sh [ROUNDS] [SIZE].
ROUNDS ?= 3
BENCH_SIZE ?= 480x320
bench-sky: $(B)/cumulo
	@$(TEST_ENV) sh tools/bench/living_sky.sh $(ROUNDS) $(BENCH_SIZE)

clean:
	rm -rf $(B)

help:
	@echo "make [all]        the library, the programs and the tools (configures first; installs missing packages)"
	@echo "make demo         render scenes/cumulus.scene to $(B)/demo.png"
	@echo "make check        every test; make stress: the long ones; make vmcheck: real kernel drivers in a VM"
	@echo "make sanitize     make check's tests built with ASan + UBSan (in $(B)/sanitize); make fuzz: libFuzzer"
	@echo "make install      PREFIX=/usr/local LIBDIR DATADIR MANDIR DESTDIR; make uninstall with the same PREFIX"
	@echo "make deps         build and run packages; deps-test, deps-vm, deps-fuzz, deps-plots: the rest"
	@echo "make sweep        the speed/accuracy sweep (30 min); make refs: rewrite the reference images"
	@echo "make sweep-methods  Kol's method against the uniform ray march; make fit-octaves: the octave model's fit"
	@echo "make bench-sky    what a field of clouds costs (ROUNDS=3 BENCH_SIZE=480x320); make sky-strip: README strip"
	@echo "make platform-info  what this machine's packages allow (./configure's summary)"
	@echo "variables: WITH_DRM|X11|WAYLAND|GPIO|OSMESA=auto|yes|no, OPT, CFLAGS, WERROR, PKG_CONFIG, NO_DEPS=1, B"
	@echo "           SANITIZE=1 (make check under ASan + UBSan), FUZZ_SECONDS=60, FUZZ_JOBS=2, FUZZ_CC=clang"

FORCE:

# dependency files of our own objects (build/vm holds a kernel tree with its own *.d, which are not ours; the
# sanitizer's copy of the tree and the fuzz build have their own)
ifneq ($(CONFIGURED),)
-include $(shell find $(B) \( -path $(B)/vm -o -path $(B)/sanitize -o -path $(B)/fuzz \) -prune -o -type f -name '*.d' \
  -print 2>/dev/null)
endif
