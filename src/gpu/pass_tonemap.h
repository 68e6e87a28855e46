/* src/gpu/pass_tonemap.h: the HDR target the sky and cloud passes draw into, and the tone map from it to the
 * caller's framebuffer (exposure, white balance, ACES curve, sRGB), or a plain copy of linear radiance. */
#ifndef CU_PASS_TONEMAP_H
#define CU_PASS_TONEMAP_H
#include "gpu_scene.h"
#include "target.h"

typedef struct cu_tonemap_locs {
    GLint exposure, white, composite;
} cu_tonemap_locs;

typedef struct cu_pass_tonemap {
    GLuint prog_tonemap, prog_copy;
    cu_tonemap_locs tonemap, copy;
    cu_target hdr;               /* colour + depth/stencil */
} cu_pass_tonemap;

int cu_pass_tonemap_create(cu_pass_tonemap *p, const cu_gpu_scene *ctx, const char *defines,
                           const char *linear_defines, cu_error *err);
void cu_pass_tonemap_destroy(cu_pass_tonemap *p, const cu_gl *gl);
/* (Re)allocates the HDR target for a w x h frame: RGBA32F for linear output, else RGBA16F or, without half-float
 * targets, RGBA8. Its format goes into ctx->hdr_format (through the renderer). */
int cu_pass_tonemap_resize(cu_pass_tonemap *p, const cu_gpu_scene *ctx, int w, int h, int linear, cu_error *err);
/* From the HDR target into framebuffer fbo: over every pixel, or (composite) blended premultiplied over what fbo
 * holds, leaving the pixels no cloud covers untouched. */
void cu_pass_tonemap_draw(const cu_pass_tonemap *p, const cu_gpu_scene *ctx, unsigned fbo, int linear,
                          int composite);
#endif
