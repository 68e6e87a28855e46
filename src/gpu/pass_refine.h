/* src/gpu/pass_refine.h: quality.edge_refine, the pixels a reduced-resolution cloud image blurs marched again at full
 * resolution. After the clouds are drawn at 1/N (pass_upsample.h), a full-resolution target is cleared, within the
 * rectangle the composite reads, to an alpha of 2 (no cloud has that) and stencil CU_REFINE_SKIP (gpu_scene.h);
 * refine_mark.frag keeps the pixels whose four low-resolution texels differ past the threshold, writing them
 * transparent black with stencil 0. Then every cloud is drawn into this target as one full-screen triangle scissored
 * to its rectangle (pass_cloud.c with ctx->refining; frame.c), under a stencil test that rejects the unmarked pixels
 * before the shader runs: the stencil is not written (write mask 0), so llvmpipe and tilers test it early although
 * the full-screen shader can discard. The hull would bring a depth pre-pass and every ellipsoid's layers for the test
 * to reject, which measured dearer than the marked pixels' march. The composite (sky.frag, upsample.frag) takes this
 * target's pixel where its alpha is at most 1 and the upsampled image elsewhere: a threshold near 0 gives the
 * full-resolution picture, 1 the upsampled one. A software rasteriser or a GPU shades in blocks (llvmpipe 4x4
 * pixels), so a thin line of marked pixels costs several times its pixel count (tools/bench/edge_refine.sh). */
#ifndef CU_PASS_REFINE_H
#define CU_PASS_REFINE_H
#include "gpu_scene.h"
#include "target.h"

typedef struct cu_pass_refine {
    GLuint prog;
    GLint factor, threshold;
    cu_target full;            /* the kept pixels' clouds, premultiplied; alpha 2 elsewhere; depth and stencil */
} cu_pass_refine;

int  cu_pass_refine_create(cu_pass_refine *p, const cu_gpu_scene *ctx, cu_error *err);
void cu_pass_refine_destroy(cu_pass_refine *p, const cu_gl *gl);
/* Makes the w x h target in `format` (kept while it fits), marks the pixels of `low` (the low-resolution cloud image
 * at 1/n) that differ past `threshold` within rect (x0, y0, x1, y1 in pixels; none outside it), and leaves the target
 * bound with its viewport, the scissor at rect, the stencil test on and the stencil write mask 0 (the cloud and
 * impostor passes set their test against CU_REFINE_SKIP when ctx->refining). */
int  cu_pass_refine_begin(cu_pass_refine *p, const cu_gpu_scene *ctx, GLuint low, int w, int h, int n,
                          double threshold, const int rect[4], GLenum format, cu_error *err);
/* After the clouds: the stencil test off and the write mask whole again. */
void cu_pass_refine_end(const cu_pass_refine *p, const cu_gl *gl);
#endif
