/* Least-squares fits of the slab C tables: Bouthors' eq. 3.32 per (group, thickness) and a log-separable alternative. */
#include "fitlib.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <gsl/gsl_blas.h>
#include <gsl/gsl_multifit_nlinear.h>
#include <gsl/gsl_vector.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif
#define DEG (M_PI / 180.0)

int cu_cells_read(const char *path, cu_cell **cells, int *n, char *msg, size_t msglen)
{
    FILE *fp = fopen(path, "r");
    if (!fp) { snprintf(msg, msglen, "cannot open table '%s'", path); return -1; }
    char line[1024];
    int cap = *n, lineno = 0;
    while (fgets(line, sizeof line, fp)) {
        lineno++;
        if (line[0] == '#' || line[0] == '\n') continue;
        cu_cell c;
        if (sscanf(line, "%d %lf %lf %lf %lf %lf %lf %lf", &c.group, &c.t, &c.d, &c.thv, &c.phv, &c.thl, &c.C, &c.Cse) != 8) {
            snprintf(msg, msglen, "%s:%d: malformed table row", path, lineno);
            fclose(fp); return -1;
        }
        if (*n >= cap) {
            cap = cap ? 2 * cap : 4096;
            cu_cell *p = realloc(*cells, sizeof(cu_cell) * cap);
            if (!p) { fclose(fp); snprintf(msg, msglen, "out of memory"); return -1; }
            *cells = p;
        }
        (*cells)[(*n)++] = c;
    }
    fclose(fp);
    return 0;
}

static int same(double a, double b) { return fabs(a - b) <= 1e-6 * (fabs(a) + fabs(b)) + 1e-9; }

static int find(const double *v, int n, double x)
{
    for (int i = 0; i < n; i++) if (same(v[i], x)) return i;
    return -1;
}

static int add_unique(double *v, int *n, double x)
{
    int i = find(v, *n, x);
    if (i >= 0) return 0;
    if (*n >= CU_FIT_MAXN) return -1;
    int k = (*n)++;
    while (k > 0 && v[k - 1] > x) { v[k] = v[k - 1]; k--; }
    v[k] = x;
    return 0;
}

static double cos_scat(double thv, double phv, double thl)
{
    /* s_L = (0, -cos thL, -sin thL), s_V = (sin thV sin phV, -cos thV, -sin thV cos phV) in Bouthors' frame */
    return cos(thl * DEG) * cos(thv * DEG) + sin(thl * DEG) * sin(thv * DEG) * cos(phv * DEG);
}

/* ---- parameter layout ----
 * Bouthors: [logP(13)] [logA1(nv)] [logA2(nl)] [B1(nv)] [B2(nl)] [logC(nv)] [logD(nv)]
 * LogSep:   [logP(13)] [H(nd*nv)] [K(nd*nl)]   log C = logP(Theta) + H(d,thV) + K(d,thL) (+ log cos thL) */
static int off_a1(const cu_fit *f) { (void)f; return CU_FIT_NTH; }
static int off_a2(const cu_fit *f) { return CU_FIT_NTH + f->nv; }
static int off_b1(const cu_fit *f) { return CU_FIT_NTH + f->nv + f->nl; }
static int off_b2(const cu_fit *f) { return CU_FIT_NTH + 2 * f->nv + f->nl; }
static int off_c(const cu_fit *f) { return CU_FIT_NTH + 2 * f->nv + 2 * f->nl; }
static int off_d(const cu_fit *f) { return CU_FIT_NTH + 3 * f->nv + 2 * f->nl; }
static int prow(const cu_fit *f) { return f->model == CU_MODEL_LOGSEP2 ? f->nd : 1; }
static int off_h(const cu_fit *f) { return CU_FIT_NTH * prow(f); }
static int off_k(const cu_fit *f) { return CU_FIT_NTH * prow(f) + f->nd * f->nv; }

static double theta_w(double cosT, int *i0)
{
    double T = acos(fmax(-1.0, fmin(1.0, cosT))) / DEG / 15.0;
    int i = (int)T;
    if (i >= CU_FIT_NTH - 1) i = CU_FIT_NTH - 2;
    *i0 = i;
    return T - i;
}

static double logp(const cu_fit *f, double cosT)
{
    int i;
    double w = theta_w(cosT, &i);
    return f->par[i] * (1 - w) + f->par[i + 1] * w;
}

static double interp_idx(const double *grid, int n, double x, int *i0)
{
    if (n == 1) { *i0 = 0; return 0; }
    int i = 0;
    while (i < n - 2 && x > grid[i + 1]) i++;
    *i0 = i;
    double w = (x - grid[i]) / (grid[i + 1] - grid[i]);
    return fmax(0.0, fmin(1.0, w));
}

