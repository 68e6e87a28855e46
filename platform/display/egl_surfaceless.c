/* platform/display/egl_surfaceless.c: headless back end on EGL_MESA_platform_surfaceless: a real GLES 3 context with no
 * window system, rendering into an offscreen framebuffer (the default for tests, screenshots and benchmarks). */
#include "display.h"
#include "egl_common.h"
#include "headless_fbo.h"
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES3/gl3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct cu_display {
    EGLDisplay dpy;
    EGLContext ctx;
    cu_headless_fbo fb;
};

/* eglGetProcAddress as void * and the last EGL error's name: shared with the windowed back ends. */
#define egl_proc cu_egl_proc
#define egl_err cu_egl_error

static void egl_close(cu_display *d)
{
    if (!d)
        return;
    if (d->ctx != EGL_NO_CONTEXT) {
        cu_headless_fbo_destroy(&d->fb, egl_proc);
        eglMakeCurrent(d->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(d->dpy, d->ctx);
    }
    if (d->dpy != EGL_NO_DISPLAY)
        eglTerminate(d->dpy);
    free(d);
}

static int egl_open(cu_display **out, const cu_display_opts *o, char *err, size_t errlen)
{
    *out = NULL;
    cu_display *d = calloc(1, sizeof *d);
    if (!d) {
        snprintf(err, errlen, "egl: out of memory");
        return 1;
    }
    d->dpy = EGL_NO_DISPLAY;
    d->ctx = EGL_NO_CONTEXT;
    const char *client_ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!client_ext || !strstr(client_ext, "EGL_MESA_platform_surfaceless")) {
        snprintf(err, errlen, "egl: EGL_MESA_platform_surfaceless is not available (install libegl-mesa0)");
        free(d);
        return 1;
    }
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    if (!get_platform_display) {
        snprintf(err, errlen, "egl: eglGetPlatformDisplayEXT missing");
        free(d);
        return 1;
    }
    d->dpy = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    EGLint major, minor;
    if (d->dpy == EGL_NO_DISPLAY || !eglInitialize(d->dpy, &major, &minor)) {
        snprintf(err, errlen, "egl: eglInitialize on the surfaceless platform failed (%s)", egl_err());
        d->dpy = EGL_NO_DISPLAY;
        egl_close(d);
        return 1;
    }
    cu_egl_keep_driver();
    if (!eglBindAPI(EGL_OPENGL_ES_API)) {
        snprintf(err, errlen, "egl: eglBindAPI(EGL_OPENGL_ES_API) failed (%s)", egl_err());
        egl_close(d);
        return 1;
    }
    const EGLint cfg_attr[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_ES3_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_NONE};
    EGLConfig cfg = NULL;
    EGLint n = 0;
    const char *dpy_ext = eglQueryString(d->dpy, EGL_EXTENSIONS);
    int no_config = dpy_ext && strstr(dpy_ext, "EGL_KHR_no_config_context");
    if (!no_config && (!eglChooseConfig(d->dpy, cfg_attr, &cfg, 1, &n) || n < 1)) {
        snprintf(err, errlen, "egl: no EGL config with EGL_OPENGL_ES3_BIT: this device offers no OpenGL ES 3");
        egl_close(d);
        return 1;
    }
    const EGLint ctx_attr[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 0, EGL_NONE};
    d->ctx = eglCreateContext(d->dpy, no_config ? EGL_NO_CONFIG_KHR : cfg, EGL_NO_CONTEXT, ctx_attr);
    if (d->ctx == EGL_NO_CONTEXT) {
        snprintf(err, errlen, "egl: cannot create an OpenGL ES 3.0 context (%s)", egl_err());
        egl_close(d);
        return 1;
    }
    if (!eglMakeCurrent(d->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, d->ctx)) {
        snprintf(err, errlen, "egl: eglMakeCurrent without a surface failed (%s)", egl_err());
        egl_close(d);
        return 1;
    }
    int w = o && o->width > 0 ? o->width : 640, h = o && o->height > 0 ? o->height : 480;
    if (cu_headless_fbo_create(&d->fb, egl_proc, w, h, o ? o->float_target : 0, err, errlen)) {
        egl_close(d);
        return 1;
    }
    *out = d;
    return 0;
}

static void *egl_get_proc(cu_display *d, const char *name)
{
    (void)d;
    return egl_proc(name);
}

static void egl_frame(cu_display *d, unsigned *fbo, int *w, int *h)
{
    *fbo = d->fb.fbo;
    *w = d->fb.width;
    *h = d->fb.height;
}

static int egl_present(cu_display *d, char *err, size_t errlen)
{
    (void)d; (void)err; (void)errlen;
    void *p = egl_proc("glFinish");
    if (p) {
        PFNGLFINISHPROC finish;
        memcpy(&finish, &p, sizeof p);
        finish();
    }
    return 0;
}

static void egl_describe(cu_display *d, char *buf, size_t len)
{
    snprintf(buf, len, "EGL surfaceless, offscreen %dx%d %s", d->fb.width, d->fb.height,
             d->fb.float_target ? "RGBA32F" : "RGBA8");
}

const cu_display_backend cu_display_egl = {
    "egl", egl_open, egl_get_proc, egl_frame, egl_present, egl_describe, egl_close,
};
