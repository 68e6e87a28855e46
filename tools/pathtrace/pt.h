/* tools/pathtrace/pt.h: the reference volumetric path tracer (delta tracking, ratio-tracked sun NEE, tabulated
 * phase sampling) as a library, so the CLI and the validation tests drive exactly the same integrator. */
#ifndef CU_PT_H
#define CU_PT_H
#include "cumulo.h"
#include "density.h"
#include "noise.h"
#include "phase.h"
#include "scene.h"
#include "sky.h"
#include "vecmath.h"
#include <stdint.h>

/* The renderer's noise seed (NOISE_SEED in src/gpu/renderer.c, private there); test_pt_cli.sh checks they agree. */
#define PT_NOISE_SEED 20130612u
/* Probability per vertex of the forward-peak sun strategy (README "Variance: the forward peak"). */
#define PT_GUIDE_DEFAULT 1.0

/* ---- random numbers: xoshiro256** seeded through splitmix64, one stream per pixel ---- */
typedef struct pt_rng {
    uint64_t s[4];
} pt_rng;
uint64_t pt_splitmix64(uint64_t *state);
/* Stream `stream` (e.g. a pixel index) of the run seeded with `seed`; streams are independent of thread count. */
void pt_rng_seed(pt_rng *r, uint64_t seed, uint64_t stream);
uint64_t pt_rng_next(pt_rng *r);
double pt_rng_uniform(pt_rng *r); /* [0, 1), 53 bits */

/* ---- phase function: the FULL function (P~ + P_p for Mie) per channel, as a density over theta ---- */
typedef struct pt_phase {
    int n;          /* grid nodes, theta_i = i * h */
    double h;       /* pi / (n - 1) */
    int mono;       /* all channels identical (HG, Cornette-Shanks): no spectral weights */
    double *f[3];   /* f_c(theta_i) = 2 pi sin(theta_i) p_c(theta_i) / norm_c, linear in theta between nodes */
    double *cdf[3]; /* cdf[c][i] = integral of f_c from 0 to theta_i (exact for the piecewise-linear f); cdf[n-1]=1 */
    double norm[3]; /* integral of 2 pi sin p over the sphere before normalisation (1 up to the table's quadrature) */
    double *gf, *gcdf; /* guide lobe: the green removed peak P_p normalised (NULL without a peak) */
} pt_phase;
int pt_phase_init(pt_phase *ph, const cu_phase_table *t, cu_error *err);
void pt_phase_free(pt_phase *ph);
/* Phase function value in sr^-1 for channel c at scattering angle theta (sin_theta = sin(theta) >= 0). */
double pt_phase_eval(const pt_phase *ph, int c, double theta, double sin_theta);
/* p_c for the angle between two unit vectors (propagation before and after scattering). */
void pt_phase_eval_dirs(const pt_phase *ph, vec3 a, vec3 b, double out[3]);
/* Samples an outgoing direction for propagation direction d from channel k's phase function and returns the three
 * channels' phase values (sr^-1) at the sampled angle in p. */
vec3 pt_phase_sample_channel(const pt_phase *ph, vec3 d, int k, pt_rng *rng, double p[3]);
/* One event of the same scheme with a uniformly chosen channel (tests): samples from the mixture (1/3) sum_c p_c and
 * returns the per-channel weights w_c = p_c / mixture (exactly 1 when mono) and, if pdf is not
 * NULL, the mixture's density in sr^-1. */
vec3 pt_phase_sample(const pt_phase *ph, vec3 d, pt_rng *rng, double w[3], double *pdf);
/* The sun-guide lobe (green P_p / f centred on axis): a sample and its density in sr^-1. Needs ph->gf. */
vec3 pt_phase_sample_peak(const pt_phase *ph, vec3 axis, pt_rng *rng);
double pt_phase_peak_pdf(const pt_phase *ph, vec3 axis, vec3 dir);

/* ---- the integrator ---- */
typedef enum pt_medium { PT_MEDIUM_CLOUD, PT_MEDIUM_SLAB } pt_medium;
typedef enum pt_env { PT_ENV_SCENE, PT_ENV_HEMISPHERES } pt_env;
typedef enum pt_mode { PT_MODE_RADIANCE, PT_MODE_TRANSMITTANCE } pt_mode;

