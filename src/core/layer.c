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
        *x = -0.5 * p->L + cu_layer_rng_unit(&p->rng) * p->L;
        *z = -0.5 * p->L + cu_layer_rng_unit(&p->rng) * p->L;
        if (is_free(p, *x, *z, r))
            return 1;
    }
    for (int k = 0; k < POCKETS && p->out->n_clouds > 0; k++) {
        const cu_layer_cloud *a = &p->out->clouds[cu_layer_rng_next(&p->rng) % (uint64_t)p->out->n_clouds];
        double ra = a->radius + r + 2.0 * GAP, ux, uz;
        /* A alone first: a spot touching it in a random direction. */
        cu_layer_rng_dir(&p->rng, &ux, &uz);
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

static int add_cloud(placer *p, const cu_layer_shape *sh, uint64_t seed, double x, double z)
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
    cu_layer_shape sh;
    double x, z;
    cu_layer_build_shape(p->type, d, p->thickness, seed, &sh);
    if (!find_spot(p, sh.radius, &x, &z)) {
        *shrunk = 1;
        double best = -1, bx = 0, bz = 0;
        for (int k = 0; k < PROBES; k++) {
            double px = -0.5 * p->L + cu_layer_rng_unit(&p->rng) * p->L, pz = -0.5 * p->L + cu_layer_rng_unit(&p->rng) * p->L;
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
        cu_layer_build_shape(p->type, d, p->thickness, seed, &sh);
        x = bx;
        z = bz;
        if (!is_free(p, x, z, sh.radius))
            return 0;
    }
    if (add_cloud(p, &sh, seed, x, z))
        return -1;
    *area = cu_layer_shape_area(&sh, p->margin);
    *d_out = d;
    return 1;
}

/* Resizes the cloud (d, seed) so its visible area is about `want` (<= its area a at d): area goes nearly as D^2,
 * the margin and the minimum radii bend that, so a few secant steps. Never below d_min. */
static double fit_size(const placer *p, double d, uint64_t seed, double a, double want, double d_min, double *a_out)
{
    for (int it = 0; it < 4 && a > 0 && want > 0; it++) {
        double nd = fmax(cu_layer_quantize(d * sqrt(want / a)), d_min);
        if (nd == d)
            break;
        cu_layer_shape sh;
        cu_layer_build_shape(p->type, nd, p->thickness, seed, &sh);
        d = nd;
        a = cu_layer_shape_area(&sh, p->margin);
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
        double d = cu_layer_draw_size(&size_rng, d_min, d_max);
        uint64_t seed = cu_layer_rng_next(&size_rng);
        cu_layer_shape sh;
        cu_layer_build_shape(spec->type, d, spec->thickness, seed, &sh);
        double a = cu_layer_shape_area(&sh, spec->margin);
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
        double d = cu_layer_draw_size(&size_rng, d_min, cap_d), a, dp;
        uint64_t seed = cu_layer_rng_next(&size_rng);
        cu_layer_shape sh;
        cu_layer_build_shape(spec->type, d, spec->thickness, seed, &sh);
        a = cu_layer_shape_area(&sh, spec->margin);
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
