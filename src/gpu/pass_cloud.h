/* src/gpu/pass_cloud.h: the depth pre-pass and the cloud pass, which share the ellipsoid hulls: depth only first
 * (Kol 3.4.2), then the hulls again with GL_EQUAL so each pixel is shaded once by cloud.frag; a full-screen
 * triangle instead when the camera is inside a hull (Kol 3.4.4). */
#ifndef CU_PASS_CLOUD_H
#define CU_PASS_CLOUD_H
#include "shading.h"

typedef struct cu_pass_cloud {
    GLuint prog_depth, prog_hull, prog_fs;
    GLuint host_sampler; /* nearest, no compare: how the host's depth texture is read, whatever its own state */
    GLint depth_viewproj;
    cu_shading_locs hull, fs;
} cu_pass_cloud;

int cu_pass_cloud_create(cu_pass_cloud *p, const cu_gpu_scene *ctx, const char *hull_defs, const char *fs_defs,
                         cu_error *err);
void cu_pass_cloud_destroy(cu_pass_cloud *p, const cu_gl *gl);
/* 1 when this frame's camera needs the full-screen path: the near plane may cut a hull (the camera inside or near
 * one, or an orthographic near plane inside the clouds' bounds). */
int cu_pass_cloud_fullscreen(const cu_gpu_scene *ctx);
/* Draws premultiplied over what the bound target holds (the sky, or nothing); its depth and stencil must be
 * cleared. Reads the host's depth (ctx->host_depth) on CU_UNIT_HOST_DEPTH when there is one. */
void cu_pass_cloud_draw(const cu_pass_cloud *p, const cu_gpu_scene *ctx);
#endif
