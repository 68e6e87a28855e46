/* src/core/scene.h: the scene description (camera, sun, cloud, ellipsoids, quality knobs), filled by the parser
 * (scene_parse.c) through the key table (scene_keys.c), which holds every key's default and range. */
#ifndef CU_SCENE_H
#define CU_SCENE_H
#include "cumulo.h"

#define CU_MAX_ELLIPSOIDS 64          /* per cloud: the shaders' uniform arrays */
#define CU_MAX_SCENE_ELLIPSOIDS 4096   /* written in one file, over all its clouds */
#define CU_MAX_CLOUDS 1024             /* written in one file ([layer] sections generate any number more) */
#define CU_MAX_LAYERS 8
#define CU_MAX_INTERVALS 8
#define CU_TIME_TEXT 40                /* an ISO 8601 time with fraction and offset fits */

typedef struct cu_ellipsoid {
    double center[3]; /* m, world */
    double radii[3];  /* m, along world x, y, z */
} cu_ellipsoid;

/* One cloud written in the file: the [ellipsoid] sections after a [cloud] header (the first cloud also takes those
 * before any). A value it does not give (has_* = 0) is the first [cloud] section's, which the scene holds:
 * cu_scene_cloud() resolves them. */
typedef struct cu_cloud_spec {
    int first, count;         /* its ellipsoids in cu_scene.ell */
    int line;                 /* of its [cloud] header (0: none) */
    int has_density, has_boundary, has_wind, has_noise_offset, has_lifetime, has_life_phase, has_wrap;
    double density_cm3;       /* droplets per cm^3 in the core */
    double boundary_m;        /* h */
    double wind[2];           /* m/s toward east and north */
    double noise_offset[3];   /* m: where in the noise field the cloud sits (its own look) */
    double lifetime;          /* s: forms, matures and dissolves over this, then forms again (0: forever) */
    double life_phase;        /* 0..1: where in its life the cloud is at time 0 */
    double wrap;              /* m: side of the square about the origin it wraps around, fading at its border (0: no) */
} cu_cloud_spec;

/* One [layer]: a field of generated cumulus (src/core/layer.c). */
typedef struct cu_scene_layer {
    int type;                 /* cu_cumulus_type */
    double base, thickness;   /* m */
    double coverage;          /* 0..1 seen from straight above */
    double extent;            /* m: side of the square centred on the origin; clouds wrap around it */
    int seed;
    double wind[2];           /* m/s toward east and north */
    double lifetime;          /* s: each cloud's life (0: forever) */
    int line;                 /* of its header */
} cu_scene_layer;

typedef enum cu_phase_model { CU_PHASE_CORNETTE_SHANKS, CU_PHASE_HG, CU_PHASE_MIE } cu_phase_model;
typedef enum cu_profile { CU_PROFILE_TAPERED, CU_PROFILE_KOL } cu_profile;
typedef enum cu_ms_mode { CU_MS_NONE, CU_MS_OCTAVES, CU_MS_SLAB, CU_MS_COLLECTOR, CU_MS_DIFFUSION } cu_ms_mode;
typedef enum cu_sky_model { CU_SKY_PREETHAM, CU_SKY_CONSTANT } cu_sky_model;
typedef enum cu_method { CU_METHOD_KOL, CU_METHOD_UNIFORM } cu_method;
typedef enum cu_shadow_method { CU_SHADOW_PEEL, CU_SHADOW_FRONT, CU_SHADOW_OSM, CU_SHADOW_FOM } cu_shadow_method;

