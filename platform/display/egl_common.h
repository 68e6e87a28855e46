/* platform/display/egl_common.h: the EGL steps the window back ends share (DRM/GBM, X11, Wayland): a platform
 * display, a GLES 3 config and context asked for explicitly, a window surface, the glmark2-style description. */
#ifndef CU_PLATFORM_EGL_COMMON_H
#define CU_PLATFORM_EGL_COMMON_H
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <stddef.h>

typedef struct cu_egl {
    EGLDisplay dpy;
    EGLConfig cfg;
    EGLContext ctx;
    EGLSurface surf;
    EGLint major, minor;
} cu_egl;

/* Initialises EGL on `platform` (EGL_PLATFORM_GBM_KHR, _X11_KHR, _WAYLAND_KHR) for native_display, picks an RGB888
 * config with a depth buffer that can render GLES 3 (if visual_id is non-zero, one whose native visual matches,
 * e.g. the GBM format) and creates a GLES 3.0 context. `who` prefixes messages ("drm", "x11"). A device that only
 * offers GLES 2 gets a message saying so and what it offers. */
int  cu_egl_init(cu_egl *e, EGLenum platform, void *native_display, EGLint visual_id, const char *who,
                 char *err, size_t errlen);
/* Creates the window surface for native_window (gbm_surface*, pointer to the X11 Window, wl_egl_window*), makes
 * the context current, and checks that GL_VERSION really is OpenGL ES 3 or newer. */
int  cu_egl_make_current(cu_egl *e, void *native_window, const char *who, char *err, size_t errlen);
/* GL and EGL entry points: eglGetProcAddress, falling back to libGLESv2 for drivers that only return extensions. */
void *cu_egl_proc(const char *name);
/* "EGL 1.5 (Mesa Project) config 0x2b: buf=32 r=8 g=8 b=8 a=0 depth=24 stencil=8 samples=0" */
void cu_egl_describe(const cu_egl *e, char *buf, size_t len);
void cu_egl_terminate(cu_egl *e);
/* Call after eglInitialize: in sanitizer builds keeps Mesa's driver loaded to the end (egl_common.c says why);
 * otherwise does nothing. */
void cu_egl_keep_driver(void);
const char *cu_egl_error(void);

#endif
