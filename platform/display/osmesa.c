/* platform/display/osmesa.c: headless back end on Mesa's OSMesa: a desktop GL 4.5 core context that compiles the same
 * `#version 300 es` shaders (GL_ARB_ES3_compatibility). Kept because it is a second, independent driver path for the
 * image tests; it is gone from Mesa >= 25.1, so EGL surfaceless is the default. */
#include "display.h"
#include "headless_fbo.h"
#include <GL/osmesa.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct cu_display {
    OSMesaContext ctx;
    unsigned char *buf;
    cu_headless_fbo fb;
};

static void *osm_proc(const char *name)
{
    OSMESAproc f = OSMesaGetProcAddress(name);
    void *p;
    memcpy(&p, &f, sizeof p);
    return p;
}

static void osm_close(cu_display *d)
{
    if (!d)
        return;
    if (d->ctx) {
        cu_headless_fbo_destroy(&d->fb, osm_proc);
        OSMesaDestroyContext(d->ctx);
    }
    free(d->buf);
    free(d);
}

static int osm_open(cu_display **out, const cu_display_opts *o, char *err, size_t errlen)
{
    *out = NULL;
    cu_display *d = calloc(1, sizeof *d);
    if (!d) {
        snprintf(err, errlen, "osmesa: out of memory");
        return 1;
    }
    const int attr[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                        OSMESA_CONTEXT_MAJOR_VERSION, 4, OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
    d->ctx = OSMesaCreateContextAttribs(attr, NULL);
    if (!d->ctx) {
        snprintf(err, errlen, "osmesa: cannot create a GL 4.5 core context (Mesa without llvmpipe?)");
        osm_close(d);
        return 1;
    }
    /* The window-system buffer is only needed to make the context current; we render into our own FBO. */
    d->buf = malloc(16 * 16 * 4);
    if (!d->buf || !OSMesaMakeCurrent(d->ctx, d->buf, GL_UNSIGNED_BYTE, 16, 16)) {
        snprintf(err, errlen, "osmesa: OSMesaMakeCurrent failed");
        osm_close(d);
        return 1;
    }
    int w = o && o->width > 0 ? o->width : 640, h = o && o->height > 0 ? o->height : 480;
    if (cu_headless_fbo_create(&d->fb, osm_proc, w, h, o ? o->float_target : 0, err, errlen)) {
        osm_close(d);
        return 1;
    }
    *out = d;
    return 0;
}

static void *osm_get_proc(cu_display *d, const char *name)
{
    (void)d;
    return osm_proc(name);
}

static void osm_frame(cu_display *d, unsigned *fbo, int *w, int *h)
{
    *fbo = d->fb.fbo;
    *w = d->fb.width;
    *h = d->fb.height;
}

static int osm_present(cu_display *d, char *err, size_t errlen)
{
    (void)d; (void)err; (void)errlen;
    void (*finish)(void);
    void *p = osm_proc("glFinish");
    if (p) {
        memcpy(&finish, &p, sizeof p);
        finish();
    }
    return 0;
}

static void osm_describe(cu_display *d, char *buf, size_t len)
{
    snprintf(buf, len, "OSMesa GL core, offscreen %dx%d %s", d->fb.width, d->fb.height,
             d->fb.float_target ? "RGBA32F" : "RGBA8");
}

const cu_display_backend cu_display_osmesa = {
    "osmesa", osm_open, osm_get_proc, osm_frame, osm_present, osm_describe, osm_close,
};
