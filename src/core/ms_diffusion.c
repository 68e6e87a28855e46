/* src/core/ms_diffusion.c: flux-limited diffusion of the sunlight a cloud scatters (see ms_diffusion.h).
 *
 * The diffuse radiance in P1 form, L(w) = (phi + 3 F.w) / 4pi, in the delta-M medium (extinction (1 - f) k_e, all
 * of it scattering, asymmetry g of the chopped phase function), with the sunbeam's first scattering as the source
 * Q = (1 - f) k_e T' (T' its delta-M transmittance to the point, per unit irradiance). The moments give
 *     div F = Q,   F = -D grad phi + G,   G = 3 D g Q w_s,   D = 1 / (3 s_tr),   s_tr = (1 - f)(1 - g) k_e,
 * where w_s is the beam's direction: G carries the forward push of the first scattering. Plain diffusion spreads
 * light through thin cloud and empty space infinitely fast; Wilson's sum limiter D = 1 / (3 s_tr + |grad phi| /
 * phi) caps the flux at c phi, and the push is capped at phi the same way (|F| <= phi: unlimited, it drains the far
 * side of a cloud below zero). Finite volumes on the grid's cells, the coefficient at a face the harmonic mean of its
 * cells', Marshak's condition where the cloud meets empty space. Both caps depend on the fluence they shape, so the
 * solve is a Picard iteration: the coefficients are taken from the fluence so far (damped), then the linear problem
 * they make is relaxed (over-relaxed Gauss-Seidel) until it settles, and again, until new coefficients change
 * nothing. Whatever the coefficients do, the last relaxation is of a fixed linear problem, so the answer is settled
 * (a few cells at the edge of a wispy cloud can make the coefficients swing; the number of rounds is bounded). The
 * source Q is ms_diffusion_beam.c's. A renderer can run the sweeps a few at a time (cu_msd_solve_continue). */
#include "ms_diffusion.h"
#include <stdlib.h>
#include <string.h>

#define SOR 1.6
#define ROUNDS 12       /* Picard rounds at most (the coefficients from the fluence, then the linear problem) */
#define ROUND_SWEEPS 40 /* sweeps of the linear problem in a round before the coefficients are taken again */
#define SETTLED 10      /* a round that settles within this many sweeps ends the solve */

/* The cells' arrays, zeroed, for the sizes g->n and g->h already set; 1 (and nothing held) when out of memory. */
static int grid_alloc(cu_msd *g)
{
    g->side = cbrt(g->h[0] * g->h[1] * g->h[2]);
    size_t count = (size_t)g->n[0] * g->n[1] * g->n[2];
    g->ke = calloc(count, sizeof *g->ke);
    g->q = calloc(count, sizeof *g->q);
    g->push = calloc(count, sizeof *g->push);
    g->phi = calloc(count, sizeof *g->phi);
    g->d = calloc(count, sizeof *g->d);
    g->leak = calloc(count, sizeof *g->leak);
    g->out = calloc(4 * count, sizeof *g->out);
    if (!g->ke || !g->q || !g->push || !g->phi || !g->d || !g->leak || !g->out) {
        cu_msd_free(g);
        return 1;
    }
    return 0;
}

