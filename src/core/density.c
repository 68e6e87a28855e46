/* src/core/density.c: extinction field of a cloud of noisy ellipsoids (see density.h). */
#include "density.h"
#include <string.h>

double cu_sigmoid(double x)
{
    if (x <= 0) return 0;
    if (x >= 1) return 1;
    return x * x * x * (x * (x * 6.0 - 15.0) + 10.0);
}

void cu_cloud_build(cu_cloud *cl, const cu_scene *s, const cu_noise *noise)
{
    if (cu_scene_cloud_count(s) == 0) {
        cu_cloud_spec none = {0};
        none.density_cm3 = s->density_cm3;
        none.boundary_m = s->boundary_m;
        cu_cloud_build_spec(cl, s, &none, noise);
        return;
    }
    cu_cloud_spec c = cu_scene_cloud(s, 0);
    cu_cloud_build_spec(cl, s, &c, noise);
}

void cu_cloud_build_spec(cu_cloud *cl, const cu_scene *s, const cu_cloud_spec *spec, const cu_noise *noise)
{
    memset(cl, 0, sizeof *cl);
    const cu_ellipsoid *ell = &s->ell[spec->first];
    cu_cloud_build_ellipsoids(cl, s, ell, spec->count, spec->density_cm3, spec->boundary_m, spec->noise_offset, noise);
}

void cu_cloud_build_ellipsoids(cu_cloud *cl, const cu_scene *s, const cu_ellipsoid *ell, int n, double density_cm3,
                               double boundary_m, const double noise_offset_m[3], const cu_noise *noise)
{
    memset(cl, 0, sizeof *cl);
    if (n > CU_MAX_ELLIPSOIDS)
        n = CU_MAX_ELLIPSOIDS; /* the parser and the layer generator keep within it */
    vec3 lo = v3(1e300, 1e300, 1e300), hi = v3(-1e300, -1e300, -1e300);
    if (n == 0)
        lo = hi = v3(0, 0, 0);
    for (int i = 0; i < n; i++) {
        vec3 c = v3_from(ell[i].center), r = v3_from(ell[i].radii);
        lo = v3(fmin(lo.x, c.x - r.x), fmin(lo.y, c.y - r.y), fmin(lo.z, c.z - r.z));
        hi = v3(fmax(hi.x, c.x + r.x), fmax(hi.y, c.y + r.y), fmax(hi.z, c.z + r.z));
    }
    /* Kol eq. 3.13-3.15: the cloud centre is the middle of the extremities; we also compute in that frame so
     * that single-precision GPU maths keeps its digits for clouds 100 km away. */
    cl->origin = v3_scale(v3_add(lo, hi), 0.5);
    cl->n = n;
    cl->bound_radius = 0;
    for (int i = 0; i < cl->n; i++) {
        cl->c[i] = v3_sub(v3_from(ell[i].center), cl->origin);
        cl->r[i] = v3_from(ell[i].radii);
        double rmax = fmax(cl->r[i].x, fmax(cl->r[i].y, cl->r[i].z));
        cl->bound_radius = fmax(cl->bound_radius, v3_len(cl->c[i]) + rmax);
    }
    cl->bounds_min = v3_sub(lo, cl->origin);
    cl->bounds_max = v3_sub(hi, cl->origin);
    for (int i = 0; i < cl->n; i++) {
        cl->neighbours[i] = 0;
        for (int j = 0; j < cl->n; j++)
            if (cu_ellipsoids_may_overlap(cl->c[i], cl->r[i], cl->c[j], cl->r[j]))
                cl->neighbours[i] |= (uint64_t)1 << j;
    }
    cl->ke = cu_scene_extinction_at(s, density_cm3);
    cl->h = boundary_m;
    cl->profile = s->profile;
    cl->noise_on = s->noise && noise != NULL;
    cl->octaves = s->noise_octaves;
    cl->noise_freq = s->noise_scale / 1000.0;
    /* The noise is the cloud's own: anchored where it was built (plus its offset), so moving the cloud with the wind
     * moves its noise with it and its sun maps stay valid (the boil is a slow drift of its own, renderer.c). */
    vec3 o = v3_scale(v3_add(cl->origin, v3_from(noise_offset_m)), cl->noise_freq);
    cl->noise_offset = v3(o.x - floor(o.x), o.y - floor(o.y), o.z - floor(o.z));
    cl->noise = noise;
}

double cu_cloud_distance(const cu_cloud *cl, vec3 p, int all)
{
    double best = -1e300;
    if (all) {
        for (int j = 0; j < cl->n; j++)
            best = fmax(best, cu_radial_distance(p, cl->c[j], cl->r[j]));
        return best;
    }
    /* Find one ellipsoid containing p; only its neighbours can be non-negative there, so their max is the max. */
    for (int i = 0; i < cl->n; i++) {
        double di = cu_radial_distance(p, cl->c[i], cl->r[i]);
        if (di >= 0) {
            best = di;
            uint64_t m = cl->neighbours[i] & ~((uint64_t)1 << i);
            while (m) {
                int j = 0;
                while (!(m & ((uint64_t)1 << j)))
                    j++;
                m &= ~((uint64_t)1 << j);
                best = fmax(best, cu_radial_distance(p, cl->c[j], cl->r[j]));
            }
            return best;
        }
        best = fmax(best, di);
    }
    return best; /* outside every ellipsoid: the largest (least negative) distance */
}

double cu_cloud_noise(const cu_cloud *cl, vec3 p)
{
    double t[3] = {p.x * cl->noise_freq + cl->noise_offset.x, p.y * cl->noise_freq + cl->noise_offset.y,
                   p.z * cl->noise_freq + cl->noise_offset.z};
    return cu_noise_fractal(cl->noise, t, cl->octaves);
}

double cu_cloud_extinction(const cu_cloud *cl, vec3 p)
{
    double d = cu_cloud_distance(cl, p, 0);
    if (d < 0)
        return 0;
    if (d >= cl->h)
        return cl->ke;
    double u = d / cl->h; /* h > 0 here, since 0 <= d < h */
    double n = cl->noise_on ? cu_cloud_noise(cl, p) : 0.0;
    if (cl->profile == CU_PROFILE_KOL)
        return cl->ke * cu_sigmoid(u + n); /* Kol eq. 3.1 as printed */
    /* Tapered: the noise amplitude 4u(1-u) vanishes at the air (u = 0) and core (u = 1) borders, so the density is
     * continuous there. Eq. 3.1 as printed jumps at both borders (Kol §3.4.4 saw the seams and applied the sigmoid
     * twice); a jump is also what a 5-segment trapezoid integrates worst. */
    return cl->ke * cu_sigmoid(u + 4.0 * u * (1.0 - u) * n);
}

void cu_log_spacing(int n, double r, double *out)
{
    if (n < 1) n = 1;
    out[0] = 0;
    if (fabs(r - 1.0) < 1e-9) {
        for (int i = 1; i <= n; i++)
            out[i] = (double)i / n;
        return;
    }
    double rn = pow(r, n) - 1.0;
    for (int i = 1; i <= n; i++)
        out[i] = (pow(r, i) - 1.0) / rn;
    out[n] = 1.0;
}
