# platform/devices.mk: the device back ends (DRM/KMS, X11, Wayland), the inputs (GPIO knob, evdev, stdin), their
# tests. Each optional back end is built only when pkg-config finds its libraries; `make platform-info` says which.

# Inputs and the sun mapping need only libc; they are always built.
PLATFORM_SRCS += platform/egl_common.c platform/input.c platform/quadrature.c platform/evdev.c \
                 platform/stdin_input.c platform/sun_control.c

# libgpiod: v1 (Debian 12: 1.6) and v2 have different APIs; the major version picks the code at build time.
GPIOD_VERSION := $(shell $(PKG) --modversion libgpiod 2>/dev/null)
ifneq ($(GPIOD_VERSION),)
PLATFORM_SRCS   += platform/gpio.c
PLATFORM_CFLAGS += -DCU_HAVE_GPIOD $(call pc_cflags,libgpiod)
PLATFORM_LIBS   += $(call pc_libs,libgpiod) -pthread
ifneq ($(filter 2 3 4 5 6 7 8 9,$(firstword $(subst ., ,$(GPIOD_VERSION)))),)
PLATFORM_CFLAGS += -DCU_GPIOD_V2
endif
endif

HAVE_DRM := $(shell $(PKG) --exists gbm libdrm egl 2>/dev/null && echo yes)
ifeq ($(HAVE_DRM),yes)
PLATFORM_SRCS   += platform/drm.c platform/drm_mode.c
PLATFORM_CFLAGS += -DCU_HAVE_DRM $(call pc_cflags,gbm libdrm)
PLATFORM_LIBS   += $(call pc_libs,gbm libdrm)
endif

HAVE_X11 := $(shell $(PKG) --exists x11 egl 2>/dev/null && echo yes)
ifeq ($(HAVE_X11),yes)
PLATFORM_SRCS   += platform/x11.c
PLATFORM_CFLAGS += -DCU_HAVE_X11 $(call pc_cflags,x11)
PLATFORM_LIBS   += $(call pc_libs,x11)
endif

# Wayland windows need xdg-shell, whose client glue wayland-scanner generates from wayland-protocols' XML. It is
# generated while the makefile is read (into $(B)/gen, already on the include path), so it exists before any
# compile whatever rule builds platform/wayland.c.
WL_SCANNER  := $(shell command -v wayland-scanner 2>/dev/null)
WL_PROTODIR := $(shell $(PKG) --variable=pkgdatadir wayland-protocols 2>/dev/null)
HAVE_WAYLAND := $(shell $(PKG) --exists wayland-client wayland-egl egl 2>/dev/null && \
                  [ -n "$(WL_SCANNER)" ] && [ -f "$(WL_PROTODIR)/stable/xdg-shell/xdg-shell.xml" ] && echo yes)
ifeq ($(HAVE_WAYLAND),yes)
WL_XDG := $(WL_PROTODIR)/stable/xdg-shell/xdg-shell.xml
WL_GEN := $(shell mkdir -p $(B)/gen && \
            { [ -f $(B)/gen/xdg-shell-client-protocol.h ] || $(WL_SCANNER) client-header $(WL_XDG) \
                $(B)/gen/xdg-shell-client-protocol.h; } && \
            { [ -f $(B)/gen/xdg-shell-protocol.inc ] || $(WL_SCANNER) private-code $(WL_XDG) \
                $(B)/gen/xdg-shell-protocol.inc; } && echo ok)
PLATFORM_SRCS   += platform/wayland.c
PLATFORM_CFLAGS += -DCU_HAVE_WAYLAND $(call pc_cflags,wayland-client wayland-egl)
PLATFORM_LIBS   += $(call pc_libs,wayland-client wayland-egl)
endif

.PHONY: platform-info
platform-info:
	@echo "display back ends: egl osmesa$(if $(filter yes,$(HAVE_DRM)), drm)$(if $(filter yes,$(HAVE_X11)), x11)$(if \
	  $(filter yes,$(HAVE_WAYLAND)), wayland)"
	@echo "gpio: $(if $(GPIOD_VERSION),libgpiod $(GPIOD_VERSION) ($(if $(filter -DCU_GPIOD_V2,$(PLATFORM_CFLAGS)),v2,v1) API),not built (no libgpiod))"

