/* src/gpu/pass_shadow.h: shadows clouds cast on other clouds and on the ground: the optical depth along the sun's
 * rays through one casting cloud, added into a target that another cloud's shading (its shadow map, the same square
 * as its sun map) or the sky pass (the ground's map) reads. */
#ifndef CU_PASS_SHADOW_H
#define CU_PASS_SHADOW_H
#include "gpu_scene.h"
#include "target.h"

typedef struct cu_pass_shadow {
    GLuint prog;
    cu_density_locs density;
    GLint origin, ax, ay, dir, size;
    GLuint zero_tex;          /* 1x1 of zero optical depth: what a cloud no other cloud shades reads */
} cu_pass_shadow;

/* Builds the program (fs_defs: the full-screen defines; the pass compiles its own noise-free variant). */
int  cu_pass_shadow_create(cu_pass_shadow *p, const cu_gpu_scene *ctx, const char *fs_defs, cu_error *err);
void cu_pass_shadow_destroy(cu_pass_shadow *p, const cu_gl *gl);
/* A target of size x size for optical depths (RGBA16F: blendable; 0 when the context cannot render to it). */
int  cu_pass_shadow_target(const cu_gl *gl, int size, cu_target *t, cu_error *err);
/* Clears the texels reg = {x0, y0, x1, y1} of t (bound) to zero optical depth, for the casters to add into (each
 * caster's rectangle is its own; the caller clips it to reg). */
void cu_pass_shadow_begin(const cu_pass_shadow *p, const cu_gpu_scene *ctx, const cu_target *t, int size,
                          const int reg[4]);
/* Adds caster's optical depth along -sun_dir into the texels [x0, x1) x [y0, y1) of the bound target, whose texel
 * (u, v) has its ray through origin + ax (2u - 1) + ay (2v - 1) (world offsets from the caster's origin, start before
 * the caster along the sun). ke: the caster's core extinction now. */
void cu_pass_shadow_add(const cu_pass_shadow *p, const cu_gpu_scene *ctx, const cu_cloud *caster, double ke,
                        vec3 origin, vec3 ax, vec3 ay, int size, const int rect[4]);
void cu_pass_shadow_end(const cu_gpu_scene *ctx);
#endif
