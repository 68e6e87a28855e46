/* src/gpu/gpu_scene.h: the frame context: what the passes read (the uploaded scene and its textures, the sun's
 * direction and axes, what earlier passes published) and the uniforms they share. The renderer fills it and orders
 * the passes; a pass reads it and never sees the renderer. */
#ifndef CU_GPU_SCENE_H
#define CU_GPU_SCENE_H
#include "density.h"
#include "gl.h"
#include "noise.h"
#include "scene.h"
#include "sky.h"
#include "slabmodel.h"
#include "sunmap.h"
#include "vecmath.h"

struct cu_collector;

/* The ground's shadow maps: clouds on up to this many winds move their shadows without remaking them. */
#define CU_GROUND_MAPS 2
/* Texture units the shaders agree on (cloud.frag, sunmap.glsl, ms_slab.glsl, density.glsl). */
/* The stencil bit of the pixels quality.edge_refine leaves to the upsampled image (pass_refine.h). */
#define CU_REFINE_SKIP 0x80u
enum { CU_UNIT_NOISE = 0, CU_UNIT_PHASE = 1, CU_UNIT_SUN_MAP = 2, CU_UNIT_SUN_TAU = 3, CU_UNIT_SLAB = 4,
       CU_UNIT_HOST_DEPTH = 10 /* after the slab pass's six */, CU_UNIT_SHADOW = 11 /* other clouds' shadow; the
       ground's in the sky pass */, CU_UNIT_SKY = 12 /* the sky pass's Perez tables */,
       CU_UNIT_CLOUDS = 13 /* the cloud image the sky pass composites (pass_sky.h: cu_pass_sky_draw_over) */,
       CU_UNIT_MSD = 14 /* the cloud's diffusion grid (ms.mode = diffusion, pass_msd.h) */,
       CU_UNIT_GROUND2 = 15 /* the sky pass's second ground shadow map */,
       CU_UNIT_REFINED = 14 /* quality.edge_refine's image, where the composites read it (sky.frag, upsample.frag): a 2D
       texture on the diffusion grid's unit, which holds a 3D one; a unit's targets are bound apart */ };

/* What the sun pass publishes (pass_sun.c): the map on CU_UNIT_SUN_MAP (peel: the interval layers; front: the
 * depth map; osm, fom: the tiles), peel's optical depths on CU_UNIT_SUN_TAU, and the intervals the map holds. peel
 * also keeps the texels (x0, y0, x1, y1, half-open, within a tile) each interval's tile was drawn over, so that the
 * later bands of a map made a band a frame draw the same (cu_sun_tile_boxes). */
typedef struct cu_sun_maps {
    GLuint map, tau;
    int intervals;
    int tile_box[CU_SUN_TILES_MAX][4];
} cu_sun_maps;

/* What the slab pass publishes (pass_slab.c): the fitted tables, the slab maps from the sun [0] and the zenith [1],
 * the zenith map's axes. model is NULL when the multiple-scattering mode is not the slab model. */
typedef struct cu_slab_maps {
    const cu_slab_model *model;
    const struct cu_collector *collector; /* collector mode only */
    GLuint tab, a[2], n[2], coll;
    vec3 sky_right, sky_up;
} cu_slab_maps;

/* The frame's camera, cloud-local (the big world offset removed in double precision on the CPU), built by
 * camera.c from the host's matrices or the scene's [camera]. */
typedef struct cu_camera {
    vec3 pos;                /* perspective: the eye */
    int ortho;               /* 1: parallel rays along view_dir, each from its pixel on the near plane */
    vec3 view_dir;           /* the view's forward direction */
    double znear;            /* of vp (cumulo's own depth planes around the clouds) */
    double near_reach;       /* perspective: the near plane's farthest point from the eye, in units of znear */
    int visible;             /* 0: the clouds' bounds lie wholly outside the view (its frustum and depths) */
    double ndc_rect[4];      /* where on screen the bounds can be: NDC x0, y0, x1, y1 within [-1, 1]; the whole
                              * screen where they reach behind the eye */
    int near_cuts;           /* 1: the host's near plane (orthographic) cuts the clouds' bounds */
    float vp[16], inv_vp[16];/* the host's x, y, w rows with cumulo's depth row */
    float inv_rot[16];       /* clip space to directions, the camera at the origin: the sky's */
    float rot_vp[16];        /* its inverse: directions (or points about the eye) to clip space */
    float host_inv_vp[16];   /* the host's own clip space to cloud-local: unprojects its depth texture */
} cu_camera;

/* The host's depth texture for this frame (0 = none) and the depth that means "no geometry". */
typedef struct cu_host_depth {
    GLuint tex;
    float clear;
} cu_host_depth;

