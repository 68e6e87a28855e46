/* platform/display/headless_fbo.h: the offscreen framebuffer both headless back ends render into (RGBA8 or RGBA32F). */
#ifndef CU_HEADLESS_FBO_H
#define CU_HEADLESS_FBO_H
#include <stddef.h>

typedef struct cu_headless_fbo {
    unsigned fbo, color;
    int width, height, float_target;
} cu_headless_fbo;

typedef void *(*cu_headless_getproc)(const char *name);
/* Creates the framebuffer with GL functions looked up through getproc. */
int cu_headless_fbo_create(cu_headless_fbo *f, cu_headless_getproc getproc, int w, int h, int float_target,
                           char *err, size_t errlen);
void cu_headless_fbo_destroy(cu_headless_fbo *f, cu_headless_getproc getproc);
#endif
