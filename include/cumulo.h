/* include/cumulo.h: the public C API of libcumulo, a real-time cumulus renderer for OpenGL ES 3.0 (Kol 2013,
 * Bouthors 2008).
 *
 * Usage (sokol-style: zero means default, the library never creates a context or prints):
 *     cu_desc desc = {0};                       // GL functions through dlsym, no logging
 *     cu_renderer *r; cu_scene *s; cu_error e;
 *     if (cu_scene_load(&s, "scenes/cumulus.scene", &e)) { fprintf(stderr, "%s\n", e.msg); ... }
 *     cu_renderer_create(&r, &desc, &e);        // needs a current GLES 3 context
 *     cu_renderer_set_scene(r, s, &e);
 *     cu_frame f = { .fbo = 0, .width = 640, .height = 480 };
 *     cu_render(r, &f, &e);                     // draws into the bound framebuffer
 *     cu_renderer_destroy(r); cu_scene_free(s);
 * Every function that can fail returns 0 on success and non-zero on failure with a one-line message in *err.
 */
#ifndef CUMULO_H
#define CUMULO_H
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct cu_renderer cu_renderer;
typedef struct cu_scene cu_scene;

typedef struct cu_error {
    char msg[512];
} cu_error;

typedef enum cu_log_level { CU_LOG_ERROR, CU_LOG_WARN, CU_LOG_INFO, CU_LOG_DEBUG } cu_log_level;
typedef void (*cu_log_fn)(void *user, cu_log_level level, const char *msg);
typedef void *(*cu_get_proc_fn)(void *user, const char *name);

typedef struct cu_desc {
    cu_get_proc_fn get_proc_address; /* GL entry points; NULL = look them up in the process (dlsym) */
    void *get_proc_user;
    cu_log_fn log;                   /* NULL = no logging */
    void *log_user;
    const char *data_dir;            /* the folder holding the tables (mie_cloud.tbl, slab_fit_bouthors.txt, ...);
                                        NULL = cu_default_data_dir() */
} cu_desc;

/* The library's version ("0.5.0"). */
const char *cu_version(void);
/* $CUMULO_DATA_DIR when it is set and not empty, else the folder `make install` put the tables in
 * (PREFIX/share/cumulo/data, fixed when the library was configured). */
const char *cu_default_data_dir(void);

/* ---- scenes (INI-style files, see scenes/cumulus.scene and README "Scene files") ---- */
int  cu_scene_load(cu_scene **out, const char *path, cu_error *err);
int  cu_scene_parse(cu_scene **out, const char *name, const char *text, size_t len, cu_error *err);
/* "section.key=value", as given to --set; errors name "--set" and the field. */
int  cu_scene_set(cu_scene *s, const char *assignment, cu_error *err);
void cu_scene_output_size(const cu_scene *s, int *width, int *height);
/* The scene's [camera]: position and look_at in world metres, vertical field of view in degrees. */
void cu_scene_camera(const cu_scene *s, double position[3], double look_at[3], double *fov_deg);
/* The scene's database origin ([scene] origin_latitude, origin_longitude in degrees, origin_altitude in metres above
 * mean sea level): where world (0, 0, 0) is on Earth, for hosts that send geodetic positions (cumulo ig). */
void cu_scene_origin(const cu_scene *s, double *latitude_deg, double *longitude_deg, double *altitude_m);
/* The scene's [camera] as a host would pass it in cu_frame: view (world -> eye) and a perspective projection for
 * the aspect ratio width / height with the given clip planes (column-major). Passing these gives the same image
 * as passing NULL. Fails for a non-positive or non-finite aspect or planes (0 < znear < zfar). */
int  cu_scene_camera_matrices(const cu_scene *s, double aspect, double znear, double zfar, float view[16],
                              float projection[16], cu_error *err);
/* The scene's [sun] latitude and longitude in degrees (north and east positive), where a host shows the sun of its
 * own clock (cu_solar_position_at). Returns 1 when the scene (or --set) gave either key, 0 when both are the defaults,
 * 0 N 0 E. */
int  cu_scene_sun_place(const cu_scene *s, double *latitude_deg, double *longitude_deg);
void cu_scene_free(cu_scene *s);
/* Replaces the scene's [layer]s by the clouds they generate, as written [cloud] sections (each with the layer's wind,
 * lifetime and wrap, and a life phase and noise offset of its own), so it renders exactly as before and a user can
 * edit them. Fails, the scene unchanged, beyond 1024 clouds or 4096 ellipsoids in all. */
int  cu_scene_expand(cu_scene *s, cu_error *err);
/* The scene as scene-file text that reads back to the same values, into buf (cap bytes, NUL-terminated): its
 * length, or 0 when it does not fit. */
