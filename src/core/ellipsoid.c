/* src/core/ellipsoid.c: ellipsoid intersection, distance, overlap and hull mesh (see ellipsoid.h). */
#include "ellipsoid.h"

int cu_ray_ellipsoid(vec3 o, vec3 d, vec3 c, vec3 r, double *t0, double *t1)
{
    /* In the ellipsoid's unit-sphere frame, from the point of closest approach (t_c, |q_c|), as cast_ray in
     * density.glsl: 1 - |q_c|^2 keeps its digits where B^2 - 4AC of the textbook quadratic cancels (a camera far
     * away relative to the radius), and no term is a product of two large ones (B^2 overflowed for radii 1e-100,
     * and its NaN interval kept the path tracer's delta tracking from ever reaching the interval's end). */
    vec3 ir = v3(1.0 / r.x, 1.0 / r.y, 1.0 / r.z);
    vec3 qs = v3_mul(v3_sub(o, c), ir), ds = v3_mul(d, ir);
    double A = v3_dot(ds, ds);
    if (!(A > 0) || !isfinite(A))
        return 0;
    double tc = -v3_dot(qs, ds) / A;
    vec3 qc = v3_add(qs, v3_scale(ds, tc));
    double h2 = 1.0 - v3_dot(qc, qc);
    if (!(h2 >= 0) || !isfinite(tc)) /* a miss, or terms out of range: never a NaN interval */
        return 0;
    double hw = sqrt(h2 / A);
    *t0 = tc - hw;
    *t1 = tc + hw;
    return 1;
}

double cu_radial_distance(vec3 p, vec3 c, vec3 r)
{
    vec3 q = v3_sub(p, c);
    double len = v3_len(q);
    double s = v3_len(v3(q.x / r.x, q.y / r.y, q.z / r.z));
    if (s < 1e-12) {
        double m = r.x < r.y ? r.x : r.y;
        return m < r.z ? m : r.z;
    }
    return len / s - len;
}

int cu_ellipsoids_may_overlap(vec3 c0, vec3 r0, vec3 c1, vec3 r1)
{
    return fabs(c0.x - c1.x) <= r0.x + r1.x && fabs(c0.y - c1.y) <= r0.y + r1.y && fabs(c0.z - c1.z) <= r0.z + r1.z;
}

double cu_hull_scale(int tess)
{
    /* A UV sphere with n_lat bands and n_lon = 2 n_lat slices has its flattest facet centre at distance
     * cos(pi/(2 n_lat)) * cos(pi/n_lon) from the centre; dividing by that puts every facet outside the unit sphere. */
    double a = CU_PI / (2.0 * tess), b = CU_PI / (2.0 * tess);
    return 1.0 / (cos(a) * cos(b)) * 1.001;
}

void cu_hull_mesh(int tess, float *verts, uint16_t *idx, int *nv, int *ni)
{
    int nlat = tess, nlon = 2 * tess;
    double k = cu_hull_scale(tess);
    int v = 0, n = 0;
    for (int i = 0; i <= nlat; i++) {
        double th = CU_PI * i / nlat;
        for (int j = 0; j <= nlon; j++) {
            double ph = 2.0 * CU_PI * j / nlon;
            if (verts) {
                /* Poles stay at radius k too: the pole caps are fans whose facets also need to contain the sphere. */
                verts[3 * v + 0] = (float)(k * sin(th) * cos(ph));
                verts[3 * v + 1] = (float)(k * cos(th));
                verts[3 * v + 2] = (float)(k * sin(th) * sin(ph));
            }
            v++;
        }
    }
    for (int i = 0; i < nlat; i++)
        for (int j = 0; j < nlon; j++) {
            int a = i * (nlon + 1) + j, b = a + nlon + 1;
            if (idx) {
                idx[n + 0] = (uint16_t)a; idx[n + 1] = (uint16_t)b; idx[n + 2] = (uint16_t)(a + 1);
                idx[n + 3] = (uint16_t)(a + 1); idx[n + 4] = (uint16_t)b; idx[n + 5] = (uint16_t)(b + 1);
            }
            n += 6;
        }
    *nv = v;
    *ni = n;
}