int cu_msd_init(cu_msd *g, const cu_cloud *cl, int cells, cu_error *err)
{
    memset(g, 0, sizeof *g);
    if (cells < CU_MSD_MIN_CELLS || cells > CU_MSD_MAX_CELLS)
        return cu_fail(err, "ms.grid: %d cells; between %d and %d", cells, CU_MSD_MIN_CELLS, CU_MSD_MAX_CELLS);
    double lo[3] = {cl->bounds_min.x, cl->bounds_min.y, cl->bounds_min.z};
    double hi[3] = {cl->bounds_max.x, cl->bounds_max.y, cl->bounds_max.z};
    double longest = 0.0, inner = cells - 2 * CU_MSD_MARGIN;
    for (int a = 0; a < 3; a++)
        longest = fmax(longest, hi[a] - lo[a]);
    if (!(longest > 0.0) || !isfinite(longest))
        longest = 1.0; /* an empty cloud: a grid of nothing, solved to zero */
    for (int a = 0; a < 3; a++) {
        /* cubic cells where the cloud is round; a flat one keeps a quarter of the cells across its thickness, so its
         * light can fall off from top to base (one cell across a layer would hold one fluence) */
        double e = fmax(hi[a] - lo[a], 1e-3 * longest);
        int n = (int)ceil(e / (longest / inner) - 1e-9);
        if (n < (int)inner / 4)
            n = (int)inner / 4;
        g->h[a] = e / n;
        g->n[a] = n + 2 * CU_MSD_MARGIN;
        lo[a] = 0.5 * (lo[a] + hi[a]) - 0.5 * g->n[a] * g->h[a];
    }
    g->lo = v3(lo[0], lo[1], lo[2]);
    if (grid_alloc(g))
        return cu_fail(err, "ms.grid: out of memory for %dx%dx%d cells", g->n[0], g->n[1], g->n[2]);
    return 0;
}

void cu_msd_free(cu_msd *g)
{
    free(g->ke);
    free(g->q);
    free(g->push);
    free(g->phi);
    free(g->d);
    free(g->leak);
    free(g->out);
    memset(g, 0, sizeof *g);
}

void cu_msd_sample(cu_msd *g, const cu_cloud *cl)
{
    cu_msd_sample_slices(g, cl, 0, g->n[2]);
}

void cu_msd_sample_slices(cu_msd *g, const cu_cloud *cl, int k0, int k1)
{
    for (int k = k0 < 0 ? 0 : k0; k < k1 && k < g->n[2]; k++)
        for (int j = 0; j < g->n[1]; j++)
            for (int i = 0; i < g->n[0]; i++) {
                vec3 c = cu_msd_centre(g, i, j, k);
                double sum = 0.0;
                for (int s = 0; s < 8; s++) /* the mean of 8 samples at the cell's quarter points */
                    sum += cu_cloud_extinction(cl, v3(c.x + ((s & 1) - 0.5) * 0.5 * g->h[0],
                                                      c.y + ((s >> 1 & 1) - 0.5) * 0.5 * g->h[1],
                                                      c.z + ((s >> 2) - 0.5) * 0.5 * g->h[2]));
                g->ke[cu_msd_at(g, i, j, k)] = (float)(sum / 8.0);
            }
}

/* Whether cell c holds cloud: an optical depth across it (its mean side) of at least CU_MSD_THIN. A wisp of less
 * scatters under a tenth of the light through it, most of which leaves at once; solved, its fluence hangs on a tiny
 * source and a huge coefficient, and the limiter's feedback makes it swing from sweep to sweep (at 0.01 the solve
 * never settles). */
static int holds(const cu_msd *g, int c)
{
    return g->ke[c] * g->side >= CU_MSD_THIN;
}

/* Whether cell (i, j, k) holds cloud (cells of empty space, and beyond the grid, do not: the cloud's surface). */
static int inside(const cu_msd *g, int i, int j, int k)
{
    return i >= 0 && j >= 0 && k >= 0 && i < g->n[0] && j < g->n[1] && k < g->n[2] && holds(g, cu_msd_at(g, i, j, k));
}

static const int OFF[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};

/* Marshak's condition at a face to empty space: no diffuse light comes in, so the flux out is phi_s / 2 with phi_s
 * the fluence at the face, which the half-cell gradient ties to the cell's: with a = 2 D / h (h the side across the
 * face), phi_s = (a phi + G.n) / (a + 1/2) and the flux out (a phi + G.n) / (2a + 1) (sweep). The diffusive part
 * alone, a phi / (a + 1/2), is the surface value the gradient and the empty cells take. */
static double surface_phi(double d, double h, double phi)
{
    double a = 2.0 * d / h;
    return a * phi / (a + 0.5);
}