size_t cu_scene_format(const cu_scene *s, char *buf, size_t cap);

/* ---- renderer ---- */
int  cu_renderer_create(cu_renderer **out, const cu_desc *desc, cu_error *err);
void cu_renderer_destroy(cu_renderer *r);
/* Copies the scene, builds the shader variants it needs and its GPU resources. */
int  cu_renderer_set_scene(cu_renderer *r, const cu_scene *s, cu_error *err);
/* The scene time in seconds ([scene] time when the scene is set): the clouds drift with their wind (wrapping around a
 * [layer]'s extent), form and dissolve through their life cycles. Nothing is rebuilt: a cloud's maps are remade
 * only when it starts a new life. Fails for a non-finite time or |t| > 1e9 s. */
int  cu_renderer_set_time(cu_renderer *r, double seconds, cu_error *err);
double cu_renderer_get_time(const cu_renderer *r);
/* The centre (world x, z in metres) of the squares that wrapping clouds wrap around: a [layer]'s extent and a
 * [cloud] wrap are about (0, 0) until this moves them. A layer is a torus, so a square about a travelling viewer
 * shows the same clouds where they overlap: an image generator keeps it on its eyepoint and flies through an endless
 * layer. Kept across cu_renderer_set_scene; nothing is rebuilt. Fails for non-finite or |x|, |z| > 1e8 m. */
int  cu_renderer_set_wrap_center(cu_renderer *r, double x, double z, cu_error *err);
/* Moves the sun (degrees); only the sun-dependent passes are redone on the next frame. */
int  cu_renderer_set_sun(cu_renderer *r, double elevation_deg, double azimuth_deg, cu_error *err);
void cu_renderer_get_sun(const cu_renderer *r, double *elevation_deg, double *azimuth_deg);
/* The sun from a UTC date and time (ISO 8601, "2026-06-21T12:00:00Z", offsets "+02:00" too; 1900..2100) and a place
 * (degrees, north and east positive): the solar position (NREL's SPA, 0.0003 deg) at that time plus the scene time,
 * so cu_renderer_set_time moves the sun too. Geometric elevation, azimuth from north toward east. */
int  cu_renderer_set_sun_utc(cu_renderer *r, const char *time_utc, double latitude_deg, double longitude_deg,
                             cu_error *err);
/* The same solar position without a renderer: elevation (refraction = 1: apparent, with the standard atmosphere's
 * refraction) and azimuth in degrees for a place at height_m above sea level. */
int  cu_solar_position_at(const char *time_utc, double latitude_deg, double longitude_deg, double height_m,
                          int refraction, double *elevation_deg, double *azimuth_deg, cu_error *err);
/* The energy closure's gain on the multiple scattering the slab model reflects (transmitted = 0) or transmits (1)
 * for the current sun: 1 when the cloud sends out no more than it intercepts, or when the mode is not the slab
 * model (src/gpu/pass_energy.c). Updated by cu_render when the sun or the clouds change. */
double cu_renderer_ms_gain(const cu_renderer *r, int transmitted);

typedef struct cu_frame {
    unsigned fbo;        /* framebuffer to draw into (0 = the default one) */
    int width, height;   /* viewport size in pixels; the frame covers (0, 0, width, height) of fbo */
    int linear;          /* 1: write linear radiance (needs a float colour target), 0: tone-mapped sRGB */
    /* The host's camera, per frame and free of cost (nothing is rebuilt when it moves). Both NULL: the scene's
     * [camera]. Both given: view is world -> eye (4x4, column-major, cumulo's world: metres, x east, y up, z south),
     * projection eye -> clip (column-major, OpenGL conventions: the eye looks down -z, clip z in [-w, w]). Any
     * perspective (bottom row (0, 0, -c, 0): any near and far, infinite far, asymmetric frusta) or orthographic
     * (bottom row (0, 0, 0, c)) projection; others are an error. Only the projection's x, y and w rows shape the
     * rays: cumulo rasterises its clouds with depth planes of its own, so the host's near and far never clip
     * a cloud, except that an orthographic view starts at the host's near plane. Reversed-Z projections work
     * (set depth_reversed for the depth texture). */
    const float *view;
    const float *projection;
    /* The host's depth: a GL depth texture (DEPTH_COMPONENT16/24/32F or DEPTH24_STENCIL8) of the frame's size holding
     * window depth under `projection` (glDepthRangef(0, 1)); 0 = none. The march stops at the host's surface, so
     * geometry inside a cloud is veiled only by the cloud in front of it. It may be the depth attachment of fbo:
     * cumulo samples it while drawing into its own target and never while fbo is bound. Its filtering and compare
     * mode are overridden by a sampler object while cumulo reads it, and left as they were. */
    unsigned depth_texture;
    int depth_reversed;  /* 1: depth is cleared to 0 and nearer is larger (GL_GREATER); 0: cleared to 1 */
    /* 1: no sky and no ground: the clouds alone, blended premultiplied over what fbo holds (tone-mapped like the
     * sky would be, or linear radiance with linear = 1). Pixels no cloud covers keep the host's colour exactly. */
    int clouds_only;
} cu_frame;
/* Draws one frame. Every GL state item listed in README "Embedding in your renderer" (framebuffer bindings,
 * program, vertex array, array buffer, renderbuffer, active texture and the textures and samplers of units 0-13,
 * viewport, blend, depth, stencil, cull face, scissor, colour mask, clear values, pixel alignment) is as the host
 * left it when this returns; so do cu_renderer_create, cu_renderer_set_scene and cu_renderer_set_sun. */
