/* src/renderer.h: the renderer's private state, shared by the renderer's modules (passes, sun map). */
#ifndef CU_RENDERER_H
#define CU_RENDERER_H
#include "density.h"
#include "gl.h"
#include "noise.h"
#include "phase.h"
#include "scene.h"
#include "sky.h"
#include "vecmath.h"

struct cu_renderer {
    cu_gl gl;
    cu_desc desc;
    char vendor[128], renderer_name[128], version[128];
    int is_gles;          /* 1: OpenGL ES context, 0: desktop GL core running the ES shaders (OSMesa) */
    int float_rt;         /* RGBA32F is colour-renderable */
    int half_rt;          /* RGBA16F is colour-renderable */

    int has_scene;
    cu_scene scene;
    cu_noise noise;
    int noise_ready;
    cu_cloud cloud;
    cu_sky sky;

    GLuint noise_tex, phase_tex;
    GLuint sun_tex, sun_fbo;
    GLuint sun_back_tex, sun_back_fbo; /* front method only, when a term needs the thickness along the sun */
    int shadow;                        /* the method in use (the scene's, or front when peel cannot run) */
    GLuint sun_layers_tex, sun_tau_tex, sun_opacity_fbo; /* peel: the opacity map, tiles of intervals */
    int sun_intervals;                 /* intervals present for the current sun direction */
    int need_sun_back;
    double white[3];                   /* white balance of the tone mapper (sky.h) */
    double phase_g_eff;                /* mean cosine of the phase function in use */
    double peak_f[3];                  /* weight of the chopped Mie peak per channel (0: analytic phase) */
    int sun_size;
    int sun_dirty;
    vec3 sun_right, sun_up;

    GLuint hull_vbo, hull_ibo, inst_vbo, hull_vao, empty_vao;
    int hull_indices;

    GLuint prog_sun, prog_sun_back, prog_sun_opacity, prog_depth, prog_cloud, prog_cloud_fs, prog_sky, prog_tonemap, prog_copy;

    GLuint hdr_fbo, hdr_tex, hdr_depth;
    int hdr_w, hdr_h;
    GLenum hdr_format;
};

void cu_log(const cu_renderer *r, cu_log_level level, const char *fmt, ...);
#endif