double cu_fit_eval(const cu_fit *f, double d, double thv, double phv, double thl)
{
    int iv = find(f->thv, f->nv, thv), il = find(f->thl, f->nl, thl);
    if (iv < 0 || il < 0) return NAN;
    double mu = cos(thl * DEG), lp = logp(f, cos_scat(thv, phv, thl));
    const double *p = f->par;
    if (f->model == CU_MODEL_BOUTHORS) {
        double A = exp(lp + p[off_a1(f) + iv] + p[off_a2(f) + il]);
        double B = p[off_b1(f) + iv] - p[off_b2(f) + il];
        double Cs = exp(p[off_c(f) + iv]), D = exp(p[off_d(f) + iv]);
        double num = log(d + D), den = log(fmax(B + D, 1e-9));
        den = den * den;
        if (den < 1e-8) den = 1e-8;   /* eq. 3.32 is singular where B* + D* = 1 */
        return A * mu * num * num / den * exp(-(d - B) * (d - B) / (2 * Cs * Cs));
    }
    int i0;
    double w = interp_idx(f->d, f->nd, d, &i0);
    int i1 = f->nd > 1 ? i0 + 1 : 0;
    double h = (1 - w) * p[off_h(f) + i0 * f->nv + iv] + w * p[off_h(f) + i1 * f->nv + iv];
    double k = (1 - w) * p[off_k(f) + i0 * f->nl + il] + w * p[off_k(f) + i1 * f->nl + il];
    if (f->model == CU_MODEL_LOGSEP2) {
        int it;
        double wt = theta_w(cos_scat(thv, phv, thl), &it);
        const double *r0 = p + i0 * CU_FIT_NTH, *r1 = p + i1 * CU_FIT_NTH;
        lp = (1 - w) * ((1 - wt) * r0[it] + wt * r0[it + 1]) + w * ((1 - wt) * r1[it] + wt * r1[it + 1]);
    }
    return mu * exp(lp + h + k);
}

typedef struct {
    cu_fit *f;
    const cu_cell *c;
    int n;
    int *fix;         /* 1 = parameter held fixed */
    int *map;         /* free index -> full index */
    int *inv;         /* full index -> free index or -1 */
    double wfloor;    /* residual scale floor: 1 % of the slice maximum */
} ctx_t;

static void unpack(ctx_t *x, const gsl_vector *v)
{
    int k = 0;
    for (int i = 0; i < x->f->npar; i++) if (!x->fix[i]) x->f->par[i] = gsl_vector_get(v, k++);
}

/* residuals ~ relative error for significant cells, absolute (in units of 1 % of the max) for faint ones */
static int resid(const gsl_vector *v, void *data, gsl_vector *r)
{
    ctx_t *x = data;
    unpack(x, v);
    for (int i = 0; i < x->n; i++) {
        const cu_cell *c = &x->c[i];
        double m = cu_fit_eval(x->f, c->d, c->thv, c->phv, c->thl);
        double e = (m - c->C) / (fabs(c->C) + x->wfloor + 2 * c->Cse);
        gsl_vector_set(r, i, isfinite(e) ? e : 1e3);
    }
    return GSL_SUCCESS;
}