# ---- tests ----
PLATFORM_TEST_CC = $(CC) $(CFLAGS_COMMON) $(call pc_cflags,cmocka) -o $@ $(filter %.c,$^) $(call pc_libs,cmocka) \
                   $(LDLIBS_COMMON)

$(B)/test_quadrature: platform/test_quadrature.c platform/quadrature.c platform/quadrature.h
	@mkdir -p $(@D)
	$(PLATFORM_TEST_CC)

$(B)/test_input: platform/test_input.c platform/input.c platform/stdin_input.c platform/sun_control.c \
                 platform/input.h platform/stdin_input.h platform/sun_control.h
	@mkdir -p $(@D)
	$(PLATFORM_TEST_CC)

$(B)/test_evdev: platform/test_evdev.c platform/evdev.c platform/evdev.h platform/input.h
	@mkdir -p $(@D)
	$(PLATFORM_TEST_CC)

$(B)/test_drm_mode: platform/test_drm_mode.c platform/drm_mode.c platform/drm_mode.h
	@mkdir -p $(@D)
	$(PLATFORM_TEST_CC)

# drm.c against a fake Pi-like display stack (libdrm, GBM and the EGL helpers defined in the test, /dev/dri faked
# through ld --wrap): needs only the libdrm and GBM headers.
ifeq ($(HAVE_DRM),yes)
$(B)/test_drm: platform/test_drm.c platform/drm.c platform/drm_mode.c platform/display.h platform/egl_common.h
	@mkdir -p $(@D)
	$(CC) $(CFLAGS_COMMON) -Iplatform $(call pc_cflags,cmocka libdrm gbm egl) -o $@ platform/test_drm.c \
	  platform/drm.c platform/drm_mode.c $(call pc_libs,cmocka) $(LDLIBS_COMMON) \
	  -Wl,--wrap=open,--wrap=stat,--wrap=opendir,--wrap=readdir,--wrap=closedir
CHECK_TESTS += $(B)/test_drm
endif

# evdev.c's device half against fake /dev/input devices: libc's open/ioctl/read/opendir wrapped at link time.
$(B)/test_evdev_dev: platform/test_evdev_dev.c platform/evdev.c platform/evdev.h platform/input.c
	@mkdir -p $(@D)
	$(CC) $(CFLAGS_COMMON) -Iplatform $(call pc_cflags,cmocka) -o $@ platform/test_evdev_dev.c platform/evdev.c \
	  platform/input.c $(call pc_libs,cmocka) $(LDLIBS_COMMON) \
	  -Wl,--wrap=open,--wrap=ioctl,--wrap=read,--wrap=opendir,--wrap=readdir,--wrap=closedir
CHECK_TESTS += $(B)/test_evdev_dev

# gpio.c against a scripted fake of libgpiod: the v2 build declares the v2 API itself, so it runs everywhere; the v1
# build needs the v1 header (libgpiod 1.x installed).
$(B)/test_gpio_v2: platform/test_gpio.c platform/gpio.c platform/gpio.h platform/quadrature.c platform/input.c
	@mkdir -p $(@D)
	$(CC) $(CFLAGS_COMMON) -DCU_GPIOD_V2 -Iplatform $(call pc_cflags,cmocka) -o $@ platform/test_gpio.c \
	  platform/quadrature.c platform/input.c $(call pc_libs,cmocka) $(LDLIBS_COMMON)
CHECK_TESTS += $(B)/test_gpio_v2

ifeq ($(firstword $(subst ., ,$(GPIOD_VERSION))),1)
$(B)/test_gpio_v1: platform/test_gpio.c platform/gpio.c platform/gpio.h platform/quadrature.c platform/input.c
	@mkdir -p $(@D)
	$(CC) $(CFLAGS_COMMON) -Iplatform $(call pc_cflags,cmocka libgpiod) -o $@ platform/test_gpio.c \
	  platform/quadrature.c platform/input.c $(call pc_libs,cmocka) $(LDLIBS_COMMON) -pthread
CHECK_TESTS += $(B)/test_gpio_v1
endif

CHECK_TESTS += $(B)/test_quadrature $(B)/test_input $(B)/test_evdev $(B)/test_drm_mode \
               platform/test_run.sh platform/test_gpio_sim.sh platform/test_soak.sh
