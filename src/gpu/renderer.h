/* src/renderer.h: the renderer's private state, shared by the renderer's modules (passes, sun map). */
#ifndef CU_RENDERER_H
#define CU_RENDERER_H
#include "density.h"
#include "gl.h"
#include "noise.h"
#include "phase.h"
#include "scene.h"
#include "slabmodel.h"
#include "sky.h"
#include "vecmath.h"

struct cu_renderer {
    cu_gl gl;
    cu_desc desc;
    char data_dir[512];   /* desc.data_dir, or cu_default_data_dir() */
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
    GLuint sun_tex, sun_fbo;           /* front: the depth map; osm, fom: the RGBA32F map of sun_map_tiles tiles */
    int sun_map_tiles;                 /* osm: 1 + slices / 4; fom: 1 + N / 2 for N coefficients */
    int shadow;                        /* the method in use (the scene's, or front when peel cannot run) */
    GLuint sun_layers_tex, sun_tau_tex, sun_opacity_fbo; /* peel: the opacity map, tiles of intervals */
    int sun_intervals;                 /* intervals present for the current sun direction */
    int ms_mode;                       /* the multiple-scattering mode in use (the scene's, or a fallback) */
    cu_slab_model *slab_model;         /* the fitted slab tables (slab and collector modes) */
    struct cu_collector *collector;    /* the collector table (collector mode) */
    GLuint coll_tex;
    GLuint slab_tab_tex;               /* the tables as a texture (ms_slab.glsl) */
    GLuint slab_a_tex[2], slab_n_tex[2], slab_fbo[2]; /* slab maps from the sun [0] and the zenith [1] */
    int sky_slab_dirty;
    vec3 sky_right, sky_up;            /* the zenith map's axes */
    double white[3];                   /* white balance of the tone mapper (sky.h) */

    double peak_f[3];                  /* weight of the chopped Mie peak per channel (0: analytic phase) */
    int sun_size;
    int sun_dirty;
    vec3 sun_right, sun_up;

    GLuint hull_vbo, hull_ibo, inst_vbo, hull_vao, empty_vao;
    int hull_indices;

    GLuint prog_sun, prog_sun_opacity, prog_slab_map, prog_depth, prog_cloud, prog_cloud_fs, prog_sky, prog_tonemap, prog_copy;

    GLuint prog_energy, energy_tex, energy_fbo; /* the slab model's energy closure (energy.c) */
    double ms_gain[2];                 /* its gains on multiple scattering reflected and transmitted, <= 1 */
    int energy_valid;                  /* the gains were measured for these clouds... */
    vec3 energy_sun;                   /* ...and this sun direction */
    double energy_ss_w[8];             /* its weights for single scattering per band of angles (energy.c) */
    GLuint hdr_fbo, hdr_tex, hdr_depth;
    int hdr_w, hdr_h;
    GLenum hdr_format;
};

void cu_log(const cu_renderer *r, cu_log_level level, const char *fmt, ...);
/* Uniforms of density.glsl (ellipsoids, extinction, boundary, noise on texture unit 0). */
void cu_set_density_uniforms(cu_renderer *r, GLuint p);
/* Uniforms of cloud.frag for a camera at `cam` (cloud-local) with view-projection vp and its inverse. */
void cu_set_cloud_uniforms(cu_renderer *r, GLuint p, vec3 cam, const float *vp, const float *inv_vp);
/* Binds the cloud pass's textures (noise, phase, sun maps, slab maps) to their units. */
void cu_bind_cloud_textures(cu_renderer *r);
#endif
