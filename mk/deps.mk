# Debian packages the project needs, and the check that installs them when one is missing.
# Building and running the engine, its tools and the platform layer (`make demo`, `make check` need these):
# compiler/make/pkg-config; EGL/GLES + Mesa's llvmpipe for a headless GLES 3 context; OSMesa, the second headless
# back end; libpng; cmocka; GSL (tools/slab's fitter); gbm/drm/libgpiod (kiosk); X11 and Wayland client libraries
# and wayland-protocols (xdg-shell) so the windowed back ends are built.
DEB_CORE     := gcc make pkg-config libc6-dev \
                libegl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri libosmesa6-dev \
                libpng-dev libcmocka-dev libgsl-dev libgbm-dev libdrm-dev libgpiod-dev \
                libx11-dev libwayland-dev wayland-protocols
# Tests only: a real X server (Xvfb) and Wayland compositor (weston) for the windowed back ends' tests, which are
# skipped without them.
DEB_TEST     := xvfb weston
# `make vmcheck` (tests/vm) runs the platform layer against real kernel drivers (vkms, gpio-sim, uinput) in a VM:
# qemu-system-x86 boots it, linux-source-6.1 is the kernel it builds, with flex/bison/bc (kconfig and the build),
# libelf-dev (objtool) and xz-utils (unpacking the source).
DEB_VM       := qemu-system-x86 linux-source-6.1 flex bison bc libelf-dev xz-utils
# Plots of `make sweep`, tools/mie/plot_phase.sh and tools/slab/plots.sh (the committed PNGs do not need it).
DEB_PLOTS    := gnuplot-nox
DEB_PACKAGES := $(DEB_CORE) $(DEB_TEST) $(DEB_VM) $(DEB_PLOTS)
PC_REQUIRED  := egl glesv2 osmesa libpng cmocka gsl

# Everything, for CI and developers.
deps:
	@sh scripts/install-deps.sh $(DEB_PACKAGES)

# Installs only when something is missing, so `make demo` works on a fresh machine and costs nothing after.
deps-check:
	@$(PKG) --exists $(PC_REQUIRED) 2>/dev/null && [ -e /usr/lib/x86_64-linux-gnu/dri/swrast_dri.so -o -n "$$(ls /usr/lib/*/dri/swrast_dri.so 2>/dev/null)" ] \
	  || sh scripts/install-deps.sh $(DEB_CORE)
