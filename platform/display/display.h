/* platform/display/display.h: the boundary between cumulo's programs and a windowing system: a back end makes a
 * GLES 3 context current, hands out the framebuffer to draw into, and presents frames (kmscube/raylib style). */
#ifndef CU_PLATFORM_DISPLAY_H
#define CU_PLATFORM_DISPLAY_H
#include <stddef.h>

typedef struct cu_display cu_display;

typedef struct cu_display_opts {
    int width, height;        /* 0 = back end's choice (headless: 640x480; drm: the connector's mode) */
    int fullscreen;           /* windowed back ends only */
    const char *mode;         /* drm: "WxH" or "WxH@Hz", NULL = preferred mode */
    const char *device;       /* drm: /dev/dri/cardN or by-path name, NULL = probe */
    int float_target;         /* headless: make the framebuffer RGBA32F (for PFM output) instead of RGBA8 */
} cu_display_opts;

typedef struct cu_display_backend {
    const char *name;         /* "egl", "osmesa", "drm", "x11", "wayland" */
    /* Creates the context and makes it current. On failure returns non-zero and writes one line to err. */
    int (*open)(cu_display **out, const cu_display_opts *opts, char *err, size_t errlen);
    /* GL entry points of this context (the engine loads every GL function through this). */
    void *(*get_proc_address)(cu_display *d, const char *name);
    /* The framebuffer object to draw the next frame into (0 = the window system's) and its size. */
    void (*frame)(cu_display *d, unsigned *fbo, int *width, int *height);
    /* Present the frame (swap buffers / page flip, waiting for vsync). Headless: glFinish. */
    int (*present)(cu_display *d, char *err, size_t errlen);
    /* One line describing the surface configuration, glmark2-style. */
    void (*describe)(cu_display *d, char *buf, size_t len);
    void (*close)(cu_display *d);
} cu_display_backend;

/* The back ends compiled into this binary, NULL-terminated, in order of preference. */
extern const cu_display_backend *const cu_display_backends[];
const cu_display_backend *cu_display_find(const char *name);

#endif