int  cu_render(cu_renderer *r, const cu_frame *f, cu_error *err);

/* 1 when drawing the last frame again (the same camera, size, output, sun and time) would not change the picture;
 * 0 while the temporal grid (quality.temporal_grid G) has pixels not marched since that last changed (G^2 - 1
 * frames after a change it did not redraw whole) or a cloud's maps or impostor wait for their turn (at most four of
 * each remade a frame), and before the first frame. A host that draws only when something changed (cumulo run on DRM/KMS and
 * headless) draws until this says 1. */
int  cu_renderer_settled(const cu_renderer *r);

/* ---- profiling: where a frame's time goes ---- */
enum { CU_PASS_MAPS, CU_PASS_SHADOWS, CU_PASS_ENERGY, CU_PASS_SKY, CU_PASS_CLOUDS, CU_PASS_UPSAMPLE, CU_PASS_TONEMAP,
       CU_PASS_COUNT };
/* A pass's name for reports: "maps" (the clouds' sun, slab and zenith maps), "shadows" (cloud-on-cloud and ground
 * shadow maps), "energy" (the energy closure), "sky", "clouds", "upsample" (quality.cloud_downsample's upsampling,
 * temporal_grid's resolve, and the sky pass that composites them into the output when it does), "tonemap";
 * NULL outside 0..CU_PASS_COUNT-1. */
const char *cu_pass_name(int pass);
/* 1: time every pass of each frame; 0: off, the default. By GPU timestamps where the context has them
 * (EXT_disjoint_timer_query's glQueryCounterEXT on GLES, GL 3.3 on desktop GL; read back at the end of cu_render,
 * which then waits for the GPU), else by the wall clock between glFinish calls (which serialise CPU and GPU, so a
 * profiled frame is slower than a plain one and its passes add up to a little less than it). */
void cu_renderer_set_profiling(cu_renderer *r, int on);
/* How the passes are timed: "GPU timestamps", "wall clock, glFinish between passes", or "not chosen yet" before the
 * first profiled frame. */
const char *cu_renderer_profiling_clock(const cu_renderer *r);
/* The last profiled frame's milliseconds per pass into ms[CU_PASS_COUNT]: 0, or 1 when none was profiled. */
int  cu_renderer_pass_times(const cu_renderer *r, double ms[CU_PASS_COUNT]);

/* ---- the frame budget: [quality] target_fps, max_downsample, max_temporal_grid ---- */
/* With a budget the renderer times every frame (GPU timer queries where the context has them, read back a few frames
 * later without waiting; else the wall clock and a glFinish at the end of cu_render) and draws the clouds at a
 * coarser resolution and a larger temporal grid while the median of 5 frames exceeds 1/target_fps, finer again when
 * it is under 3/4 of it; each change is logged. This gives the resolution (1/cloud_downsample) and temporal grid the
 * next frame is drawn at and the budget's last median frame time in ms (0 before the first): 0, or 1 when the scene
 * sets no budget (its own cloud_downsample and temporal_grid are given then). */
int  cu_renderer_budget(const cu_renderer *r, int *cloud_downsample, int *temporal_grid, double *frame_ms);

/* Image files for screenshots: RGBA8 pixels, top row first, as 8-bit PNG; RGB float pixels (linear radiance, top
 * row first) as PFM. Every write is checked, including the final flush and close (a full disk is an error). */
int  cu_write_png(const char *path, const unsigned char *rgba, int width, int height, cu_error *err);
int  cu_write_pfm(const char *path, const float *rgb, int width, int height, cu_error *err);

/* GL_VENDOR / GL_RENDERER / GL_VERSION of the context the renderer runs in, and the paths it chose. */
const char *cu_renderer_gl_string(const cu_renderer *r, int which /* 0 vendor, 1 renderer, 2 version */);

#ifdef __cplusplus
}
#endif
#endif