/* analytic Jacobian of the log-linear forms: dr/dp = M/s * d(log M)/dp, with d(log M)/dp the interpolation weights */
static int resid_df(const gsl_vector *v, void *data, gsl_matrix *J)
{
    ctx_t *x = data;
    cu_fit *f = x->f;
    unpack(x, v);
    gsl_matrix_set_zero(J);
    for (int i = 0; i < x->n; i++) {
        const cu_cell *c = &x->c[i];
        double m = cu_fit_eval(f, c->d, c->thv, c->phv, c->thl);
        double s = fabs(c->C) + x->wfloor + 2 * c->Cse, a = isfinite(m) ? m / s : 0;
        int iv = find(f->thv, f->nv, c->thv), il = find(f->thl, f->nl, c->thl), i0, it;
        double w = interp_idx(f->d, f->nd, c->d, &i0), wt = theta_w(cos_scat(c->thv, c->phv, c->thl), &it);
        int i1 = f->nd > 1 ? i0 + 1 : 0;
        int idx[16]; double cf[16]; int k = 0;
        if (f->model == CU_MODEL_BOUTHORS) {
            /* d log M / dp for eq. 3.32 with B = B1 - B2, C* = e^lc, D* = e^ld */
            const double *p = f->par;
            double B = p[off_b1(f) + iv] - p[off_b2(f) + il], Cs = exp(p[off_c(f) + iv]), D = exp(p[off_d(f) + iv]);
            double lbd = log(fmax(B + D, 1e-9)), lnum = log(c->d + D);
            int guard = lbd * lbd < 1e-8 || B + D <= 1e-9;
            double dden_dB = guard ? 0 : 2.0 / ((B + D) * lbd);          /* d log(den) / dB */
            double dlogM_dB = -dden_dB + (c->d - B) / (Cs * Cs);
            double dnum_dD = fabs(lnum) > 1e-12 ? 2.0 / ((c->d + D) * lnum) : 0;
            idx[k] = it; cf[k++] = 1 - wt;
            idx[k] = it + 1; cf[k++] = wt;
            idx[k] = off_a1(f) + iv; cf[k++] = 1;
            idx[k] = off_a2(f) + il; cf[k++] = 1;
            idx[k] = off_b1(f) + iv; cf[k++] = dlogM_dB;
            idx[k] = off_b2(f) + il; cf[k++] = -dlogM_dB;
            idx[k] = off_c(f) + iv; cf[k++] = (c->d - B) * (c->d - B) / (Cs * Cs);
            idx[k] = off_d(f) + iv; cf[k++] = D * (dnum_dD - dden_dB);
        } else if (f->model == CU_MODEL_LOGSEP2) {
            idx[k] = i0 * CU_FIT_NTH + it; cf[k++] = (1 - w) * (1 - wt);
            idx[k] = i0 * CU_FIT_NTH + it + 1; cf[k++] = (1 - w) * wt;
            idx[k] = i1 * CU_FIT_NTH + it; cf[k++] = w * (1 - wt);
            idx[k] = i1 * CU_FIT_NTH + it + 1; cf[k++] = w * wt;
        } else {
            idx[k] = it; cf[k++] = 1 - wt;
            idx[k] = it + 1; cf[k++] = wt;
        }
        if (f->model != CU_MODEL_BOUTHORS) {
            idx[k] = off_h(f) + i0 * f->nv + iv; cf[k++] = 1 - w;
            idx[k] = off_h(f) + i1 * f->nv + iv; cf[k++] = w;
            idx[k] = off_k(f) + i0 * f->nl + il; cf[k++] = 1 - w;
            idx[k] = off_k(f) + i1 * f->nl + il; cf[k++] = w;
        }
        for (int q = 0; q < k; q++) {
            int col = x->inv[idx[q]];
            if (col >= 0 && cf[q] != 0) gsl_matrix_set(J, i, col, gsl_matrix_get(J, i, col) + a * cf[q]);
        }
    }
    return GSL_SUCCESS;
}

/* cells that are zero by construction: no diffuse light goes down at the top or up at the bottom */
static int structural_zero(const cu_cell *c)
{
    return (c->d <= 1e-9 * c->t && c->thv < 90) || (c->d >= c->t * (1 - 1e-9) && c->thv > 90);
}