static vec3 gradient(const cu_msd *g, int i, int j, int k)
{
    int c = cu_msd_at(g, i, j, k);
    double v[3];
    for (int a = 0; a < 3; a++) {
        double side[2];
        for (int e = 0; e < 2; e++) {
            const int *o = OFF[2 * a + e];
            side[e] = inside(g, i + o[0], j + o[1], k + o[2]) ? g->phi[cu_msd_at(g, i + o[0], j + o[1], k + o[2])]
                                                              : surface_phi(g->d[c], g->h[a], g->phi[c]);
        }
        v[a] = (side[0] - side[1]) / (2.0 * g->h[a]);
    }
    return v3(v[0], v[1], v[2]);
}

/* The cloud's surface as the cells see it is a staircase: a face of it slanted to the grid's axes, normal n, is
 * covered by cell faces of |n_x| + |n_y| + |n_z| times its area (1.5 times over a sphere, more over a noisy cloud),
 * and Marshak's condition at every one of them lets the light out through that much surface. The solve still sends
 * out what came in, but from a fluence too low by about that factor near the surface, where the light the eye sees
 * comes from. So each cloud cell's faces to empty space leak in proportion to the true surface: weighted by
 * |n| / (|n_x| + |n_y| + |n_z|), n the gradient of the cells' occupancy by the 3x3x3 Sobel operator (the surface's
 * slant over the neighbouring cells; a cell's own faces say only which way it steps), taken per metre: a flat
 * layer's cells are wider than tall, and a step of one cell up over one across is a gentle slope there, not 45 degrees.
 * 1 where n is zero. */
static void leak_weights(cu_msd *g)
{
    static const double W[3] = {1.0, 2.0, 1.0}; /* the smoothing across the derivative's axis, offsets -1, 0, 1 */
    for (int k = 0; k < g->n[2]; k++)
        for (int j = 0; j < g->n[1]; j++)
            for (int i = 0; i < g->n[0]; i++) {
                int c = cu_msd_at(g, i, j, k);
                g->leak[c] = 1.0f;
                if (!holds(g, c))
                    continue; /* read only at cloud cells' faces */
                double n[3] = {0.0, 0.0, 0.0};
                for (int dz = -1; dz <= 1; dz++)
                    for (int dy = -1; dy <= 1; dy++)
                        for (int dx = -1; dx <= 1; dx++) {
                            if (!inside(g, i + dx, j + dy, k + dz))
                                continue;
                            n[0] += dx * W[dy + 1] * W[dz + 1];
                            n[1] += dy * W[dx + 1] * W[dz + 1];
                            n[2] += dz * W[dx + 1] * W[dy + 1];
                        }
                for (int a = 0; a < 3; a++)
                    n[a] /= g->h[a]; /* in metres: a flat layer's cells are wider than tall */
                double l1 = fabs(n[0]) + fabs(n[1]) + fabs(n[2]);
                if (l1 > 0.0)
                    g->leak[c] = (float)(sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) / l1);
            }
}

/* The coefficients from the fluence so far, half way from the last ones (damped: they feed back on the fluence they
 * shape): Wilson's limited D, at most two cells (no light yet: the first round), and the push 3 |g| D Q capped at
 * phi. */
static void coefficients(cu_msd *g, double s_tr_per_ke, double g3)
{
    double most = 2.0 * fmax(g->h[0], fmax(g->h[1], g->h[2]));
    for (int k = 0; k < g->n[2]; k++)
        for (int j = 0; j < g->n[1]; j++)
            for (int i = 0; i < g->n[0]; i++) {
                int c = cu_msd_at(g, i, j, k);
                if (!holds(g, c)) {
                    g->d[c] = g->push[c] = 0.0f;
                    continue;
                }
                double inv = 3.0 * s_tr_per_ke * g->ke[c];
                if (g->phi[c] > 0.0f)
                    inv += v3_len(gradient(g, i, j, k)) / g->phi[c];
                double d = inv > 1.0 / most ? 1.0 / inv : most;
                int first = !(g->d[c] > 0.0f);
                g->d[c] = (float)(first ? d : 0.5 * (g->d[c] + d));
                double p = fmin(g3 * g->d[c] * g->q[c], g->phi[c]);
                g->push[c] = (float)(first ? p : 0.5 * (g->push[c] + p));
            }
}