struct cu_scene {
    char name[256];
    unsigned char explicit_key[96]; /* by cu_scene_keys index: keys the file or --set gave (a preset leaves them) */
    /* [scene] */
    double time;              /* s: wind, life cycles and (with [sun] time_utc) the sun follow it */
    double origin_lat, origin_lon, origin_alt; /* degrees, degrees, m: where world (0, 0, 0) is on Earth (WGS84) */
    /* [output] */
    int width, height;
    double exposure;          /* multiplies radiance (kcd/m^2) before tone mapping */
    /* [camera] */
    double cam_pos[3], cam_look[3];
    double cam_fov;           /* degrees, vertical */
    /* [sun] */
    double sun_elevation, sun_azimuth; /* degrees */
    double latitude, longitude;        /* degrees, north and east positive: with time_utc, where the sun is seen */
    int has_time_utc;
    char time_utc[CU_TIME_TEXT];       /* ISO 8601: the sun's position at scene time 0 */
    double turbidity;         /* Preetham atmospheric turbidity */
    int has_sun_irradiance;
    double sun_irradiance[3]; /* klx-like units per channel, on a plane perpendicular to the rays */
    /* [sky] */
    cu_sky_model sky_model;
    double sky_color[3];      /* constant sky: radiance, linear RGB */
    double ground_albedo;
    /* [cloud] */
    double density_cm3;       /* droplets per cm^3 in the core (rho_0) */
    double droplet_radius_um; /* effective radius r_e */
    double boundary_m;        /* h */
    double noise_scale;       /* 1 = the noise tile spans 1000 m */
    cu_phase_model phase;
    double phase_g;
    cu_profile profile;
    double cloud_wind[2], cloud_noise_offset[3], cloud_lifetime, cloud_life_phase, cloud_wrap; /* every cloud's
                                                                                                 defaults */
    double boil;              /* m/s: how fast the noise drifts through every cloud, its direction turning */
    /* [cloud] ... [ellipsoid] ... (clouds[0]'s density and boundary are the fields above) */
    int n_clouds;
    cu_cloud_spec clouds[CU_MAX_CLOUDS];
    int n_ellipsoids;
    cu_ellipsoid ell[CU_MAX_SCENE_ELLIPSOIDS];
    /* [layer] ... */
    int n_layers;
    cu_scene_layer layers[CU_MAX_LAYERS];
    /* [quality] */
    int segments;             /* per ellipsoid crossed */
    double segment_ratio;     /* geometric ratio of consecutive segment lengths (1 = uniform) */
    double boundary_step;     /* m: a chord that never reaches the core is marched in steps of at most this (0: off) */
    double ramp_step;         /* m: a chord's entry ramp is marched in steps of at most this (0: Kol's share) */
    int cloud_downsample;     /* 1..4: the cloud pass at 1/N resolution, upsampled (pass_upsample.c) */
    double edge_refine;       /* with cloud_downsample > 1: pixels whose low-resolution neighbourhood differs by
                               * more than this are marched again at full resolution (pass_refine.c); 0: off */
    int temporal_grid;        /* 1..4: each frame marches 1 of G x G cloud pixels, the rest reprojected
                               * (pass_temporal.c); 1: every pixel every frame */
    double target_fps;        /* the frame budget (0: off): the renderer measures its frames and moves cloud_downsample
                               * and temporal_grid between theirs and the two below (src/core/budget.c) */
    int max_downsample, max_temporal_grid;
    int hull_tessellation;    /* latitude bands of the hull mesh (longitude = 2x) */
    int max_intervals;        /* merged in-cloud intervals per pixel */
    int noise;                /* 0/1 */
    int noise_octaves;        /* mip levels summed, 1..5 (Kol eq. 3.74 uses 5) */
    int noise_baked;          /* 0/1: the octaves' weighted sum baked into one 64^3 texture (2 reads, not 10) */
    int sun_map_size;         /* texels per side */
    int sun_map_frames;       /* a creeping sun's maps are made again over this many frames, a band of rows a frame */
    int lod_pixels;           /* a field's clouds smaller on screen than this get the far level of detail */
    int impostor_pixels;      /* a cloud narrower than this on screen is drawn from its impostor (0: never) */
    double impostor_degrees;  /* ... remade when the direction to it has turned by more than this */
    int sky_grid;             /* pixels: the sky worked out at the corners of cells this size and interpolated
                               * (pass_sky.c); 0: at every pixel */
    int cloud_shadows;        /* 0/1: clouds shade each other and the ground */
    int integration;          /* 0 energy-conserving segments, 1 Kol's trapezoids of F (eq. 3.20) */
    int preset;               /* cu_preset: high (the defaults), medium, low (presets.c) */
    cu_method method;         /* kol: analytic chords, few log-spaced segments, sun maps; uniform: the mainstream
                                 ray march (N uniform jittered steps, M steps toward the sun at each), the baseline */
    int uniform_steps;        /* method = uniform: steps along the view ray through the cloud */
    int uniform_sun_steps;    /* method = uniform: steps toward the sun from each sample */
    /* [light] */
    cu_shadow_method shadow;
    int sun_intervals;        /* most in-cloud intervals per sun ray the opacity map stores (layers / 2) */
    int sun_samples;          /* trapezoid segments per interval in the opacity pass (multiple of 4) */
    int sun_filter;           /* 0 nearest, 1 bilinear lookup of the opacity map */
    int sun_planar;           /* 0 off, 1 on, 2 auto: the opacity map read below each texel's entry (sunmap.glsl) */
    int osm_slices;           /* shadow = osm: opacity slices per sun ray (multiple of 4, 4..64) */
    int fom_coefficients;     /* shadow = fom: Fourier terms N (a_0..a_N-1, b_1..b_N-1) */
    /* [ms] */
    cu_ms_mode ms_mode;
    int ms_octaves;
    double ms_a, ms_b, ms_c;  /* Wrenninge: extinction, scattering and anisotropy factors per octave */
    int sky_light;            /* the isotropic sky-and-ground light term, 0/1 */
    int ms_iterations;        /* collector search: most steps (Bouthors: most converge within 10) */
    double ms_blur_m;         /* slab model: width of the box the slab maps are averaged over (Kol: a fixed LOD) */
    int ms_grid;              /* diffusion: cells along the longest side of a cloud's grid (src/core/ms_diffusion.h) */
    int ms_lobe;              /* diffusion: the forward lobe's own scatterings toward the eye (src/core/ms_lobe.h), 0/1 */
    int ms_frame_work;        /* diffusion: thousands of cell updates a frame for re-solves (src/gpu/pass_msd.h) */
    int ms_closure;           /* slab model: scale multiple scattering so a cloud sends out no more than it
                                 intercepts (src/gpu/pass_energy.c), 0/1 */
};

void cu_scene_defaults(cu_scene *s);
/* Extinction coefficient of the core in m^-1 (k_e = rho_0 * 2 pi r_e^2, Kol eq. 3.3). */
double cu_scene_core_extinction(const cu_scene *s);
/* The same for a density of rho cm^-3 with the scene's droplets. */
double cu_scene_extinction_at(const cu_scene *s, double density_cm3);
/* Cloud i of the file with every value resolved (its own, or the first [cloud] section's; the noise offset of a
 * cloud that gives none differs from cloud to cloud). */
cu_cloud_spec cu_scene_cloud(const cu_scene *s, int i);
/* The written clouds: n_clouds, or 1 for a scene built in code that filled ell[] but no cloud list. */
int cu_scene_cloud_count(const cu_scene *s);
#endif
