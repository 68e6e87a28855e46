/* src/core/layer.c: generated cumulus layers (see layer.h): power-law cloud sizes, ellipsoid clusters with flat
 * bases, and non-overlapping placement on a torus, largest first. */
#include "layer.h"
#include "error.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Bit-identical layers need a*b+c rounded twice everywhere: GCC in ISO C mode (-std=c99) never fuses it into an
 * FMA, clang does unless told (GCC rejects the pragma under -Werror, hence the guard). */
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
static uint64_t rng_next(uint64_t *s)
{
    uint64_t z = (*s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}
static double rng_unit(uint64_t *s) { return (double)(rng_next(s) >> 11) * 0x1.0p-53; } /* [0, 1) */
static double rng_range(uint64_t *s, double lo, double hi) { return lo + (hi - lo) * rng_unit(s); }
/* A unit vector in the xz plane, by rejection from the square (no sin/cos). */
static void rng_dir(uint64_t *s, double *x, double *z)
{
    for (int i = 0; i < 64; i++) {
        double a = 2.0 * rng_unit(s) - 1.0, b = 2.0 * rng_unit(s) - 1.0, q = a * a + b * b;
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

static double quantize(double d) { return floor(d * 16.0 + 0.5) / 16.0; }

static double draw_size(uint64_t *s, double lo, double hi)
{
    const double e = 1.0 - CU_LAYER_SIZE_EXPONENT;
    double a = pow(lo, e), b = pow(hi, e);
    double d = quantize(pow(a + rng_unit(s) * (b - a), 1.0 / e));
    return d < lo ? lo : d > hi ? hi : d;
}

/* One cloud's ellipsoids relative to its footprint centre: off = (dx, height of the centre above the base, dz). */
typedef struct shape {
    int n;
    double off[CU_LAYER_MAX_PER_CLOUD][3], r[CU_LAYER_MAX_PER_CLOUD][3];
    double radius, height;
} shape;

/* Appends an ellipsoid, forced into the cloud's bounds: radii >= the minimum, inside the footprint circle of radius
 * R, between the base and H; one whose bottom ends within 1 m of the base is put exactly on it and kept flat
 * (ry <= its horizontal radii), so the base row reads as one flat base. */
static void shape_add(shape *sh, double R, double H, double dx, double y, double dz, double rx, double ry, double rz)
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
static void shape_base_row(shape *sh, uint64_t *s, double R, double H, int m, double r0lo, double r0hi, double ryb)
{
    double ox, oz, k = rng_range(s, 0.98, 1.02), r0 = rng_range(s, r0lo, r0hi) * R;
    rng_dir(s, &ox, &oz);
    double o = rng_range(s, 0.0, 0.03) * R;
    shape_add(sh, R, H, ox * o, ryb, oz * o, r0 * k, ryb, r0 / k);
    double ux, uz;
    rng_dir(s, &ux, &uz);
    for (int j = 0; j < m; j++) {
        double rho = rng_range(s, 0.45, 0.6) * R, r = R - rho - rng_range(s, 0.0, 0.03) * R;
        double kk = rng_range(s, 0.9, 1.1), ry = ryb * rng_range(s, 0.8, 1.0);
        shape_add(sh, R, H, ux * rho, ry, uz * rho, r * kk, ry, r / kk);
        double c = ring_step[m][0], sn = ring_step[m][1], nx = c * ux - sn * uz, nz = sn * ux + c * uz;
        ux = nx;
        uz = nz;
    }
}

static void build_shape(cu_cumulus_type t, double d, double thickness, uint64_t seed, shape *sh)
{
    const cu_cumulus_info *ti = &type_info[t];
    uint64_t s = seed ^ 0x5851f42d4c957f2dULL;
    double R = 0.5 * d, H = fmin(rng_range(&s, ti->aspect_min, ti->aspect_max) * d, thickness);
    int n = ti->ell_min + (int)(rng_next(&s) % (uint64_t)(ti->ell_max - ti->ell_min + 1));
    sh->n = 0;
    if (t != CU_CUMULUS_CONGESTUS) {
        /* Domes: humilis is nearly all base row (flat, 60% of its height) under one cap; mediocris has a thinner
         * base row (40%) and half its ellipsoids stacked into a dome narrowing toward the top at H. */
        int hum = t == CU_CUMULUS_HUMILIS, nb = hum ? n - 1 : n / 2 + 1, nu = n - nb;
        shape_base_row(sh, &s, R, H, nb - 1, 0.97, 1.0, (hum ? 0.3 : 0.2) * H);
        for (int j = 0; j < nu; j++) {
            double f = (double)(j + 1) / nu, dx, dz;
            double rho = (0.25 * (1.0 - f) + 0.05) * R * rng_range(&s, 0.5, 1.0);
            double r = (0.62 - 0.27 * f) * R * rng_range(&s, 0.9, 1.1), k = rng_range(&s, 0.9, 1.1);
            double top = j == nu - 1 ? H : H * (0.62 + 0.38 * f), ry = 0.4 * top;
            rng_dir(&s, &dx, &dz);
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
            rng_dir(&s, &fx, &fz);
            rng_dir(&s, &gx, &gz);
            double foot = (t2 == 0 ? rng_range(&s, 0.0, 0.12) : rng_range(&s, 0.25, 0.4)) * R;
            double r0 = (t2 == 0 ? rng_range(&s, 0.38, 0.46) : rng_range(&s, 0.26, 0.34)) * R;
            double top = t2 == 0 ? H : H * rng_range(&s, 0.5, 0.8), span = top - ryb;
            double ry = fmax(span / (2.0 + 1.2 * (k - 1)), CU_LAYER_MIN_RADIUS);
            double step = k > 1 ? fmax((span - 2.0 * ry) / (k - 1), 0.0) : 0.0, aniso = rng_range(&s, 0.9, 1.1);
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
static double shape_area(const shape *sh, double margin)
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

/* A drawn cloud before placement. */
typedef struct draw {
    double d;
    uint64_t seed;
    int index;
} draw;

static int draw_desc(const void *a, const void *b)
{
    const draw *x = a, *y = b;
    if (x->d != y->d)
        return x->d > y->d ? -1 : 1;
    return (x->index > y->index) - (x->index < y->index);
}

/* The placement state: the torus, a uniform grid of cells listing every cloud whose footprint's bounding box
 * touches the cell, and the layer being filled. */
typedef struct placer {
    double L, cs;
    int nc;
    int *head, *next, *who, n_entries, cap_entries;
    int *stamp, stamp_id; /* per cloud: the pocket search that last saw it, so a pair is tried once per search */
    cu_layer *out;
    int cap_clouds, cap_ell;
    uint64_t rng;
    double margin, base, thickness;
    cu_cumulus_type type;
} placer;

/* Tangent placement leaves this much gap (m), so rounding never turns a touch into an overlap. */
#define GAP 1e-3

static double wrap(double x, double L)
{
    x -= L * floor(x / L + 0.5);
    if (x >= 0.5 * L)
        x -= L;
    if (x < -0.5 * L)
        x += L;
    return x;
}

static int cell_of(const placer *p, double x)
{
    int i = (int)floor((x + 0.5 * p->L) / p->cs);
    i %= p->nc;
    return i < 0 ? i + p->nc : i;
}

static int is_free(const placer *p, double x, double z, double r)
{
    int n = (int)floor(2.0 * (r + GAP) / p->cs) + 2;
    if (n > p->nc)
        n = p->nc;
    int i0 = cell_of(p, x - r - GAP), j0 = cell_of(p, z - r - GAP);
    for (int a = 0; a < n; a++)
        for (int b = 0; b < n; b++) {
            int cell = ((j0 + b) % p->nc) * p->nc + (i0 + a) % p->nc;
            for (int e = p->head[cell]; e >= 0; e = p->next[e]) {
                const cu_layer_cloud *c = &p->out->clouds[p->who[e]];
                double dx = wrap(x - c->center[0], p->L), dz = wrap(z - c->center[2], p->L), rr = r + c->radius + GAP;
                if (dx * dx + dz * dz < rr * rr)
                    return 0;
            }
        }
    return 1;
}

static int insert(placer *p, int id)
{
    const cu_layer_cloud *c = &p->out->clouds[id];
    int n = (int)floor(2.0 * c->radius / p->cs) + 2;
    if (n > p->nc)
        n = p->nc;
    int i0 = cell_of(p, c->center[0] - c->radius), j0 = cell_of(p, c->center[2] - c->radius);
    for (int a = 0; a < n; a++)
        for (int b = 0; b < n; b++) {
            if (p->n_entries == p->cap_entries) {
                int cap = p->cap_entries ? 2 * p->cap_entries : 4096;
                int *nx = realloc(p->next, sizeof *nx * (size_t)cap);
                if (!nx)
                    return 1;
                p->next = nx;
                int *w = realloc(p->who, sizeof *w * (size_t)cap);
                if (!w)
                    return 1;
                p->who = w;
                p->cap_entries = cap;
            }
            int cell = ((j0 + b) % p->nc) * p->nc + (i0 + a) % p->nc, e = p->n_entries++;
            p->who[e] = id;
            p->next[e] = p->head[cell];
            p->head[cell] = e;
        }
    return 0;
}

/* Finds a free spot for a footprint of radius r: uniform darts first (random sequential adsorption), then pockets
 * tangent to a random placed cloud A and one of its neighbours B (the two circle-circle intersections of the
 * circles about A and B widened by r), which find the last gaps of a crowded layer where darts almost never land. */
static int find_spot(placer *p, double r, double *x, double *z)
{
    enum { DARTS = 32, POCKETS = 24 };
    for (int k = 0; k < DARTS; k++) {
        *x = -0.5 * p->L + rng_unit(&p->rng) * p->L;
        *z = -0.5 * p->L + rng_unit(&p->rng) * p->L;
        if (is_free(p, *x, *z, r))
            return 1;
    }
    for (int k = 0; k < POCKETS && p->out->n_clouds > 0; k++) {
        const cu_layer_cloud *a = &p->out->clouds[rng_next(&p->rng) % (uint64_t)p->out->n_clouds];
        double ra = a->radius + r + 2.0 * GAP, ux, uz;
        /* A alone first: a spot touching it in a random direction. */
        rng_dir(&p->rng, &ux, &uz);
        *x = wrap(a->center[0] + ux * ra, p->L);
        *z = wrap(a->center[2] + uz * ra, p->L);
        if (is_free(p, *x, *z, r))
            return 1;
        p->stamp_id++;
        p->stamp[a - p->out->clouds] = p->stamp_id;
        int n = (int)floor(2.0 * (ra + r) / p->cs) + 2;
        if (n > p->nc)
            n = p->nc;
        int i0 = cell_of(p, a->center[0] - ra - r), j0 = cell_of(p, a->center[2] - ra - r);
        for (int ci = 0; ci < n; ci++)
            for (int cj = 0; cj < n; cj++) {
                int cell = ((j0 + cj) % p->nc) * p->nc + (i0 + ci) % p->nc;
                for (int e = p->head[cell]; e >= 0; e = p->next[e]) {
                    if (p->stamp[p->who[e]] == p->stamp_id)
                        continue;
                    p->stamp[p->who[e]] = p->stamp_id;
                    const cu_layer_cloud *b = &p->out->clouds[p->who[e]];
                    double rb = b->radius + r + 2.0 * GAP;
                    double dx = wrap(b->center[0] - a->center[0], p->L), dz = wrap(b->center[2] - a->center[2], p->L);
                    double d2 = dx * dx + dz * dz, d = sqrt(d2);
                    if (!(d > 0) || d >= ra + rb || d <= fabs(ra - rb))
                        continue;
                    /* Along AB to the chord of the two circles, then +-h across it. */
                    double t = (ra * ra - rb * rb + d2) / (2.0 * d), h2 = ra * ra - t * t;
                    if (!(h2 > 0))
                        continue;
                    double h = sqrt(h2), ex = dx / d, ez = dz / d;
                    for (int sgn = -1; sgn <= 1; sgn += 2) {
                        *x = wrap(a->center[0] + ex * t - sgn * ez * h, p->L);
                        *z = wrap(a->center[2] + ez * t + sgn * ex * h, p->L);
                        if (is_free(p, *x, *z, r))
                            return 1;
                    }
                }
            }
    }
    return 0;
}

static int add_cloud(placer *p, const shape *sh, uint64_t seed, double x, double z)
{
    cu_layer *o = p->out;
    if (o->n_clouds == p->cap_clouds) {
        int cap = p->cap_clouds ? 2 * p->cap_clouds : 256;
        cu_layer_cloud *c = realloc(o->clouds, sizeof *c * (size_t)cap);
        if (!c)
            return 1;
        o->clouds = c;
        int *st = realloc(p->stamp, sizeof *st * (size_t)cap);
        if (!st)
            return 1;
        memset(st + p->cap_clouds, 0, sizeof *st * (size_t)(cap - p->cap_clouds));
        p->stamp = st;
        p->cap_clouds = cap;
    }
    while (o->n_ell + sh->n > p->cap_ell) {
        int cap = p->cap_ell ? 2 * p->cap_ell : 1024;
        cu_layer_ellipsoid *e = realloc(o->ell, sizeof *e * (size_t)cap);
        if (!e)
            return 1;
        o->ell = e;
        p->cap_ell = cap;
    }
    cu_layer_cloud *c = &o->clouds[o->n_clouds];
    c->center[0] = x;
    c->center[1] = p->base;
    c->center[2] = z;
    c->radius = sh->radius;
    c->height = sh->height;
    c->first = o->n_ell;
    c->count = sh->n;
    c->seed = seed;
    for (int i = 0; i < sh->n; i++) {
        cu_layer_ellipsoid *e = &o->ell[o->n_ell++];
        e->center[0] = x + sh->off[i][0];
        e->center[1] = p->base + sh->off[i][1];
        e->center[2] = z + sh->off[i][2];
        for (int k = 0; k < 3; k++)
            e->radii[k] = sh->r[i][k];
    }
    return insert(p, o->n_clouds++);
}

/* Radius of the largest footprint centred at (x, z) that stays clear of every placed cloud, capped at rmax (only
 * clouds within rmax matter, and they are all listed in the cells of that box); negative inside a cloud. */
static double free_radius(const placer *p, double x, double z, double rmax)
{
    int n = (int)floor(2.0 * rmax / p->cs) + 2;
    if (n > p->nc)
        n = p->nc;
    int i0 = cell_of(p, x - rmax), j0 = cell_of(p, z - rmax);
    double best = rmax;
    for (int a = 0; a < n; a++)
        for (int b = 0; b < n; b++) {
            int cell = ((j0 + b) % p->nc) * p->nc + (i0 + a) % p->nc;
            for (int e = p->head[cell]; e >= 0; e = p->next[e]) {
                const cu_layer_cloud *c = &p->out->clouds[p->who[e]];
                double dx = wrap(x - c->center[0], p->L), dz = wrap(z - c->center[2], p->L);
                best = fmin(best, sqrt(dx * dx + dz * dz) - c->radius - 2.0 * GAP);
                if (best < 0)
                    return best;
            }
        }
    return best;
}

/* Places a cloud of diameter d. Where no spot takes it whole, it shrinks to the largest hole among random probes
 * (a greedy gap filling that packs far denser than shrinking by a fixed factor and searching again), or is dropped
 * when no hole takes D_min. Returns 1 placed (*area: its visible area; *d_out: the size placed, *shrunk set when
 * below d), 0 dropped, -1 out of memory. */
static int place(placer *p, double d, uint64_t seed, double d_min, double *area, double *d_out, int *shrunk)
{
    enum { PROBES = 64 };
    shape sh;
    double x, z;
    build_shape(p->type, d, p->thickness, seed, &sh);
    if (!find_spot(p, sh.radius, &x, &z)) {
        *shrunk = 1;
        double best = -1, bx = 0, bz = 0;
        for (int k = 0; k < PROBES; k++) {
            double px = -0.5 * p->L + rng_unit(&p->rng) * p->L, pz = -0.5 * p->L + rng_unit(&p->rng) * p->L;
            double r = free_radius(p, px, pz, 0.5 * d);
            if (r > best) {
                best = r;
                bx = px;
                bz = pz;
            }
        }
        /* The shape's radius is d/2 to rounding; 1e-9 of slack keeps it inside the hole. */
        double nd = floor(2.0 * best * (1.0 - 1e-9) * 16.0) / 16.0;
        if (nd < d_min)
            return 0;
        d = nd;
        build_shape(p->type, d, p->thickness, seed, &sh);
        x = bx;
        z = bz;
        if (!is_free(p, x, z, sh.radius))
            return 0;
    }
    if (add_cloud(p, &sh, seed, x, z))
        return -1;
    *area = shape_area(&sh, p->margin);
    *d_out = d;
    return 1;
}

/* Resizes the cloud (d, seed) so its visible area is about `want` (<= its area a at d): area goes nearly as D^2,
 * the margin and the minimum radii bend that, so a few secant steps. Never below d_min. */
static double fit_size(const placer *p, double d, uint64_t seed, double a, double want, double d_min, double *a_out)
{
    for (int it = 0; it < 4 && a > 0 && want > 0; it++) {
        double nd = fmax(quantize(d * sqrt(want / a)), d_min);
        if (nd == d)
            break;
        shape sh;
        build_shape(p->type, nd, p->thickness, seed, &sh);
        d = nd;
        a = shape_area(&sh, p->margin);
        if (d == d_min)
            break;
    }
    *a_out = a;
    return d;
}

static int check_range(cu_error *err, const char *field, double v, double lo, double hi, const char *unit)
{
    if (isfinite(v) && v >= lo && v <= hi)
        return 0;
    if (hi == HUGE_VAL)
        return cu_fail(err, "layer: %s = %g%s must be a finite number >= %g%s", field, v, unit, lo, unit);
    return cu_fail(err, "layer: %s = %g%s is outside [%g, %g]%s", field, v, unit, lo, hi, unit);
}

static void layer_empty(cu_layer *l)
{
    l->clouds = NULL;
    l->ell = NULL;
    l->n_clouds = l->n_ell = 0;
}

void cu_layer_free(cu_layer *l)
{
    if (!l)
        return;
    free(l->clouds);
    free(l->ell);
    layer_empty(l);
}

int cu_layer_generate(const cu_layer_spec *spec, cu_layer *out, cu_error *err)
{
    if (!out)
        return cu_fail(err, "layer: no layer to fill");
    layer_empty(out);
    if (!spec)
        return cu_fail(err, "layer: no spec");
    const cu_cumulus_info *ti = cu_cumulus_type_info(spec->type);
    if (!ti)
        return cu_fail(err, "layer: type = %d is not a cumulus type (cumulus-humilis, cumulus-mediocris, "
                            "cumulus-congestus)", (int)spec->type);
    if (check_range(err, "base", spec->base, CU_LAYER_BASE_MIN, CU_LAYER_BASE_MAX, " m") ||
        check_range(err, "thickness", spec->thickness, CU_LAYER_THICKNESS_MIN, CU_LAYER_THICKNESS_MAX, " m") ||
        check_range(err, "coverage", spec->coverage, 0.0, 1.0, "") ||
        check_range(err, "extent", spec->extent, CU_LAYER_EXTENT_MIN, CU_LAYER_EXTENT_MAX, " m") ||
        check_range(err, "margin", spec->margin, 0.0, HUGE_VAL, " m"))
        return 1;
    if (spec->coverage == 0)
        return 0;
    const double L = spec->extent, target = spec->coverage * L * L;
    /* D_max is clipped to half the square, so a footprint stays clear of its own periodic images. */
    const double d_min = ti->d_min, d_max = fmin(ti->d_max, 0.5 * L);
    if (d_max < d_min)
        return cu_fail(err, "layer: extent = %g m is too small for %s, whose smallest clouds are %g m across "
                            "(extent >= %g m)", L, ti->name, d_min, 2.0 * d_min);
    if (spec->margin >= 0.5 * d_max)
        return cu_fail(err, "layer: margin = %g m hides every %s cloud (their largest radius here is %g m)",
                       spec->margin, ti->name, 0.5 * d_max);

    placer p;
    memset(&p, 0, sizeof p);
    p.L = L;
    p.out = out;
    p.margin = spec->margin;
    p.base = spec->base;
    p.thickness = spec->thickness;
    p.type = spec->type;
    p.rng = spec->seed ^ 0xd1b54a32d192ed03ULL;
    uint64_t size_rng = spec->seed;

    /* 1. Draw sizes until their visible areas sum to the target; the cloud that would overshoot is resized to the
     * deficit (or, if that is below D_min, kept at D_min only when that lands closer). */
    draw *dr = NULL;
    int nd = 0, cap = 0, rc = 1;
    double sum = 0;
    for (;;) {
        if (nd == CU_LAYER_MAX_CLOUDS) {
            cu_fail(err, "layer: coverage %g over %g m x %g m of %s needs more than %d clouds", spec->coverage, L, L,
                    ti->name, CU_LAYER_MAX_CLOUDS);
            goto fail;
        }
        double d = draw_size(&size_rng, d_min, d_max);
        uint64_t seed = rng_next(&size_rng);
        shape sh;
        build_shape(spec->type, d, spec->thickness, seed, &sh);
        double a = shape_area(&sh, spec->margin);
        int last = sum + a >= target;
        if (last) {
            d = fit_size(&p, d, seed, a, target - sum, d_min, &a);
            if (sum + a - target > target - sum)
                break;
        }
        if (nd == cap) {
            cap = cap ? 2 * cap : 256;
            draw *nw = realloc(dr, sizeof *nw * (size_t)cap);
            if (!nw)
                goto oom;
            dr = nw;
        }
        dr[nd].d = d;
        dr[nd].seed = seed;
        dr[nd].index = nd;
        nd++;
        sum += a;
        if (last)
            break;
    }

    /* 2. Place them largest first, as dart throwing fills space best that way. */
    qsort(dr, (size_t)nd, sizeof *dr, draw_desc);
    p.cs = fmax(d_min, L / 2048.0);
    p.nc = (int)floor(L / p.cs);
    if (p.nc < 1)
        p.nc = 1;
    p.cs = L / p.nc;
    p.head = malloc(sizeof *p.head * (size_t)p.nc * (size_t)p.nc);
    if (!p.head)
        goto oom;
    for (long i = 0; i < (long)p.nc * p.nc; i++)
        p.head[i] = -1;
    double placed = 0, cap_d = d_max;
    int shrunk = 0;
    for (int i = 0; i < nd; i++) {
        double a, dp;
        int s0 = 0, r = place(&p, dr[i].d, dr[i].seed, d_min, &a, &dp, &s0);
        if (r < 0)
            goto oom;
        if (s0) {
            shrunk = 1;
            cap_d = fmin(cap_d, r ? dp : d_min);
        }
        if (r)
            placed += a;
    }

    /* 3. Where clouds had to shrink or were dropped, the layer is short: fill the gaps with new draws no larger
     * than the size that stopped fitting, until the target is met, 32 clouds in a row find no room even at D_min
     * (saturation: what coverage near 1 ends at), or the cloud limit. */
    for (int misses = 0; shrunk && misses < 32 && out->n_clouds < CU_LAYER_MAX_CLOUDS && placed < target;) {
        double d = draw_size(&size_rng, d_min, cap_d), a, dp;
        uint64_t seed = rng_next(&size_rng);
        shape sh;
        build_shape(spec->type, d, spec->thickness, seed, &sh);
        a = shape_area(&sh, spec->margin);
        int last = placed + a >= target;
        if (last) {
            d = fit_size(&p, d, seed, a, target - placed, d_min, &a);
            if (placed + a - target > target - placed)
                break;
        }
        int s0 = 0, r = place(&p, d, seed, d_min, &a, &dp, &s0);
        if (r < 0)
            goto oom;
        if (s0)
            cap_d = fmin(cap_d, r ? dp : d_min);
        misses = r ? 0 : misses + 1;
        if (r)
            placed += a;
        if (r && last && !s0)
            break;
    }
    rc = 0;
    goto done;
oom:
    cu_fail(err, "layer: out of memory");
fail:
    cu_layer_free(out);
done:
    free(dr);
    free(p.head);
    free(p.next);
    free(p.who);
    free(p.stamp);
    return rc;
}

double cu_layer_coverage(const cu_layer *l, const cu_layer_spec *spec, int grid)
{
    if (!l || !spec || grid < 1 || grid > 8192 || !isfinite(spec->extent) || !(spec->extent > 0) ||
        !isfinite(spec->margin) || spec->margin < 0)
        return -1.0;
    const double L = spec->extent, cs = L / grid, m = spec->margin;
    unsigned char *mask = calloc((size_t)grid * (size_t)grid, 1);
    if (!mask)
        return -1.0;
    for (int e = 0; e < l->n_ell; e++) {
        const cu_layer_ellipsoid *el = &l->ell[e];
        double a = el->radii[0] - m, c = el->radii[2] - m;
        if (a <= 0 || c <= 0)
            continue;
        double cx = el->center[0], cz = el->center[2];
        long j0 = (long)ceil((cz - c + 0.5 * L) / cs - 0.5), j1 = (long)floor((cz + c + 0.5 * L) / cs - 0.5);
        for (long j = j0; j <= j1; j++) {
            double t = (-0.5 * L + (j + 0.5) * cs - cz) / c;
            if (t * t > 1.0)
                continue;
            double w = a * sqrt(1.0 - t * t);
            long i0 = (long)ceil((cx - w + 0.5 * L) / cs - 0.5), i1 = (long)floor((cx + w + 0.5 * L) / cs - 0.5);
            if (i1 - i0 + 1 >= grid) {
                i0 = 0;
                i1 = grid - 1;
            }
            unsigned char *row = mask + (size_t)(((j % grid) + grid) % grid) * (size_t)grid;
            for (long i = i0; i <= i1; i++)
                row[((i % grid) + grid) % grid] = 1;
        }
    }
    size_t n = 0;
    for (size_t i = 0; i < (size_t)grid * (size_t)grid; i++)
        n += mask[i];
    free(mask);
    return (double)n / ((double)grid * (double)grid);
}