/* One over-relaxed Gauss-Seidel sweep over the cloud's cells; returns the sum of the changes. u is the direction the
 * push goes (the beam's, or against it for g < 0): G = u push at a cell. Per unit volume, a face across side h
 * carries -D_f (phi_j - phi_i) / h^2 + G_f.n / h between two cloud cells (D_f the harmonic mean, G_f the mean), and
 * (a phi + G.n) / ((2a + 1) h) out of the cloud (Marshak, surface_phi), weighted by the cell's leak (leak_weights). */
static double sweep(cu_msd *g, vec3 u)
{
    double sum = 0.0, uv[3] = {u.x, u.y, u.z};
    for (int k = 0; k < g->n[2]; k++)
        for (int j = 0; j < g->n[1]; j++)
            for (int i = 0; i < g->n[0]; i++) {
                int c = cu_msd_at(g, i, j, k);
                if (!holds(g, c))
                    continue;
                double di = g->d[c], diag = 0.0, rhs = g->q[c];
                for (int f = 0; f < 6; f++) {
                    int ax = f >> 1, sgn = OFF[f][ax], ii = i + OFF[f][0], jj = j + OFF[f][1], kk = k + OFF[f][2];
                    double h = g->h[ax], gi = uv[ax] * g->push[c] * sgn;
                    if (inside(g, ii, jj, kk)) {
                        int cj = cu_msd_at(g, ii, jj, kk);
                        double dj = g->d[cj], df = 2.0 * di * dj / (di + dj);
                        diag += df / (h * h);
                        rhs += df * g->phi[cj] / (h * h) - 0.5 * (gi + uv[ax] * g->push[cj] * sgn) / h;
                    } else {
                        double a2 = 2.0 * di / h, w = g->leak[c] / ((2.0 * a2 + 1.0) * h);
                        diag += w * a2;
                        rhs -= w * gi;
                    }
                }
                double now = g->phi[c] + SOR * (rhs / diag - g->phi[c]);
                if (!(now > 0.0))
                    now = 0.0;
                sum += fabs(now - g->phi[c]);
                g->phi[c] = (float)now;
            }
    return sum;
}

/* Cells of empty space next to the cloud take the mean of their cloud neighbours' fluence and flux at the shared
 * faces, so the shader's trilinear reads near the surface blend toward the surface's light, not toward zero. */
static void surface_values(cu_msd *g)
{
    for (int k = 0; k < g->n[2]; k++)
        for (int j = 0; j < g->n[1]; j++)
            for (int i = 0; i < g->n[0]; i++) {
                int c = cu_msd_at(g, i, j, k);
                if (holds(g, c))
                    continue;
                double sum[4] = {0, 0, 0, 0};
                int m = 0;
                for (int f = 0; f < 6; f++) {
                    int ii = i + OFF[f][0], jj = j + OFF[f][1], kk = k + OFF[f][2];
                    if (!inside(g, ii, jj, kk))
                        continue;
                    int cj = cu_msd_at(g, ii, jj, kk);
                    sum[0] += surface_phi(g->d[cj], g->h[f >> 1], g->phi[cj]);
                    for (int e = 1; e < 4; e++)
                        sum[e] += g->out[4 * cj + e];
                    m++;
                }
                for (int e = 0; e < 4 && m > 0; e++)
                    g->out[4 * c + e] = (float)(sum[e] / m);
            }
}

/* One sweep of the linear problem of the present coefficients; g->change becomes its summed change relative to the
 * summed fluence. */
