# platform/: display back ends (headless EGL surfaceless, OSMesa; DRM/KMS and windows from devices.mk) and inputs.
PLATFORM_SRCS := platform/display.c platform/egl_common.c platform/egl_surfaceless.c platform/osmesa.c \
                 platform/headless_fbo.c
PLATFORM_CFLAGS := $(call pc_cflags,egl osmesa)
PLATFORM_LIBS := $(call pc_libs,egl osmesa)
-include platform/devices.mk
