/* src/gpu/upload.h: the scene's data as the GL objects the passes read through the frame context: the noise
 * volume, the phase table, the instanced ellipsoid hulls. */
#ifndef CU_UPLOAD_H
#define CU_UPLOAD_H
#include "gpu_scene.h"
#include "phase.h"

/* The noise's own mip levels as a 3-D texture, into ctx->noise_tex; or, with baked_octaves > 0 (quality.noise_baked),
 * that many octaves baked into one level (cu_noise_bake). 0, or 1 with a message. */
int cu_upload_noise(cu_gpu_scene *ctx, const cu_noise *n, int baked_octaves, cu_error *err);
/* The phase table (row 0: the chopped phase function, row 1: the removed peak), into ctx->phase_tex; with lobe
 * (ms.lobe), rows 2 .. 2 + CU_LOBE_ROWS - 1 the lobe's own light (cu_ms_lobe_table in ctx->msd_f's medium). */
int cu_upload_phase(cu_gpu_scene *ctx, const cu_phase_table *t, int lobe, cu_error *err);
/* The hull mesh of ctx->scene's tessellation and an empty VAO for full-screen draws, into ctx's hull fields. */
int cu_upload_hulls(cu_gpu_scene *ctx, cu_error *err);
/* One instance per ellipsoid of cl on the hull mesh: a buffer and the VAO that draws them (the caller owns both). */
void cu_upload_instances(const cu_gpu_scene *ctx, const cu_cloud *cl, GLuint *vbo, GLuint *vao);
/* Deletes all of the above and zeroes their names. */
void cu_upload_delete(cu_gpu_scene *ctx);
#endif
