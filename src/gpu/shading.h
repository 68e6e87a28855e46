/* src/gpu/shading.h: the uniforms and textures of shaders_gles/cloud.frag (with ms_octaves.glsl, ms_slab.glsl,
 * ms_collector.glsl), shared by the programs built from it: the cloud pass (hulls, full screen) and the energy closure. */
#ifndef CU_SHADING_H
#define CU_SHADING_H
#include "gpu_scene.h"

typedef struct cu_shading_locs {
    cu_density_locs density;
    cu_sun_locs sun;
    GLint viewproj, inv_viewproj, cam, bound_R, seg_ratio, boundary_step, ramp_step, phase_n, sun_irr, sky_rad, ground_rad, ms_abc, ms_g,
        peak_f, ms_gain, out_scale, out_max;
    GLint slab_t, slab_thv, slab_thl, slab_th, slab_lod, sky_right, sky_up, coll_t, coll_thl, coll_thv, coll_phi;
    GLint ortho, view_dir, inv_viewport, host_depth_on, host_inv_vp, host_clear, host_scale, shadow_g;
    GLint px_map, motion, msd_lo, msd_size, msd_dm;
} cu_shading_locs;

/* Looks every location up once, after linking, and points the samplers at their texture units. */
void cu_shading_locs_get(const cu_gl *gl, GLuint p, cu_shading_locs *l);
/* Uses p and sets everything for a camera at `cam` (cloud-local) with view-projection vp and its inverse. */
void cu_shading_uniforms(const cu_gpu_scene *ctx, GLuint p, const cu_shading_locs *l, vec3 cam, const float *vp,
                         const float *inv_vp);
/* Only the camera (the energy closure's views differ in nothing else). */
void cu_shading_camera(const cu_gpu_scene *ctx, const cu_shading_locs *l, vec3 cam, const float *vp,
                       const float *inv_vp);
/* The frame's view (orthographic or not, its size) and the host's depth, for the cloud pass's programs. */
void cu_shading_frame(const cu_gpu_scene *ctx, const cu_shading_locs *l);
/* Binds noise, phase, sun maps and slab maps to their units; leaves unit 0 active. */
void cu_shading_bind(const cu_gpu_scene *ctx);
#endif
