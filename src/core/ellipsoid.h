/* src/core/ellipsoid.h: ellipsoid geometry shared by the renderer, tests and path tracer: ray intersection, Kol's
 * radial distance, overlap (neighbour) masks, and the circumscribing hull mesh. */
#ifndef CU_ELLIPSOID_H
#define CU_ELLIPSOID_H
#include "vecmath.h"
#include <stdint.h>

/* Intersects the ray o + t d (d need not be unit) with the ellipsoid (c, r). Returns 1 and t0 <= t1 on a hit
 * (t0 == t1 for a tangent ray), 0 on a miss. Uses the cancellation-free form of the quadratic. */
int cu_ray_ellipsoid(vec3 o, vec3 d, vec3 c, vec3 r, double *t0, double *t1);
/* Kol's radial signed distance to the surface (positive inside): with q = p - c, s = |q / r|,
 * d = |q| (1/s - 1). At the centre it returns the smallest radius (the limit depends on direction). */
double cu_radial_distance(vec3 p, vec3 c, vec3 r);
/* Conservative overlap test (axis-aligned boxes); exact overlap implies this. */
int cu_ellipsoids_may_overlap(vec3 c0, vec3 r0, vec3 c1, vec3 r1);
/* The hull mesh's vertices lie on a sphere scaled by this factor so the polygonal hull contains the ellipsoid. */
double cu_hull_scale(int tessellation);
/* Unit-sphere hull with `tess` latitude bands and 2*tess longitudes: writes xyz floats and 16-bit indices
 * (triangles). Returns the counts through nv/ni; pass NULL buffers to query sizes. */
void cu_hull_mesh(int tess, float *verts, uint16_t *idx, int *nv, int *ni);
#endif
