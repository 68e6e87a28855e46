/* src/core/cumulus_type.c: the cumulus types and one generated cloud of each (see cumulus_type.h). */
#include "cumulus_type.h"
#include <math.h>
#include <string.h>

/* Bit-identical layers need a*b+c rounded twice everywhere (see layer.c). */
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#endif

/* Sizes. Cloud footprint diameters follow N(D) ~ D^-b between D_min and D_max, b = CU_LAYER_SIZE_EXPONENT = 1.7.
 * Checked against the papers' abstracts:
 * - Neggers, Jonker & Siebesma 2003 (J. Atmos. Sci. 60, 1060-1074), LES of several shallow cumulus cases compared
 *   with observed populations: the cloud size density is a power law with exponent -1.70 at the smaller sizes,
 *   over roughly one order of magnitude, bounded above by a distinct scale break. (Their size is, from memory,
 *   the square root of the projected area, proportional to our D for a given shape.) The one decade and the break
 *   are why each type's D range below spans a decade or less and stops at D_max instead of running on.
 * - Sengupta, Welch, Navar, Berendes & Chen 1990 (J. Appl. Meteor. 29, 1245-), Landsat MSS cumulus fields: a mix
 *   of two power laws, slopes about 1.4-2.3 below 1 km diameter and 2.1-4.75 above. 1.7 lies in the small-cloud
 *   range, where most of our clouds are.
 * Quoted from memory, not checked here, and relied on only as "b of 1.7-2 with a break near 1 km":
 * - Benner & Curry 1998 (J. Geophys. Res. 103, 28753-28767), small tropical cumulus from Landsat and aircraft: a
 *   power law with b near 2.
 * - Cahalan & Joseph 1989 (Mon. Wea. Rev. 117, 261-272), Landsat cloud fields: cumulus sizes follow a power law
 *   that breaks near 0.5-1 km.
 * Inverse CDF of the truncated law with e = 1 - b: D = (D_min^e + u (D_max^e - D_min^e))^(1/e).
 *
 * Types. The WMO cloud atlas describes the species in words only (paraphrased from memory: humilis of slight
 * vertical extent, flattened; mediocris of moderate extent, tops with small protuberances; congestus markedly
 * sprouting, often of great vertical extent). The numbers are ours, chosen to read as those species, not measured:
 * - humilis D 200-1500 m, height/D 0.2-0.4: fair-weather cumulus a few hundred metres deep at most;
 * - mediocris D 300-2500 m, height/D 0.5-0.9;
 * - congestus D 500-4000 m, height/D 1.0-1.6 (towers as tall as wide or taller), clipped to the layer thickness.
 * Plank 1969 (Florida cumulus populations from aircraft photographs; J. Appl. Meteor. 8, 46-67 from memory) finds
 * in its abstract a considerable variance in how vertical and horizontal dimensions relate, which a per-cloud
 * aspect ratio drawn from a range reproduces. */

static const cu_cumulus_info type_info[CU_CUMULUS_TYPES] = {
    {"cumulus-humilis", 200.0, 1500.0, 0.2, 0.4, 3, 6},
    {"cumulus-mediocris", 300.0, 2500.0, 0.5, 0.9, 5, 10},
    {"cumulus-congestus", 500.0, 4000.0, 1.0, 1.6, 8, 16},
};

const cu_cumulus_info *cu_cumulus_type_info(cu_cumulus_type t)
{
    return (int)t >= 0 && (int)t < CU_CUMULUS_TYPES ? &type_info[t] : NULL;
}

int cu_cumulus_type_parse(const char *name, cu_cumulus_type *out)
{
    for (int i = 0; name && i < CU_CUMULUS_TYPES; i++)
        if (strcmp(name, type_info[i].name) == 0) {
            *out = (cu_cumulus_type)i;
            return 0;
        }
    return 1;
}

const char *cu_cumulus_type_name(cu_cumulus_type t)
{
    const cu_cumulus_info *ti = cu_cumulus_type_info(t);
    return ti ? ti->name : "unknown";
}