static void relax_once(cu_msd *g)
{
    size_t count = (size_t)g->n[0] * g->n[1] * g->n[2];
    double change = sweep(g, g->u), total = 0.0;
    for (size_t c = 0; c < count; c++)
        total += g->phi[c];
    g->change = total > 0.0 ? change / total : 0.0;
}

/* A fine grid's first solve starts from a coarse one's answer (nested iteration). Gauss-Seidel smooths a cell's
 * error with its neighbours' and carries it across the grid a cell a sweep, so the sweeps a solve from nothing needs
 * grow with the cells across: 64 cells took 657 sweeps and 3.2 s on a sphere, 96 stopped at the budget of 1000 (21 s)
 * short of the tolerance, its far side still dark. A grid of half the cells a side (each the mean of 8) is solved
 * first, itself from a coarser one past NEST_CELLS, and its fluence, read trilinearly at the fine cells' centres
 * (with the surface values its empty cells hold), is where the fine solve starts: the fine sweeps then only mend
 * what the coarse cells could not hold. Out of memory, the solve starts from nothing as before. */
#define NEST_CELLS 40

int cu_msd_coarsen(const cu_msd *g, cu_msd *c)
{
    memset(c, 0, sizeof *c);
    for (int a = 0; a < 3; a++) {
        c->n[a] = (g->n[a] + 1) / 2;
        c->h[a] = 2.0 * g->h[a];
    }
    c->lo = g->lo;
    if (grid_alloc(c))
        return 1;
    for (int k = 0; k < c->n[2]; k++)
        for (int j = 0; j < c->n[1]; j++)
            for (int i = 0; i < c->n[0]; i++) {
                double sum = 0.0; /* fine cells past an odd grid's end count as empty space */
                for (int e = 0; e < 8; e++) {
                    int fi = 2 * i + (e & 1), fj = 2 * j + (e >> 1 & 1), fk = 2 * k + (e >> 2);
                    if (fi < g->n[0] && fj < g->n[1] && fk < g->n[2])
                        sum += g->ke[cu_msd_at(g, fi, fj, fk)];
                }
                c->ke[cu_msd_at(c, i, j, k)] = (float)(sum / 8.0);
            }
    return 0;
}

void cu_msd_start_from(cu_msd *g, const cu_msd *c)
{
    for (int k = 0; k < g->n[2]; k++)
        for (int j = 0; j < g->n[1]; j++)
            for (int i = 0; i < g->n[0]; i++) {
                int cell = cu_msd_at(g, i, j, k), idx[3] = {i, j, k}, lo[3], hi[3];
                if (!holds(g, cell))
                    continue;
                double t[3];
                for (int a = 0; a < 3; a++) {
                    double x = 0.5 * idx[a] - 0.25; /* the fine centre in the coarse cells' centres' index */
                    lo[a] = (int)floor(x);
                    t[a] = x - lo[a];
                    hi[a] = lo[a] + 1 < c->n[a] ? lo[a] + 1 : c->n[a] - 1;
                    if (lo[a] < 0)
                        lo[a] = 0;
                }
                double phi = 0.0;
                for (int e = 0; e < 8; e++) {
                    int ci = e & 1 ? hi[0] : lo[0], cj = e >> 1 & 1 ? hi[1] : lo[1], ck = e >> 2 ? hi[2] : lo[2];
                    double w = (e & 1 ? t[0] : 1.0 - t[0]) * (e >> 1 & 1 ? t[1] : 1.0 - t[1]) *
                               (e >> 2 ? t[2] : 1.0 - t[2]);
                    phi += w * c->out[4 * cu_msd_at(c, ci, cj, ck)];
                }
                g->phi[cell] = (float)phi;
            }
}

static void start_from_coarse(cu_msd *g, vec3 sun_dir, double f, double asym, int max_sweeps, double tol)
{
    cu_msd c;
    if (cu_msd_coarsen(g, &c))
        return;
    cu_msd_solve(&c, sun_dir, f, asym, max_sweeps, tol);
    cu_msd_start_from(g, &c);
    cu_msd_free(&c);
}

