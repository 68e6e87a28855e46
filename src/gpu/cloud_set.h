/* src/gpu/cloud_set.h: the clouds a renderer draws: the scene's written clouds and the ones its [layer]s generate,
 * each with its own hull instances and sun and slab maps, moved by the wind and aged by its life cycle at the scene's
 * time (Kol 3.4.7) without rebuilding anything. */
#ifndef CU_CLOUD_SET_H
#define CU_CLOUD_SET_H
#include "gpu_scene.h"
#include "pass_impostor.h"
#include "pass_msd.h"
#include "target.h"

typedef struct cu_cloud_slot {
    cu_cloud cloud;            /* cloud-local geometry; cloud.origin is where the cloud is now */
    vec3 rest;                 /* its origin at time 0 */
    vec3 wind;                 /* m/s, world (x east, z south) */
    double wrap;               /* m: side of the square about the world origin it wraps around (0: it does not) */
    double lifetime, life_phase;
    double ke_rest;            /* core extinction when mature */
    double factor;             /* density now against mature: life cycle x border fade */
    int cycle;                 /* which life it is in (a new life is a new look: its noise offset moves) */
    vec3 noise_rest;           /* noise offset of life 0 */
    vec3 boil;                 /* m: how far the noise has drifted through the cloud (the view's noise) */
    vec3 maps_boil;            /* ... when its maps were made (they lag the view by at most CU_BOIL_STEP) */
    GLuint inst_vbo, vao;
    cu_target sun_map, slab_map[2];
    cu_sun_maps sun;
    cu_slab_maps slab;
    int has_maps;              /* the GL objects above exist */
    int map_size;              /* their texels a side (a level of detail: what the cloud covers on screen) */
    int want_size;             /* what this frame's view asks for */
    double pixels;             /* its diameter on screen this frame */
    double radius_xz;          /* m: its footprint's radius about its origin seen from above (the draw order's) */
    int maps_valid;            /* made for maps_sun and this look */
    int zenith_valid;
    vec3 maps_sun;
    /* quality.sun_map_frames > 1: the maps made again a band of rows a frame into these spares, lit by next_sun, and
     * swapped in with the last band (frame_maps.c); until then the cloud is lit by maps_sun */
    cu_target next_sun_map, next_slab_map[2];
    cu_sun_maps next_sun_maps;
    vec3 next_sun, next_boil;
    int next_band;             /* bands drawn so far (0: none under way) */
    int next_box[2];           /* the rows of next_sun's map that rays can meet the cloud in, shared out among the
                                * bands (cu_sun_band_rows), fixed at the first band */
    int next_zenith;           /* the zenith's slab map is made again too (the noise boiled on) */
    cu_target shadow;          /* other clouds' optical depth over its sun-map square (pass_shadow.c) */
    int has_shadow;            /* this frame: some other cloud shades it, and shadow holds their optical depth */
    uint64_t shadow_sig;       /* what shadow was made for: the casters, their densities, where they are (to a
                                * radius of this cloud), the sun, the map */
    double shadow_time;        /* the scene's time then: its casters on other winds have moved on since */
    int ground_q;              /* its density in 64ths as its ground map holds its shadow (frame_ground.c) */
    int ground_next_q;         /* ... as the map made again in bands does (-1: bands of different densities) */
    cu_cloud_msd msd;          /* ms.mode = diffusion: its diffusion grid (pass_msd.c) */
    cu_impostor imp;           /* quality.impostor_pixels: its image, when it is small on screen (frame_impostor.c) */
} cu_cloud_slot;

/* How far the noise may drift (m), and the sun creep (degrees), before a cloud's maps are remade (a few clouds a
 * frame, frame_maps.c); a sun that jumps farther than CU_SUN_MAP_JUMP in one frame, or that a cloud's maps lag by more
 * than cu_sun_map_lag, remakes them at once. Maps made over quality.sun_map_frames = K frames lag a sun turned v
 * degrees a frame by up to (2K - 1) v; the bound lets them keep up with a sun turned up to CU_SUN_MAP_JUMP a frame
 * (at K = 1: 1 degree, whole maps as soon as a cloud's fall a degree behind). */
#define CU_BOIL_STEP 4.0
#define CU_SUN_MAP_STEP 0.05
#define CU_SUN_MAP_JUMP 1.0
static inline double cu_sun_map_lag(int frames)
{
    return (2 * frames - 1) * CU_SUN_MAP_JUMP;
}
/* Whether the unit directions a and b lie more than `degrees` apart (what every map's sun is tested by). */
static inline int cu_sun_apart(vec3 a, vec3 b, double degrees)
{
    return v3_dot(a, b) < cos(degrees * CU_PI / 180.0);
}

typedef struct cu_cloud_set {
    cu_cloud_slot *slot;
    int n;
    double boil;               /* m/s ([cloud] boil) */
    double wrap_cx, wrap_cz;   /* m: the centre of the squares wrapping clouds wrap around (the viewer's, for an IG) */
    int num_ell;               /* the largest cloud's ellipsoid count (>= 1): what the programs are built for */
} cu_cloud_set;

/* The scene's clouds, CPU side (GL objects are made when a cloud is first drawn). */
int  cu_cloud_set_build(cu_cloud_set *cs, const cu_scene *s, const cu_noise *noise, cu_error *err);
void cu_cloud_set_free(cu_cloud_set *cs, const cu_gl *gl);
/* Deletes a cloud's sun and slab maps (they are made again at the next size asked for). */
void cu_cloud_slot_free_maps(cu_cloud_slot *sl, const cu_gl *gl);
/* Positions and densities at scene time t (s). */
void cu_cloud_set_at_time(cu_cloud_set *cs, double t);
/* Where a cloud is in its life, 0..1 (its fade; the density follows through cu_cloud_fade_density): forms over the
 * first fifth, mature, dissolves over the last fifth, smooth (C1) at both ends so nothing pops; 1 for lifetime 0. */
double cu_cloud_life(double t, double lifetime, double phase, int *cycle);
/* The density factor that makes a chord of optical depth min(tau0, 4) (tau0: the cloud's core extinction times its
 * radius) as opaque as r of its full opacity: a thick cloud's density must fall a long way before it thins at all,
 * so a fade linear in density keeps it opaque and then drops it within seconds; this one fades what is seen. */
double cu_cloud_fade_density(double r, double tau0);
/* The fade near the border of a wrapping layer: 0 on the border, 1 a fade width inside. */
double cu_cloud_border_fade(vec3 pos, double wrap, double fade_width);
#endif
