/* src/gpu/pass_refine.h: quality.edge_refine, the pixels a reduced-resolution cloud image blurs marched again at full
 * resolution. After the clouds are drawn at 1/N (pass_upsample.h), a full-resolution target is cleared, within the
 * rectangle the composite reads, to an alpha of 2 (no cloud has that) and stencil CU_REFINE_SKIP (gpu_scene.h);
 * refine_mark.frag keeps the pixels whose four low-resolution texels differ past the threshold, writing them
 * transparent black with stencil 0. The cloud pass then draws every cloud into this target as at full resolution:
 * its stencil test (EQUAL 0; the full-screen pass and impostors test the mark bit alone) shades the kept pixels only,
 * before the shader runs, and the frame's clear of depth and stencil between clouds, under the write mask this pass
 * leaves, keeps the marks. The composite (sky.frag, upsample.frag) takes this target's pixel where its alpha is at
 * most 1 and the upsampled image elsewhere: a threshold near 0 gives the full-resolution picture, 1 the upsampled one.
 * What it costs is the marked pixels' march plus a full-resolution mark pass, clear and depth pre-pass; a software
 * rasteriser or a GPU shades in blocks (llvmpipe 4x4 pixels), so a thin line of marked pixels costs several times its
 * pixel count (tools/bench/edge_refine.sh). */
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
 * bound with its viewport, the stencil test on as the cloud pass expects (EQUAL 0 over all bits) and the stencil
 * write mask at the bits below CU_REFINE_SKIP. */
int  cu_pass_refine_begin(cu_pass_refine *p, const cu_gpu_scene *ctx, GLuint low, int w, int h, int n,
                          double threshold, const int rect[4], GLenum format, cu_error *err);
/* After the clouds: the stencil test off and the write mask whole again. */
void cu_pass_refine_end(const cu_pass_refine *p, const cu_gl *gl);
#endif
