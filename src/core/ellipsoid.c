/* src/core/ellipsoid.c: ellipsoid intersection, distance, overlap and hull mesh (see ellipsoid.h). */
#include "ellipsoid.h"

int cu_ray_ellipsoid(vec3 o, vec3 d, vec3 c, vec3 r, double *t0, double *t1)
{
    vec3 q = v3_sub(o, c);
    vec3 ir = v3(1.0 / r.x, 1.0 / r.y, 1.0 / r.z);
    vec3 qs = v3_mul(q, ir), ds = v3_mul(d, ir);
    double A = v3_dot(ds, ds), B = 2.0 * v3_dot(qs, ds), C = v3_dot(qs, qs) - 1.0;
    if (!(A > 0))
        return 0;
    double disc = B * B - 4.0 * A * C;
    if (disc < 0)
        return 0;
    double sq = sqrt(disc);
    /* q = -(B + sign(B) sqrt(disc))/2 avoids subtracting nearly equal numbers (grazing rays, far cameras). */
    double qq = -0.5 * (B + (B >= 0 ? sq : -sq));
    double a, b;
    if (qq != 0) {
        a = qq / A;
        b = C / qq;
    } else { /* B = 0 and disc = 0: tangent through the axis */
        a = b = -B / (2 * A);
    }
    *t0 = a < b ? a : b;
    *t1 = a < b ? b : a;
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