/* splitmix64 (Steele, Lea & Flood 2014): integer-only, so every machine draws the same stream. Each decision below
 * uses +, -, *, /, sqrt and floor (correctly rounded in IEEE 754) on these draws; the one pow, in the size draw,
 * is rounded to 1/16 m so a last-ulp difference between libms flips a size only with probability ~1e-13. */
uint64_t cu_layer_rng_next(uint64_t *s)
{
    uint64_t z = (*s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}
double cu_layer_rng_unit(uint64_t *s) { return (double)(cu_layer_rng_next(s) >> 11) * 0x1.0p-53; } /* [0, 1) */
double cu_layer_rng_range(uint64_t *s, double lo, double hi) { return lo + (hi - lo) * cu_layer_rng_unit(s); }
/* A unit vector in the xz plane, by rejection from the square (no sin/cos). */
void cu_layer_rng_dir(uint64_t *s, double *x, double *z)
{
    for (int i = 0; i < 64; i++) {
        double a = 2.0 * cu_layer_rng_unit(s) - 1.0, b = 2.0 * cu_layer_rng_unit(s) - 1.0, q = a * a + b * b;
        if (q > 1e-4 && q <= 1.0) {
            double k = 1.0 / sqrt(q);
            *x = a * k;
            *z = b * k;
            return;
        }
    }
    *x = 1.0;
    *z = 0.0;
}

double cu_layer_quantize(double d) { return floor(d * 16.0 + 0.5) / 16.0; }

double cu_layer_draw_size(uint64_t *s, double lo, double hi)
{
    const double e = 1.0 - CU_LAYER_SIZE_EXPONENT;
    double a = pow(lo, e), b = pow(hi, e);
    double d = cu_layer_quantize(pow(a + cu_layer_rng_unit(s) * (b - a), 1.0 / e));
    return d < lo ? lo : d > hi ? hi : d;
}


/* Appends an ellipsoid, forced into the cloud's bounds: radii >= the minimum, inside the footprint circle of radius
 * R, between the base and H; one whose bottom ends within 1 m of the base is put exactly on it and kept flat
 * (ry <= its horizontal radii), so the base row reads as one flat base. */
static void shape_add(cu_layer_shape *sh, double R, double H, double dx, double y, double dz, double rx, double ry, double rz)
{
    const double m = CU_LAYER_MIN_RADIUS;
    rx = fmax(rx, m);
    ry = fmax(ry, m);
    rz = fmax(rz, m);
    double rh = fmax(rx, rz);
    if (rh > R) { /* the central ellipsoid's anisotropy can take it past the footprint edge */
        rx *= R / rh;
        rz *= R / rh;
        rh = R;
    }
    double rho = sqrt(dx * dx + dz * dz);
    if (rho + rh > R) {
        double k = rho > 0 ? (R - rh) / rho : 0.0;
        dx *= k;
        dz *= k;
    }
    ry = fmin(ry, 0.5 * H);
    y = fmin(fmax(y, ry), H - ry);
    if (y - ry < 1.0) {
        ry = fmin(ry, fmin(rx, rz));
        y = ry;
    }
    int i = sh->n++;
    sh->off[i][0] = dx;
    sh->off[i][1] = y;
    sh->off[i][2] = dz;
    sh->r[i][0] = rx;
    sh->r[i][1] = ry;
    sh->r[i][2] = rz;
}

/* cos, sin of 2 pi / m: ring directions by rotation, without libm trigonometry. */
static const double ring_step[9][2] = {
    {1, 0}, {1, 0}, {-1, 0}, {-0.5, 0.86602540378443865}, {0, 1}, {0.30901699437494745, 0.95105651629515353},
    {0.5, 0.86602540378443865}, {0.62348980185873359, 0.7818314824680298}, {0.70710678118654757, 0.70710678118654757},
};

/* The base row: a wide, nearly round central ellipsoid (r0lo..r0hi of the footprint radius) and a ring of m smaller
 * ones reaching the same edge at varied heights, all with their bottoms on the base. Seen from above the cloud then
 * fills nearly all of its bounding circle. Coverage is the packing fraction of the circles times that fill, and a
 * random packing of circles cannot go far past 0.9, so a lumpier outline would put coverage 0.7 out of reach; the
 * renderer's boundary noise gives the outline its detail instead. */
static void shape_base_row(cu_layer_shape *sh, uint64_t *s, double R, double H, int m, double r0lo, double r0hi, double ryb)
{
    double ox, oz, k = cu_layer_rng_range(s, 0.98, 1.02), r0 = cu_layer_rng_range(s, r0lo, r0hi) * R;
    cu_layer_rng_dir(s, &ox, &oz);
    double o = cu_layer_rng_range(s, 0.0, 0.03) * R;
    shape_add(sh, R, H, ox * o, ryb, oz * o, r0 * k, ryb, r0 / k);
    double ux, uz;
    cu_layer_rng_dir(s, &ux, &uz);
    for (int j = 0; j < m; j++) {
        double rho = cu_layer_rng_range(s, 0.45, 0.6) * R, r = R - rho - cu_layer_rng_range(s, 0.0, 0.03) * R;
        double kk = cu_layer_rng_range(s, 0.9, 1.1), ry = ryb * cu_layer_rng_range(s, 0.8, 1.0);
        shape_add(sh, R, H, ux * rho, ry, uz * rho, r * kk, ry, r / kk);
        double c = ring_step[m][0], sn = ring_step[m][1], nx = c * ux - sn * uz, nz = sn * ux + c * uz;
        ux = nx;
        uz = nz;
    }
}

void cu_layer_build_shape(cu_cumulus_type t, double d, double thickness, uint64_t seed, cu_layer_shape *sh)
{
    const cu_cumulus_info *ti = cu_cumulus_type_info(t);
    uint64_t s = seed ^ 0x5851f42d4c957f2dULL;
    double R = 0.5 * d, H = fmin(cu_layer_rng_range(&s, ti->aspect_min, ti->aspect_max) * d, thickness);
    int n = ti->ell_min + (int)(cu_layer_rng_next(&s) % (uint64_t)(ti->ell_max - ti->ell_min + 1));
    sh->n = 0;
    if (t != CU_CUMULUS_CONGESTUS) {
        /* Domes: humilis is nearly all base row (flat, 60% of its height) under one cap; mediocris has a thinner
         * base row (40%) and half its ellipsoids stacked into a dome narrowing toward the top at H. */
        int hum = t == CU_CUMULUS_HUMILIS, nb = hum ? n - 1 : n / 2 + 1, nu = n - nb;
        shape_base_row(sh, &s, R, H, nb - 1, 0.97, 1.0, (hum ? 0.3 : 0.2) * H);
        for (int j = 0; j < nu; j++) {
            double f = (double)(j + 1) / nu, dx, dz;
            double rho = (0.25 * (1.0 - f) + 0.05) * R * cu_layer_rng_range(&s, 0.5, 1.0);
            double r = (0.62 - 0.27 * f) * R * cu_layer_rng_range(&s, 0.9, 1.1), k = cu_layer_rng_range(&s, 0.9, 1.1);
            double top = j == nu - 1 ? H : H * (0.62 + 0.38 * f), ry = 0.4 * top;
            cu_layer_rng_dir(&s, &dx, &dz);
            shape_add(sh, R, H, dx * rho, top - ry, dz * rho, r * k, ry, r / k);
        }
    } else {
        /* Towers: a thin base row (20% of the height), then 1-3 turrets of stacked, narrowing ellipsoids rising
         * from it, the first (central, widest) to H, the others to 50-80% of it. */
        int nb = 3 + (n - 8) / 3, nu = n - nb, nt = 1 + (nu >= 6) + (nu >= 9);
        double ryb = 0.1 * H;
        shape_base_row(sh, &s, R, H, nb - 1, 0.97, 1.0, ryb);
        for (int t2 = 0; t2 < nt; t2++) {
            int k = nu / nt + (t2 < nu % nt);
            double fx, fz, gx, gz;
            cu_layer_rng_dir(&s, &fx, &fz);
            cu_layer_rng_dir(&s, &gx, &gz);
            double foot = (t2 == 0 ? cu_layer_rng_range(&s, 0.0, 0.12) : cu_layer_rng_range(&s, 0.25, 0.4)) * R;
            double r0 = (t2 == 0 ? cu_layer_rng_range(&s, 0.38, 0.46) : cu_layer_rng_range(&s, 0.26, 0.34)) * R;
            double top = t2 == 0 ? H : H * cu_layer_rng_range(&s, 0.5, 0.8), span = top - ryb;
            double ry = fmax(span / (2.0 + 1.2 * (k - 1)), CU_LAYER_MIN_RADIUS);
            double step = k > 1 ? fmax((span - 2.0 * ry) / (k - 1), 0.0) : 0.0, aniso = cu_layer_rng_range(&s, 0.9, 1.1);
            for (int i = 0; i < k; i++) {
                double r = r0 * (1.0 - 0.45 * (k > 1 ? (double)i / (k - 1) : 0.0)), drift = 0.04 * R * i;
                shape_add(sh, R, H, fx * foot + gx * drift, ryb + ry + i * step, fz * foot + gz * drift, r * aniso,
                          ry, r / aniso);
            }
        }
    }
    /* Stretch horizontally so the bounding circle is exactly D: sizes then follow the drawn power law. */
    double bound = 0;
    for (int i = 0; i < sh->n; i++)
        bound = fmax(bound, sqrt(sh->off[i][0] * sh->off[i][0] + sh->off[i][2] * sh->off[i][2]) +
                                fmax(sh->r[i][0], sh->r[i][2]));
    double k = R / bound;
    sh->radius = 0;
    sh->height = 0;
    for (int i = 0; i < sh->n; i++) {
        sh->off[i][0] *= k;
        sh->off[i][2] *= k;
        sh->r[i][0] *= k;
        sh->r[i][2] *= k;
        sh->radius = fmax(sh->radius, sqrt(sh->off[i][0] * sh->off[i][0] + sh->off[i][2] * sh->off[i][2]) +
                                          fmax(sh->r[i][0], sh->r[i][2]));
        sh->height = fmax(sh->height, sh->off[i][1] + sh->r[i][1]);
    }
}

/* Area seen from above of the union of the footprint ellipses shrunk by margin: exact along x (interval union),
 * midpoint rule over 128 rows in z (relative error ~1e-3 for one cloud, far below the coverage tolerance). */
double cu_layer_shape_area(const cu_layer_shape *sh, double margin)
{
    enum { ROWS = 128 };
    double R = sh->radius, dz = 2.0 * R / ROWS, sum = 0;
    for (int row = 0; row < ROWS; row++) {
        double z = -R + (row + 0.5) * dz, lo[CU_LAYER_MAX_PER_CLOUD], hi[CU_LAYER_MAX_PER_CLOUD];
        int n = 0;
        for (int i = 0; i < sh->n; i++) {
            double a = sh->r[i][0] - margin, c = sh->r[i][2] - margin;
            if (a <= 0 || c <= 0)
                continue;
            double t = (z - sh->off[i][2]) / c;
            if (t * t >= 1.0)
                continue;
            double w = a * sqrt(1.0 - t * t), l = sh->off[i][0] - w;
            int j = n++;
            for (; j > 0 && lo[j - 1] > l; j--) {
                lo[j] = lo[j - 1];
                hi[j] = hi[j - 1];
            }
            lo[j] = l;
            hi[j] = sh->off[i][0] + w;
        }
        double end = -1e300;
        for (int i = 0; i < n; i++) {
            if (hi[i] <= end)
                continue;
            sum += hi[i] - fmax(lo[i], end);
            end = hi[i];
        }
    }
    return sum * dz;
}

