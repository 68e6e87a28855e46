# Debian packages the project needs, and the check that installs them when one is missing.
# Why each one: compiler/make/pkg-config build us; EGL/GLES + Mesa's llvmpipe give a headless GLES 3 context;
# OSMesa is the second headless back end; libpng writes and reads PNGs; cmocka runs the unit tests;
# GSL fits the multiple-scattering model (tools/slab); gbm/drm/libgpiod are the kiosk platform layer.
# `make vmcheck` (tests/vm) runs the platform layer against real kernel drivers (vkms, gpio-sim, uinput) in a VM:
# qemu-system-x86 boots it, linux-source-6.1 is the kernel it builds, with flex/bison/bc (kconfig and the build),
# libelf-dev (objtool) and xz-utils (unpacking the source).
DEB_PACKAGES := gcc make pkg-config libc6-dev \
                libegl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri libosmesa6-dev \
                libpng-dev libcmocka-dev libgsl-dev libgbm-dev libdrm-dev libgpiod-dev \
                qemu-system-x86 linux-source-6.1 flex bison bc libelf-dev xz-utils
PC_REQUIRED  := egl glesv2 osmesa libpng cmocka gsl

deps:
	@sh scripts/install-deps.sh $(DEB_PACKAGES)

# Installs only when something is missing, so `make demo` works on a fresh machine and costs nothing after.
deps-check:
	@$(PKG) --exists $(PC_REQUIRED) 2>/dev/null && [ -e /usr/lib/x86_64-linux-gnu/dri/swrast_dri.so -o -n "$$(ls /usr/lib/*/dri/swrast_dri.so 2>/dev/null)" ] \
	  || sh scripts/install-deps.sh $(DEB_PACKAGES)
