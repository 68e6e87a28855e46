/* src/gpu/pass_upsample.h: the clouds at a fraction of the frame's resolution (quality.cloud_downsample): a target of
 * 1/N the size the cloud pass draws into, and the pass that brings it up to the frame (upsample.frag). */
#ifndef CU_PASS_UPSAMPLE_H
#define CU_PASS_UPSAMPLE_H
#include "gpu_scene.h"
#include "target.h"

typedef struct cu_pass_upsample {
    GLuint prog;
    GLint factor, depth_on, depth_clear, lin, refined_on;
    GLuint depth_sampler;
    cu_target low;             /* premultiplied cloud radiance and coverage, with its own depth and stencil */
} cu_pass_upsample;

int  cu_pass_upsample_create(cu_pass_upsample *p, const cu_gpu_scene *ctx, cu_error *err);
void cu_pass_upsample_destroy(cu_pass_upsample *p, const cu_gl *gl);
/* Makes the low-resolution target ceil(w / n) x ceil(h / n) in the HDR target's format (kept while it fits) and binds
 * it cleared to transparent, with its viewport. */
int  cu_pass_upsample_begin(cu_pass_upsample *p, const cu_gpu_scene *ctx, int w, int h, int n, GLenum format,
                            cu_error *err);
/* Blends the low-resolution clouds (low: the target's own texture, or the temporal grid's image) over what `hdr`
 * holds, at w x h. proj: the frame's projection (column-major), whose z rows turn the host's window depth into
 * distances when ctx has the host's depth. refined (0: none): quality.edge_refine's full-resolution image, taken
 * instead where its alpha is at most 1 (pass_refine.h). */
void cu_pass_upsample_draw(const cu_pass_upsample *p, const cu_gpu_scene *ctx, GLuint low, GLuint refined, GLuint hdr,
                           int w, int h, int n, const double *proj);
#endif