typedef struct cu_gpu_scene {
    const cu_gl *gl;
    cu_log_fn log;
    void *log_user;
    int float_rt, half_rt;   /* RGBA32F, RGBA16F colour-renderable */

    const cu_scene *scene;
    const cu_cloud *cloud;   /* the cloud being drawn (one of the renderer's cloud set) */
    double ke_scale;         /* its density now against its maps' (life cycle, border fade): 1 for a still cloud */
    int num_ell;             /* ellipsoids the programs are built for: the scene's largest cloud */
    const cu_sky *sky;
    const cu_noise *noise;
    int shadow;              /* the sun-map method in use (the scene's, or front when the context cannot) */
    int ms_mode;             /* the multiple-scattering mode in use */
    double peak_f[3];        /* weight of the chopped Mie peak per channel (0: analytic phase) */
    double phase_asym;       /* mean cosine of the phase function without its peak (green) */
    double msd_f, msd_g;     /* ms.mode = diffusion's delta-M medium: f of the whole phase function, g' of the rest */
    double white[3];         /* the tone mapper's white balance (sky.h) */

    GLuint noise_tex, phase_tex;
    GLuint hull_vbo, hull_ibo, empty_vao; /* the hull mesh (instanced per ellipsoid); a VAO for full-screen draws */
    GLuint hull_vao;         /* the cloud being drawn's: its instances on the mesh */
    int hull_indices;

    /* The sun's frame: the sun maps are orthographic views along -sun_dir, 2 sun_R square, sun_size texels. */
    vec3 sun_dir, sun_right, sun_up;
    double sun_R;
    int sun_size;

    cu_camera camera;        /* this frame's */
    cu_host_depth host_depth;/* this frame's */
    int width, height;       /* this frame's size */
    int host_scale;          /* frame pixels per pixel of the pass drawing (quality.cloud_downsample), 1 or N */
    int refining;            /* quality.edge_refine's full-resolution pass (pass_refine.h): draw only where the
                              * stencil bit CU_REFINE_SKIP is clear */
    /* quality.temporal_grid: the cloud pass draws one pixel of each G x G block into a target of its own (pass_w x
     * pass_h; 0: the frame's, at 1/host_scale) with a projection shifted onto those pixels; px_map takes its pixels
     * to the cloud image's (xy * px_map.xy + px_map.zw), motion is how far the cloud now drawn moved since the last
     * frame (world x, z in m) */
    int pass_w, pass_h;
    float px_map[4];
    float motion[2];
    cu_sun_maps sun;         /* published by the sun pass */
    GLuint sun_ext;          /* the cloud's shadow from other clouds (pass_shadow.c; a 1x1 zero when none) */
    GLuint ground_tau[CU_GROUND_MAPS]; /* the ground's shadow maps, a wind each (frame_ground.c) or a texture of */
    vec3 ground_map[CU_GROUND_MAPS];   /* zeros; each one's centre (x, z, world) and side (m) */
    int ground_maps;                   /* how many of them hold shadows this frame (the first ones) */
    double ground_ink[CU_GROUND_MAPS][4]; /* where on the ground each can be other than zero: world x0, z0, x1, z1
                                           * (x1 < x0: nowhere) */
    cu_slab_maps slab;       /* published by the slab pass */
    GLuint msd_tex;          /* the cloud's diffusion grid (pass_msd.c), its cloud-local corner and extent (m) */
    vec3 msd_lo, msd_size;
    double ms_gain[2];       /* published by the energy closure: gains on reflected, transmitted multiple scattering */
    GLenum hdr_format;       /* published by the tone map: the HDR target's format */
} cu_gpu_scene;

void cu_gpu_log(const cu_gpu_scene *ctx, cu_log_level level, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Sets sun_dir (from the sky), its axes and the maps' half-size. */
void cu_gpu_scene_set_sun(cu_gpu_scene *ctx);

/* The uniform location in p, or -1 (setting -1 is a no-op: a variant that compiled a uniform out costs nothing). */
GLint cu_gpu_loc(const cu_gl *gl, GLuint p, const char *name);
/* Points sampler `name` of p at texture unit `unit`, once after linking (a program keeps its uniforms). */
void cu_gpu_unit(const cu_gl *gl, GLuint p, const char *name, int unit);

/* density.glsl (and sun_depth.frag's ellipsoids). Looking up also points u_noise at CU_UNIT_NOISE. */
typedef struct cu_density_locs {
    GLint ell_c, ell_ir, ke, h, noise_freq, noise_offset, noise_mean;
} cu_density_locs;
void cu_density_locs_get(const cu_gl *gl, GLuint p, cu_density_locs *l);
void cu_density_uniforms(const cu_gpu_scene *ctx, const cu_density_locs *l);

/* The sun's frame (sunmap.glsl, the sun passes, sky.frag's u_sun_dir). Looking up also points the sun-map samplers
 * at their units. */
typedef struct cu_sun_locs {
    GLint dir, right, up, R, size, intervals, tau_scale;
} cu_sun_locs;
void cu_sun_locs_get(const cu_gl *gl, GLuint p, cu_sun_locs *l);
/* The one place the sun's direction and axes reach the shaders. */
void cu_sun_uniforms(const cu_gpu_scene *ctx, const cu_sun_locs *l);

/* The asymmetry parameter the shadows' two-stream transmission takes: the scene's g for an analytic phase, the Mie
 * table's value (0.86 for r_e = 6 um) for Mie. */
double cu_shadow_g(const cu_gpu_scene *ctx);
/* What the sky and cloud passes multiply their radiance by (see gpu_scene.c). */
void cu_out_scale(const cu_gpu_scene *ctx, float s[3]);
/* The largest value the sky and cloud passes store (see gpu_scene.c). */
float cu_out_max(const cu_gpu_scene *ctx);
#endif
