# mk/deps.mk: the Debian packages cumulo needs, by purpose, and the checks that install them when one is missing.
#
# Building and running (`make deps`; what a Raspberry Pi kiosk needs): the compiler, make and pkg-config; EGL and
# GLES headers with Mesa's EGL and llvmpipe (headless rendering, and the fallback on machines without a GPU driver);
# libpng (the library writes and reads PNG); OSMesa (the second headless back end); GBM and libdrm (full screen on
# DRM/KMS); libgpiod (the GPIO knob); X11 and Wayland client libraries with wayland-protocols and wayland-scanner
# (windows). Each optional back end is built when its package is there (./configure says which).
DEB_BUILD := gcc make pkg-config libc6-dev libegl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri libpng-dev \
             libosmesa6-dev libgbm-dev libdrm-dev libgpiod-dev libx11-dev libwayland-dev libwayland-bin \
             wayland-protocols
# Tests (`make deps-test`): cmocka for the unit tests, GSL for tools/slab's model fitter and its tests, a real X
# server (Xvfb) and Wayland compositor (weston) for the windowed back ends' tests (skipped without them), and tshark:
# Wireshark's CIGI dissector decodes what `cumulo ig` and its test host exchange, a decoder nobody here wrote (the
# CIGI tests skip that check without it; the package's debconf question is answered no by the noninteractive install).
DEB_TEST  := libcmocka-dev libgsl-dev xvfb weston tshark
# `make vmcheck` (`make deps-vm`): qemu boots a kernel built from linux-source-6.1 (flex, bison, bc for kconfig,
# libelf-dev for objtool, xz-utils to unpack) to test DRM, GPIO and evdev against real drivers.
DEB_VM    := qemu-system-x86 linux-source-6.1 flex bison bc libelf-dev xz-utils
# `make fuzz` (`make deps-fuzz`): clang builds the libFuzzer targets of tests/fuzz; libFuzzer and clang's sanitizer
# runtimes are in libclang-rt-14-dev (Debian 12 splits them from clang). Plain builds and `make sanitize` (gcc's own
# ASan and UBSan) need neither.
DEB_FUZZ  := clang libclang-rt-14-dev
# Plots of `make sweep` and the tools' plot scripts (`make deps-plots`; the committed PNGs do not need it).
DEB_PLOTS := gnuplot-nox

# The pkg-config modules and files that say the build packages are there, so a configured machine asks dpkg nothing.
PC_BUILD := egl glesv2 libpng osmesa gbm libdrm libgpiod x11 wayland-client wayland-egl wayland-protocols
PC_TEST  := cmocka gsl

.PHONY: deps deps-test deps-vm deps-fuzz deps-plots deps-all
deps:
	@sh scripts/install-deps.sh $(DEB_BUILD)
deps-test:
	@sh scripts/install-deps.sh $(DEB_TEST)
deps-vm:
	@sh scripts/install-deps.sh $(DEB_VM)
deps-fuzz:
	@sh scripts/install-deps.sh $(DEB_FUZZ)
deps-plots:
	@sh scripts/install-deps.sh $(DEB_PLOTS)
deps-all: deps deps-test deps-vm deps-fuzz deps-plots

# Run before ./configure: installs the build (or test) packages only when pkg-config misses one of their modules.
# NO_DEPS=1 skips it (a machine without apt, or a packager's build root); configure then says what is missing.
DEPS_ENSURE_BUILD = $(if $(NO_DEPS),:,$(PKG_CONFIG) --exists $(PC_BUILD) 2>/dev/null && \
                    [ -n "$$(ls /usr/lib/*/dri/swrast_dri.so /usr/lib/dri/swrast_dri.so 2>/dev/null)" ] \
                    || sh scripts/install-deps.sh $(DEB_BUILD))
DEPS_ENSURE_FUZZ  = $(if $(NO_DEPS),:,command -v $(FUZZ_CC) >/dev/null && echo 'int LLVMFuzzerTestOneInput(const char *d, \
                    long n) { return d && n < 0; }' | $(FUZZ_CC) -fsanitize=fuzzer -x c - -o /dev/null 2>/dev/null \
                    || sh scripts/install-deps.sh $(DEB_FUZZ))
DEPS_ENSURE_TEST  = $(if $(NO_DEPS),:,$(PKG_CONFIG) --exists $(PC_TEST) 2>/dev/null && command -v Xvfb >/dev/null && \
                    command -v tshark >/dev/null \
                    || sh scripts/install-deps.sh $(DEB_TEST))
