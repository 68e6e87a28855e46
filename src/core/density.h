/* src/core/density.h: the cloud's extinction field (Kol eqs. 3.1-3.3 with the radial distance to the ellipsoid union),
 * built once from a scene; the CPU twin of the shader's density, shared with tests and the path tracer. */
#ifndef CU_DENSITY_H
#define CU_DENSITY_H
#include "ellipsoid.h"
#include "noise.h"
#include "scene.h"
#include <stdint.h>

typedef struct cu_cloud {
    vec3 origin;                      /* world position of the local frame (centre of the ellipsoids' bounds) */
    int n;
    vec3 c[CU_MAX_ELLIPSOIDS];        /* centres, local */
    vec3 r[CU_MAX_ELLIPSOIDS];        /* radii */
    uint64_t neighbours[CU_MAX_ELLIPSOIDS]; /* bit j set: ellipsoid j may overlap i (i itself included) */
    vec3 bounds_min, bounds_max;      /* local AABB of the union */
    double bound_radius;              /* radius of a sphere about the local origin containing the union */
    double ke;                        /* core extinction, m^-1 */
    double h;                         /* boundary thickness, m */
    cu_profile profile;
    int noise_on, octaves;
    double noise_freq;                /* texture tiles per metre */
    vec3 noise_offset;                /* fract(origin * noise_freq), so local coordinates keep precision */
    const cu_noise *noise;
} cu_cloud;

/* The scene's first cloud (none: an empty cloud). */
void cu_cloud_build(cu_cloud *cl, const cu_scene *s, const cu_noise *noise);
/* A resolved cloud of the file (cu_scene_cloud). */
void cu_cloud_build_spec(cu_cloud *cl, const cu_scene *s, const cu_cloud_spec *spec, const cu_noise *noise);
/* Any n <= CU_MAX_ELLIPSOIDS ellipsoids (world) with the scene's droplets, profile and noise settings. */
void cu_cloud_build_ellipsoids(cu_cloud *cl, const cu_scene *s, const cu_ellipsoid *ell, int n, double density_cm3,
                               double boundary_m, const double noise_offset_m[3], const cu_noise *noise);
/* Kol eq. 3.2: s(x) = 6x^5 - 15x^4 + 10x^3, clamped to [0,1]. */
double cu_sigmoid(double x);
/* Signed radial distance to the union (max over ellipsoids). all = 1 uses every ellipsoid, 0 the neighbour lists
 * (identical results; the test proves it). */
double cu_cloud_distance(const cu_cloud *cl, vec3 p_local, int all);
/* Extinction coefficient k_e(p) in m^-1 at a local position. */
double cu_cloud_extinction(const cu_cloud *cl, vec3 p_local);
/* Fractal noise in [-1,1] at a local position. */
double cu_cloud_noise(const cu_cloud *cl, vec3 p_local);
/* Segment boundaries in geometric progression (ratio r >= 1, shortest first): x_i = (r^i - 1)/(r^N - 1),
 * i = 0..N, written to out[N+1] as fractions of the chord; r = 1 gives uniform spacing. */
void cu_log_spacing(int n, double ratio, double *out);
#endif