int cu_fit_slice(cu_fit *f, int model, int group, double t, const cu_cell *cells, int n, const int *use)
{
    memset(f, 0, sizeof *f);
    f->model = model; f->group = group; f->t = t;
    int m = 0;
    cu_cell *sel = malloc(sizeof(cu_cell) * (n > 0 ? n : 1));
    if (!sel) return -1;
    for (int i = 0; i < n; i++) {
        const cu_cell *c = &cells[i];
        if (c->group != group || !same(c->t, t)) continue;
        if (add_unique(f->thv, &f->nv, c->thv) || add_unique(f->thl, &f->nl, c->thl) || add_unique(f->d, &f->nd, c->d)) {
            free(sel); return -1;
        }
        if (use && !use[i]) continue;
        if (structural_zero(c)) continue;
        sel[m++] = *c;
        if (c->C > f->cmax) f->cmax = c->C;
    }
    if (m == 0 || f->cmax <= 0) { free(sel); f->status = -1; return -1; }
    f->npar = model == CU_MODEL_BOUTHORS ? CU_FIT_NTH + 4 * f->nv + 2 * f->nl : off_k(f) + f->nd * f->nl;
    if (f->npar > (int)(sizeof f->par / sizeof f->par[0])) { free(sel); return -1; }
    int *fix = calloc(f->npar, sizeof(int)), *map = calloc(f->npar, sizeof(int));
    /* degeneracies removed by fixing: P*(90 deg) = 1 (P* against A), A2*(thL_0) = 1 and B2*(thL_0) = 0 (A1/A2 and
     * B1/B2 offsets); in the log-separable form K(d, thL_0) = 0. For n = 16+ P* = 1 (isotropic, as in Bouthors). */
    for (int r = 0; r < (model == CU_MODEL_BOUTHORS ? 1 : prow(f)); r++)
        for (int k = 0; k < CU_FIT_NTH; k++) if (k == 6 || group == 8) fix[r * CU_FIT_NTH + k] = 1;
    /* starting values */
    double sumlog = 0;
    int nlog = 0;
    for (int i = 0; i < m; i++) if (sel[i].C > 0) { sumlog += log(sel[i].C / cos(sel[i].thl * DEG)); nlog++; }
    double l0 = nlog ? sumlog / nlog : log(f->cmax);
    if (model == CU_MODEL_BOUTHORS) {
        fix[off_a2(f)] = 1; fix[off_b2(f)] = 1;
        for (int iv = 0; iv < f->nv; iv++) {
            /* peak depth and height of the (thV) profiles averaged over the other angles */
            double best = -1, bd = t / 2;
            for (int i = 0; i < m; i++)
                if (same(sel[i].thv, f->thv[iv]) && sel[i].C > best) { best = sel[i].C / cos(sel[i].thl * DEG); bd = sel[i].d; }
            f->par[off_a1(f) + iv] = best > 0 ? log(best) : l0;
            f->par[off_b1(f) + iv] = bd;
            f->par[off_c(f) + iv] = log(0.5 * t);
            f->par[off_d(f) + iv] = log(0.1 * t + 2.0);
        }
    } else {
        for (int il = 0; il < f->nl; il++) if (il == 0) for (int id = 0; id < f->nd; id++) fix[off_k(f) + id * f->nl] = 1;
        for (int id = 0; id < f->nd; id++)
            for (int iv = 0; iv < f->nv; iv++) {
                double s = 0; int k = 0;
                for (int i = 0; i < m; i++)
                    if (same(sel[i].thv, f->thv[iv]) && same(sel[i].d, f->d[id]) && sel[i].C > 0) { s += log(sel[i].C / cos(sel[i].thl * DEG)); k++; }
                f->par[off_h(f) + id * f->nv + iv] = k ? s / k : l0 - 5;
            }
    }
    int p = 0;
    int *inv = malloc(sizeof(int) * f->npar);
    for (int i = 0; i < f->npar; i++) { inv[i] = -1; if (!fix[i]) { inv[i] = p; map[p++] = i; } }
    ctx_t x = { f, sel, m, fix, map, inv, 0.01 * f->cmax };
    /* Eq. 3.32 has local minima (the log^2 ratio is singular where B* + D* = 1 and the Gaussian can switch off
     * cells), so it is started from several (C*, D*) guesses and the lowest cost wins; the log-linear forms are
     * convex up to the weights and need one start. */
    static const double cs0[] = { 0.5, 0.25, 1.0, 0.5 }, ds0[] = { 0.1, 0.5, 0.02, 2.0 };
    int nstart = model == CU_MODEL_BOUTHORS ? 4 : 1;
    double *init = malloc(sizeof(double) * f->npar), *best = malloc(sizeof(double) * f->npar);
    memcpy(init, f->par, sizeof(double) * f->npar);
    double best_cost = INFINITY;
    int best_iter = 0, best_status = -1;
    gsl_vector *v = gsl_vector_alloc(p);
    gsl_multifit_nlinear_parameters fp = gsl_multifit_nlinear_default_parameters();
    fp.trs = gsl_multifit_nlinear_trs_lm;   /* Levenberg-Marquardt */
    fp.scale = gsl_multifit_nlinear_scale_more;
    gsl_multifit_nlinear_workspace *w = gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &fp, m, p);
    gsl_multifit_nlinear_fdf fdf;
    memset(&fdf, 0, sizeof fdf);
    fdf.f = resid; fdf.df = resid_df; fdf.fvv = NULL; fdf.n = m; fdf.p = p; fdf.params = &x;
    for (int st = 0; st < nstart; st++) {
        memcpy(f->par, init, sizeof(double) * f->npar);
        if (model == CU_MODEL_BOUTHORS)
            for (int iv = 0; iv < f->nv; iv++) {
                f->par[off_c(f) + iv] = log(cs0[st] * t);
                f->par[off_d(f) + iv] = log(ds0[st] * t + 2.0);
            }
        for (int k = 0; k < p; k++) gsl_vector_set(v, k, f->par[map[k]]);
        int info = 0;
        gsl_multifit_nlinear_init(v, &fdf, w);
        int status = gsl_multifit_nlinear_driver(300, 1e-8, 1e-8, 1e-8, NULL, NULL, &info, w);
        double cost;
        gsl_blas_ddot(gsl_multifit_nlinear_residual(w), gsl_multifit_nlinear_residual(w), &cost);
        if (isfinite(cost) && cost < best_cost) {
            best_cost = cost; best_status = status; best_iter = (int)gsl_multifit_nlinear_niter(w);
            unpack(&x, gsl_multifit_nlinear_position(w));
            memcpy(best, f->par, sizeof(double) * f->npar);
        }
    }
    memcpy(f->par, best, sizeof(double) * f->npar);
    f->status = best_status; f->iter = best_iter;
    gsl_multifit_nlinear_free(w);
    gsl_vector_free(v);
    free(init); free(best);
    free(fix); free(map); free(inv); free(sel);
    return 0;
}

