/* src/gpu/renderer.h: the renderer's private state: the scene, the frame context the passes read, the passes, and
 * what is dirty. Only renderer.c (and tests that look inside) include it; no pass does. */
#ifndef CU_RENDERER_H
#define CU_RENDERER_H
#include "cloud_set.h"
#include "frame_budget.h"
#include "gpu_scene.h"
#include "pass_clock.h"
#include "pass_cloud.h"
#include "pass_energy.h"
#include "pass_refine.h"
#include "pass_shadow.h"
#include "pass_sky.h"
#include "pass_slab.h"
#include "pass_sun.h"
#include "pass_temporal.h"
#include "pass_tonemap.h"
#include "pass_upsample.h"

/* The clouds' optical depth toward the sun over a square of ground about the camera, for the clouds on one wind, in
 * a frame drifting with it (frame_ground.c); with more winds than maps the last holds the rest and does not drift. */
typedef struct cu_ground_map {
    vec3 wind;            /* m/s */
    int mixed;            /* clouds on other winds too: it does not drift */
    cu_target map;
    int ink[4];           /* the texels of map that can hold shadow (x0, y0, x1, y1, half-open; empty: none): every
                           * other texel is zero, so the sky pass reads no map there (pass_sky.c) */
    uint64_t sig;
    uint64_t scene;       /* the positions, in its drifting frame, of its clouds that shade its square */
    vec3 sun;             /* the sun it was made for */
    vec3 at;              /* its square: centre x, z (drifting frame) and side (m) */
    cu_target next;       /* quality.sun_map_frames > 1: made again a band of rows a frame, then swapped */
    uint64_t next_sig, next_scene;
    int next_ink[4];
    vec3 next_sun, next_at;
    int band;             /* its bands drawn so far (0: none under way) */
    long patches;         /* times only the texels of clouds whose density changed were made again */
} cu_ground_map;

struct cu_renderer {
    cu_gl gl;
    cu_desc desc;
    char data_dir[512];   /* desc.data_dir, or cu_default_data_dir() */
    char vendor[128], renderer_name[128], version[128];
    int is_gles;          /* 1: OpenGL ES context, 0: desktop GL core running the ES shaders (OSMesa) */

    int has_scene;
    cu_scene scene;
    cu_noise noise;
    int noise_ready;
    cu_cloud_set clouds;  /* every cloud of the scene, with its maps */
    cu_cloud none;        /* what ctx->cloud points at between clouds: empty */
    cu_sky sky;
    double time;          /* the scene time the clouds are at (s) */
    double wrap_cx, wrap_cz; /* cu_renderer_set_wrap_center's, kept across scenes */
    int profile, profiled;   /* cu_renderer_set_profiling; a frame was profiled */
    double pass_ms[CU_PASS_COUNT], prof_t; /* this frame's times per pass (ms), and the last mark's clock */
    cu_pass_clock prof;      /* how the passes are timed: GPU timestamps or the wall clock (profile.c) */
    int *order;           /* this frame's visible clouds, back to front (clouds.n) */
    double *order_key;
    cu_camera *cams;      /* each cloud's camera this frame */

    cu_gpu_scene ctx;     /* what the passes read: points at the above, holds the uploaded objects */
    cu_pass_sun pass_sun;
    cu_pass_slab pass_slab;
    cu_pass_energy pass_energy;
    cu_pass_sky pass_sky;
    cu_pass_cloud pass_cloud;
    cu_pass_cloud pass_cloud_far; /* a field's clouds smaller on screen than quality.lod_pixels (none: prog 0) */
    cu_pass_tonemap pass_tonemap;
    cu_pass_upsample pass_upsample; /* quality.cloud_downsample > 1 or temporal_grid > 1: the cloud image brought up */
    cu_pass_refine pass_refine;     /* quality.edge_refine with cloud_downsample > 1: its pixels again at full size */
    cu_pass_temporal pass_temporal; /* quality.temporal_grid > 1 (prog 0 otherwise) */
    int temporal_off_said;          /* the log line saying why the grid is not used this scene */
    int refine_off_said;            /* the log line saying edge_refine is off under the temporal grid */
    cu_pass_impostor pass_impostor; /* quality.impostor_pixels > 0 (prog 0 otherwise) */
    long impostors_made;  /* impostor images made since the scene was set (tests read it) */
    unsigned long frame_no; /* frames rendered by this renderer (impostors drawn in the frame before are current) */
    cu_pass_shadow pass_shadow;
    int shadows;          /* clouds shade each other and the ground (several clouds, or a ground to shade) */
    cu_ground_map ground[CU_GROUND_MAPS]; /* the clouds' shadow on the ground, a map a wind (frame_ground.c) */
    int ground_maps;      /* in use */
    int ground_unseen;    /* the last frame showed no ground: the maps were left as they were */
    vec3 frame_sun;       /* the sun of the last frame's maps (a sun that jumped since remakes them at once) */
    int frame_sun_valid;

    cu_frame_budget fb;   /* quality.target_fps, and this frame's resolution and grid (fb.d, fb.g) */

    /* Whether the picture has settled (cu_renderer_settled): what the last frame was drawn from, the frames still to
     * draw before the temporal grid has marched every pixel since it last changed, a map refresh left for later. */
    struct cu_frame_key {
        double view[16], proj[16], time;
        vec3 sun;
        int width, height, linear, clouds_only, downsample, grid;
        unsigned depth_texture;
    } last_key;
    int settle_left, maps_deferred, sparse_grid, drawn;
    long msd_work;             /* ms.mode = diffusion: cell updates left this frame for grids solved again (pass_msd.h) */

    int sun_dirty;        /* the sun moved or the scene changed: the energy closure is measured again */
};
#endif
