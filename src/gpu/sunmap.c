/* src/gpu/sunmap.c: sun-map geometry on the CPU (see sunmap.h). */
#include "sunmap.h"
#include <math.h>

void cu_sun_basis(vec3 d, vec3 *right, vec3 *up)
{
    vec3 ref = fabs(d.y) < 0.99 ? v3(0, 1, 0) : v3(1, 0, 0);
    *right = v3_norm(v3_cross(ref, d));
    *up = v3_cross(d, *right);
}

double cu_sun_radius(const cu_cloud *cl)
{
    return cl->bound_radius * 1.01 + 1.0;
}

/* An ellipsoid's shadow on a plane, seen along the plane's normal, reaches sqrt(sum (r_k u_k)^2) from its centre's
 * image along any unit u in the plane (the support function of the axis-aligned ellipsoid: an orthographic view). */
void cu_sun_map_texels(const cu_cloud *cl, vec3 right, vec3 up, double R, int size, int box[4])
{
    double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
    for (int i = 0; i < cl->n; i++) {
        vec3 r = cl->r[i], axis[2] = {right, up};
        for (int a = 0; a < 2; a++) {
            vec3 u = axis[a];
            double c = v3_dot(cl->c[i], u);
            double h = sqrt(r.x * r.x * u.x * u.x + r.y * r.y * u.y * u.y + r.z * r.z * u.z * u.z);
            lo[a] = fmin(lo[a], c - h);
            hi[a] = fmax(hi[a], c + h);
        }
    }
    for (int a = 0; a < 2; a++) {
        /* texel t's centre lies at ((t + 0.5) / size * 2 - 1) R: the first at or past lo, the last at or before hi */
        double t0 = floor((lo[a] / R + 1.0) * 0.5 * size - 0.5) - 1.0;
        double t1 = ceil((hi[a] / R + 1.0) * 0.5 * size - 0.5) + 2.0;
        box[a] = t0 < 0 ? 0 : t0 > size ? size : (int)t0;
        box[2 + a] = t1 < box[a] ? box[a] : t1 > size ? size : (int)t1;
    }
}

void cu_sun_band_rows(int size, int lo, int hi, int bands, int b, int rows[2])
{
    if (!(hi > lo)) {
        lo = 0;
        hi = size;
    }
    rows[0] = b <= 0 ? 0 : lo + (int)((long)(hi - lo) * b / bands);
    rows[1] = b >= bands - 1 ? size : lo + (int)((long)(hi - lo) * (b + 1) / bands);
}

int cu_union_intervals(const cu_cloud *cl, vec3 o, vec3 d, double *a, double *b, int max)
{
    double t0[CU_MAX_ELLIPSOIDS], t1[CU_MAX_ELLIPSOIDS];
    int n = 0;
    for (int i = 0; i < cl->n; i++) {
        double x, y;
        if (cu_ray_ellipsoid(o, d, cl->c[i], cl->r[i], &x, &y) && y > 0) {
            if (x < 0)
                x = 0;
            if (y <= x)
                continue;
            int k = n++;
            while (k > 0 && t0[k - 1] > x) {
                t0[k] = t0[k - 1];
                t1[k] = t1[k - 1];
                k--;
            }
            t0[k] = x;
            t1[k] = y;
        }
    }
    int m = 0;
    for (int k = 0; k < n;) {
        double lo = t0[k], hi = t1[k];
        k++;
        while (k < n && t0[k] <= hi) {
            if (t1[k] > hi)
                hi = t1[k];
            k++;
        }
        if (m < max) {
            a[m] = lo;
            b[m] = hi;
        }
        m++;
    }
    return m;
}

int cu_sun_max_intervals(const cu_cloud *cl, vec3 sun_dir, int grid)
{
    vec3 right, up;
    cu_sun_basis(sun_dir, &right, &up);
    double R = cu_sun_radius(cl), a[1], b[1];
    int best = 0;
    for (int y = 0; y < grid; y++)
        for (int x = 0; x < grid; x++) {
            double u = ((x + 0.5) / grid * 2 - 1) * R, v = ((y + 0.5) / grid * 2 - 1) * R;
            vec3 o = v3_add(v3_add(v3_scale(right, u), v3_scale(up, v)), v3_scale(sun_dir, 2 * R));
            int m = cu_union_intervals(cl, o, v3_scale(sun_dir, -1), a, b, 0);
            if (m > best)
                best = m;
        }
    return best;
}