static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

double cu_quantile(const double *s, int n, double q)
{
    if (n <= 0) return NAN;
    double pos = q * (n - 1);
    int i = (int)pos;
    if (i >= n - 1) return s[n - 1];
    return s[i] + (s[i + 1] - s[i]) * (pos - i);
}

int cu_fit_errors(const cu_fit *f, const cu_cell *cells, int n, const int *use, int want, double frac, double *err,
                  int max, double *noise_med)
{
    int k = 0;
    double *noise = malloc(sizeof(double) * (max > 0 ? max : 1));
    for (int i = 0; i < n && k < max; i++) {
        const cu_cell *c = &cells[i];
        if (c->group != f->group || !same(c->t, f->t)) continue;
        if (use && (use[i] != 0) != (want != 0)) continue;
        if (!(c->C > frac * f->cmax)) continue;
        double m = cu_fit_eval(f, c->d, c->thv, c->phv, c->thl);
        err[k] = isfinite(m) ? fabs(m - c->C) / c->C : 1e3;
        noise[k] = c->Cse / c->C;
        k++;
    }
    qsort(err, k, sizeof(double), cmp_d);
    qsort(noise, k, sizeof(double), cmp_d);
    if (noise_med) *noise_med = cu_quantile(noise, k, 0.5);
    free(noise);
    return k;
}

void cu_fit_write(FILE *fp, const cu_fit *f)
{
    const double *p = f->par;
    const char *g[] = { "", "1", "2", "3", "4", "5-6", "7-9", "10-15", "16+" };
    const char *gn = f->group >= 1 && f->group <= 8 ? g[f->group] : "?";
    if (f->model == CU_MODEL_LOGSEP2) {
        for (int id = 0; id < f->nd; id++)
            for (int k = 0; k < CU_FIT_NTH; k++)
                fprintf(fp, "P %s %.6g d/t=%.4g Theta=%g %.6g\n", gn, f->t, f->d[id] / f->t, 15.0 * k, exp(p[id * CU_FIT_NTH + k]));
    } else
        for (int k = 0; k < CU_FIT_NTH; k++) fprintf(fp, "P %s %.6g Theta=%g %.6g\n", gn, f->t, 15.0 * k, exp(p[k]));
    if (f->model == CU_MODEL_BOUTHORS) {
        for (int i = 0; i < f->nv; i++)
            fprintf(fp, "A1 %s %.6g thetaV=%g %.6g\nB1 %s %.6g thetaV=%g %.6g\nC %s %.6g thetaV=%g %.6g\nD %s %.6g thetaV=%g %.6g\n",
                    gn, f->t, f->thv[i], exp(p[off_a1(f) + i]), gn, f->t, f->thv[i], p[off_b1(f) + i], gn, f->t, f->thv[i],
                    exp(p[off_c(f) + i]), gn, f->t, f->thv[i], exp(p[off_d(f) + i]));
        for (int l = 0; l < f->nl; l++)
            fprintf(fp, "A2 %s %.6g thetaL=%g %.6g\nB2 %s %.6g thetaL=%g %.6g\n", gn, f->t, f->thl[l], exp(p[off_a2(f) + l]),
                    gn, f->t, f->thl[l], p[off_b2(f) + l]);
    } else {
        for (int id = 0; id < f->nd; id++) {
            for (int i = 0; i < f->nv; i++)
                fprintf(fp, "H %s %.6g d/t=%.4g thetaV=%g %.6g\n", gn, f->t, f->d[id] / f->t, f->thv[i], exp(p[off_h(f) + id * f->nv + i]));
            for (int l = 0; l < f->nl; l++)
                fprintf(fp, "K %s %.6g d/t=%.4g thetaL=%g %.6g\n", gn, f->t, f->d[id] / f->t, f->thl[l], exp(p[off_k(f) + id * f->nl + l]));
        }
    }
}