/* Whether no cell holds any fluence yet: a solve from nothing. */
static int unlit(const cu_msd *g)
{
    size_t count = (size_t)g->n[0] * g->n[1] * g->n[2];
    for (size_t c = 0; c < count; c++)
        if (g->phi[c] != 0.0f)
            return 0;
    return 1;
}

/* The fluence and flux into out, the texture's four channels. */
static void finish(cu_msd *g)
{
    for (int k = 0; k < g->n[2]; k++)
        for (int j = 0; j < g->n[1]; j++)
            for (int i = 0; i < g->n[0]; i++) {
                int c = cu_msd_at(g, i, j, k);
                float *o = &g->out[4 * c];
                o[0] = o[1] = o[2] = o[3] = 0.0f;
                if (!holds(g, c))
                    continue;
                vec3 F = v3_add(v3_scale(gradient(g, i, j, k), -g->d[c]), v3_scale(g->u, g->push[c]));
                o[0] = g->phi[c];
                o[1] = (float)F.x;
                o[2] = (float)F.y;
                o[3] = (float)F.z;
            }
    surface_values(g);
    g->solving = 0;
}

void cu_msd_solve_begin(cu_msd *g, vec3 sun_dir, double f, double asym, int max_sweeps, double tol)
{
    if (!(f >= 0.0 && f < 1.0))
        f = 0.0;
    if (!(asym > -1.0 && asym < 1.0))
        asym = 0.0;
    if ((g->n[0] > NEST_CELLS || g->n[1] > NEST_CELLS || g->n[2] > NEST_CELLS) && unlit(g))
        start_from_coarse(g, sun_dir, f, asym, max_sweeps, tol);
    cu_msd_first_scattering(g, sun_dir, f);
    leak_weights(g);
    g->s_tr_per_ke = (1.0 - f) * (1.0 - asym);
    g->g3 = 3.0 * fabs(asym);
    g->u = v3_scale(sun_dir, asym < 0.0 ? 1.0 : -1.0); /* the beam travels away from the sun */
    g->max_sweeps = max_sweeps;
    g->tol = tol;
    g->sweeps = g->round = g->in_round = g->round_most = 0;
    g->change = 0.0;
    g->solving = 1;
    if (max_sweeps <= 0)
        finish(g);
}

/* Picard rounds: new coefficients, then relax until a sweep changes at most tol of the fluence or the round's
 * sweeps are spent; done when a round's relaxation settles within SETTLED sweeps (the new coefficients hardly moved
 * the fluence), or after the last round, whose relaxation runs to the end of the budget. */
int cu_msd_solve_continue(cu_msd *g, int sweeps)
{
    int ran = 0;
    while (g->solving && ran < sweeps) {
        if (g->round_most == 0) {
            coefficients(g, g->s_tr_per_ke, g->g3);
            int last = g->round == ROUNDS - 1, left = g->max_sweeps - g->sweeps;
            g->round_most = last || left < ROUND_SWEEPS ? left : ROUND_SWEEPS;
        }
        relax_once(g);
        ran++;
        g->sweeps++;
        g->in_round++;
        if (g->change > g->tol && g->in_round < g->round_most)
            continue;
        int settled = g->in_round <= SETTLED && g->change <= g->tol;
        g->round++;
        g->in_round = g->round_most = 0;
        if (settled || g->round >= ROUNDS || g->sweeps >= g->max_sweeps)
            finish(g);
    }
    return ran;
}

void cu_msd_solve(cu_msd *g, vec3 sun_dir, double f, double asym, int max_sweeps, double tol)
{
    cu_msd_solve_begin(g, sun_dir, f, asym, max_sweeps, tol);
    while (g->solving)
        cu_msd_solve_continue(g, max_sweeps);
}