typedef struct pt_ctx {
    cu_scene scene;           /* copy: the context does not depend on the caller's scene afterwards */
    cu_noise noise;
    cu_cloud cloud;           /* cloud.ke = cu_phase_table_extinction(), exactly as the renderer */
    cu_phase_table table;
    pt_phase phase;
    cu_sky sky;
    /* Medium: the scene's cloud, or (tests) an infinite slab -slab_thickness <= y <= 0 of constant extinction. */
    pt_medium medium;
    double slab_ke, slab_thickness;
    double majorant;          /* >= max extinction; tests raise it to exercise non-binary ratio tracking */
    /* Light: sun (directional, next-event estimation only) and the environment seen by escaping rays. */
    vec3 sun_dir;             /* unit, toward the sun */
    double sun_irr[3];        /* irradiance perpendicular to the rays */
    pt_env env;
    double env_up[3], env_down[3]; /* PT_ENV_HEMISPHERES: radiance for dir.y > 0 and dir.y <= 0 */
    int max_depth;            /* scattering events per path; a path reaching it is cut (counted, biased low) */
    uint64_t max_steps;       /* tracking steps (real and null collisions, shadow rays included) per path: a path
                                 reaching it is cut and counted, so no scene can keep a path going forever */
    double guide;             /* probability per vertex of the extra forward-peak sun estimate (Mie + sun; 0 = off) */
    /* Camera, cloud-local. */
    vec3 cam;
    mat4 inv_rot;             /* clip -> direction, as the renderer's sky pass */
    int width, height;
} pt_ctx;

typedef struct pt_counters {
    uint64_t paths, scatters, truncated, density_evals;
    uint64_t step_capped; /* paths cut at max_steps */
    uint64_t path_steps;  /* steps of the path being traced (pt_radiance and pt_transmittance reset it) */
} pt_counters;
/* Default of pt_ctx.max_steps. A path diffusing through optical thickness tau takes ~tau^2 scattering events, each
 * with a shadow ray of a few steps (ratio tracking's roulette): 1e5 covers tau ~ 150 along a whole random walk,
 * beyond which what a path carries is tiny, and bounds the legal extremes (radii 1e5 m, k_e 6e7 m^-1: tau 1e13,
 * where every step is a collision) at 1e5 extinction lookups per path. */
#define PT_MAX_STEPS 100000

/* Builds everything from a scene (data_dir holds mie_cloud.tbl). Returns 0, or 1 with a message. */
int pt_ctx_init(pt_ctx *c, const cu_scene *s, const char *data_dir, cu_error *err);
/* Rebuilds c (from pt_ctx_init) for scene s, keeping its noise texture (the costly part, the same for every scene);
 * the integrator's settings return to their defaults. Returns 0, or 1 with a message (c then needs pt_ctx_free). */
int pt_ctx_set_scene(pt_ctx *c, const cu_scene *s, const char *data_dir, cu_error *err);
void pt_ctx_free(pt_ctx *c);
/* Test hook: replace the cloud by a slab of optical thickness tau (thickness 1000 m, top at local y = 0). */
void pt_ctx_use_slab(pt_ctx *c, double tau);

/* Extinction k_e in m^-1 at a local position for the context's medium. */
double pt_extinction(const pt_ctx *c, vec3 p);
/* Local-space ray through the centre of pixel (x, y) (y = 0 top row), or jittered by (jx, jy) in [0,1). */
void pt_camera_ray(const pt_ctx *c, double px, double py, vec3 *o, vec3 *d);
/* Radiance arriving at o from direction -d (i.e. seen looking along d), one path sample. */
void pt_radiance(const pt_ctx *c, vec3 o, vec3 d, pt_rng *rng, double L[3], pt_counters *k);
/* Transmittance exp(-tau) from o along d to infinity, one ratio-tracking sample (unbiased). */
double pt_transmittance(const pt_ctx *c, vec3 o, vec3 d, pt_rng *rng, pt_counters *k);

typedef struct pt_render_opts {
    int width, height, spp, threads;
    uint64_t seed;
    int aa;           /* jitter inside the pixel instead of its centre */
    pt_mode mode;
    int progress;     /* progress bar with ETA on stderr */
} pt_render_opts;
/* Renders mean and standard error of the mean (rgb floats, top row first; se may be NULL). Returns 0 or 1. */
int pt_render(const pt_ctx *c, const pt_render_opts *o, float *mean, float *se, pt_counters *k, cu_error *err);
/* The whole job for a program that links the path tracer (the sweep): a context for scene s with the integrator's
 * defaults (max depth, forward-peak guide: what cumulo-pt runs without options), the camera at o's size (the scene's
 * output size is ignored), pt_render, and the context freed. data_dir holds mie_cloud.tbl. Returns 0, or 1 with a
 * message. */
int pt_render_scene(const cu_scene *s, const char *data_dir, const pt_render_opts *o, float *mean, float *se,
                    pt_counters *k, cu_error *err);

/* Writes k_e on an nx*ny*nz grid of voxel centres over the cloud's local AABB: raw float32 little-endian, x
 * fastest, plus a text header at path + ".txt". */
int pt_dump_density(const pt_ctx *c, const char *path, int nx, int ny, int nz, uint32_t noise_seed, cu_error *err);
#endif
