/* src/gpu/pass_sky.h: the sky pass: one full-screen triangle of analytic sky (Preetham) or constant sky, the sun
 * disk and the ground, under the clouds (shaders_gles/sky.frag). */
#ifndef CU_PASS_SKY_H
#define CU_PASS_SKY_H
#include "gpu_scene.h"

typedef struct cu_pass_sky {
    GLuint prog;
    cu_sun_locs sun;
    GLint inv_viewproj, sun_irr, out_max, ground, out_scale, sky_color, perez, zenith, norm;
    GLint ground_sun, eye, gmap, shadow_g;
} cu_pass_sky;

int cu_pass_sky_create(cu_pass_sky *p, const cu_gpu_scene *ctx, const char *defines, cu_error *err);
void cu_pass_sky_destroy(cu_pass_sky *p, const cu_gl *gl);
/* Draws into the bound target, for the directions of ctx->camera. */
void cu_pass_sky_draw(const cu_pass_sky *p, const cu_gpu_scene *ctx);
#endif
