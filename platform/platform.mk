# platform/platform.mk: the display back ends (platform/display/), the inputs (platform/input/) and the host
# simulations' protocols (platform/sim/) the programs use.
# Which optional back ends are built comes from ./configure ($(B)/config.mk, $(B)/gen/config.h).
DISPLAY_SRCS := platform/display/display.c platform/display/egl_common.c platform/display/egl_surfaceless.c \
                platform/display/headless_fbo.c platform/display/drm_mode.c \
                $(if $(filter 1,$(HAVE_OSMESA)),platform/display/osmesa.c) \
                $(if $(filter 1,$(HAVE_DRM)),platform/display/drm.c platform/display/drm_probe.c) \
                $(if $(filter 1,$(HAVE_X11)),platform/display/x11.c) \
                $(if $(filter 1,$(HAVE_WAYLAND)),platform/display/wayland.c)
# The knob's logic (gpio.c) is the same for both libgpiod APIs; the glue is the one configure found (GPIO_API 1 or 2).
GPIO_SRCS    := platform/input/gpio.c platform/input/gpio_errors.c platform/input/gpio_v$(GPIO_API).c
INPUT_SRCS   := platform/input/input.c platform/input/input_backend.c platform/input/input_set.c platform/input/evdev.c \
                platform/input/stdin_input.c platform/input/quadrature.c platform/input/knob_speed.c \
                platform/input/sun_control.c platform/input/clock_control.c \
                $(if $(filter 1,$(HAVE_GPIO)),$(GPIO_SRCS))
# The simulator links of `cumulo ig` (platform/sim/): the protocols' decoders are pure functions of datagrams into
# sim_state.h; geodetic.c turns the state into a camera; udp.c and sim_link.c do the I/O.
SIM_SRCS     := platform/sim/cigi.c platform/sim/fgfs.c platform/sim/xplane.c platform/sim/geodetic.c \
                platform/sim/udp.c platform/sim/sim_link.c
PLATFORM_SRCS := $(DISPLAY_SRCS) $(INPUT_SRCS) $(SIM_SRCS)
PLATFORM_OBJS := $(PLATFORM_SRCS:%.c=$(B)/obj/%.o)
PLATFORM_LIBS := $(EGL_LIBS) $(OSMESA_LIBS) $(DRM_LIBS) $(X11_LIBS) $(WAYLAND_LIBS) $(GPIO_LIBS) -lm -lpthread

PLATFORM_CPPFLAGS := -Iplatform/display -Iplatform/input -Iplatform/sim -I$(B)/gen
CFLAGS_PLATFORM := $(CFLAGS_BASE) $(PLATFORM_CPPFLAGS)
$(eval $(call flags_rule,platform,$(CC) $(CFLAGS_PLATFORM) $(EGL_CFLAGS) $(OSMESA_CFLAGS) $(DRM_CFLAGS) \
  $(X11_CFLAGS) $(WAYLAND_CFLAGS) $(GPIO_CFLAGS)))

# Each back end's file gets its own libraries' flags, and only it.
$(B)/obj/platform/display/egl_common.o $(B)/obj/platform/display/egl_surfaceless.o: XCFLAGS := $(EGL_CFLAGS)
$(B)/obj/platform/display/osmesa.o: XCFLAGS := $(OSMESA_CFLAGS)
$(B)/obj/platform/display/drm.o $(B)/obj/platform/display/drm_probe.o: XCFLAGS := $(DRM_CFLAGS) $(EGL_CFLAGS)
$(B)/obj/platform/display/x11.o: XCFLAGS := $(X11_CFLAGS) $(EGL_CFLAGS)
$(B)/obj/platform/display/wayland.o: XCFLAGS := $(WAYLAND_CFLAGS) $(EGL_CFLAGS)
$(B)/obj/platform/input/gpio_v1.o $(B)/obj/platform/input/gpio_v2.o: XCFLAGS := $(GPIO_CFLAGS)

# xdg-shell's client glue, generated from wayland-protocols' XML by wayland-scanner.
WL_GEN := $(B)/gen/xdg-shell-client-protocol.h $(B)/gen/xdg-shell-protocol.inc
$(B)/gen/xdg-shell-client-protocol.h: $(WAYLAND_XDG_XML)
	@mkdir -p $(@D)
	$(WAYLAND_SCANNER) client-header $(WAYLAND_XDG_XML) $@
$(B)/gen/xdg-shell-protocol.inc: $(WAYLAND_XDG_XML)
	@mkdir -p $(@D)
	$(WAYLAND_SCANNER) private-code $(WAYLAND_XDG_XML) $@
$(B)/obj/platform/display/wayland.o: $(WL_GEN)

$(B)/obj/platform/%.o: platform/%.c $(B)/flags/platform
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_PLATFORM) $(XCFLAGS) -c $< -o $@

.PHONY: platform-info
platform-info:
	@sh ./configure $(CONFIGURE_ARGS)
