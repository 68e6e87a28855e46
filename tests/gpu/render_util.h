/* tests/gpu/render_util.h: headless rendering for tests: open a back end by name, render a scene (file or text, with
 * --set style overrides) to linear float or tone-mapped RGBA8, and compare images with stated tolerances. */
#ifndef CU_TEST_RENDER_UTIL_H
#define CU_TEST_RENDER_UTIL_H
#include "cumulo.h"
#include "display.h"
#include "session.h"
#include "vecmath.h"
#include <stdint.h>

extern const cu_display_backend cu_display_egl;
extern const cu_display_backend cu_display_osmesa;

typedef struct tr_ctx {
    cli_session s;           /* what the cumulo program opens (app/session.h); the three below alias it */
    const cu_display_backend *be;
    cu_display *disp;
    cu_renderer *r;
    int w, h, linear;
    char err[600];
} tr_ctx;

/* Opens back end `be` with a w x h target (float when linear) and a renderer. Returns 0 or fills err. */
int tr_open(tr_ctx *c, const cu_display_backend *be, int w, int h, int linear);
/* Sets the scene (path, or text when path starts with '['), applies `sets` (NULL-terminated), renders one frame. */
int tr_render(tr_ctx *c, const char *scene, const char *const *sets);
/* Moves the camera of the current scene and renders again (used for continuity sweeps). */
int tr_render_scene(tr_ctx *c, const cu_scene *s);
/* Renders the current scene again (after cu_renderer_set_sun, say). */
int tr_render_again(tr_ctx *c);
/* Renders the current scene again from another camera: scene's (a path) with camera position pos and look_at look
 * (scene keys' values), passed as host matrices, so that the renderer keeps its maps and grids (a new scene would
 * start over). */
int tr_render_from(tr_ctx *c, const char *scene, const char *pos, const char *look);
int tr_read_rgbf(tr_ctx *c, float *rgb);      /* top row first, w*h*3 */
int tr_read_rgba8(tr_ctx *c, uint8_t *rgba);  /* top row first, w*h*4 */
void tr_close(tr_ctx *c);
/* Direction through the centre of pixel (x, y) of a w x h frame (y = 0 at the top) from the scene's camera, as the
 * renderer defines it. */
vec3 tr_pixel_dir(const cu_scene *s, int w, int h, int x, int y);

typedef struct tr_diff {
    int max_diff;        /* max per-channel difference, 0..255 */
    double frac_over;    /* fraction of pixels with some channel differing by more than `threshold` */
    double psnr;         /* dB over RGB */
} tr_diff;
tr_diff tr_compare_rgba8(const uint8_t *a, const uint8_t *b, int w, int h, int threshold);
/* The largest absolute difference of two linear images of n floats, relative to b's brightest value. */
double tr_rel_diff(const float *a, const float *b, size_t n);
/* Writes result, reference and an amplified difference image under build/test-output/<name>-*.png. */
void tr_save_failure(const char *name, const uint8_t *got, const uint8_t *ref, int w, int h);
#endif
