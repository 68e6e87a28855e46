/* tools/slab/slab_phase.c: the slab Monte Carlo's phase functions: HG, isotropic and a tabulated Mie function with
 * its forward peak chopped (evaluation, sampling by the inverse CDF, reading data/mie_cloud.tbl). */
#include "slab.h"
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif


double cu_phase_eval(const cu_phase *ph, double c)
{
    if (ph->kind == CU_PH_ISO) return 0.25 / M_PI;
    if (ph->kind == CU_PH_HG) {
        double g = ph->g, q = 1.0 + g * g - 2.0 * g * c;
        return (1.0 - g * g) / (4.0 * M_PI * q * sqrt(q));
    }
    if (c > 1.0) c = 1.0;
    if (c < -1.0) c = -1.0;
    double th = acos(c);
    int i = (int)(th / ph->dth);
    if (i >= ph->n - 1) i = ph->n - 2;
    /* the density is linear in mu between nodes: the same function the sampler inverts exactly */
    double h = ph->mu[i] - ph->mu[i + 1];
    double x = h > 0 ? (ph->mu[i] - c) / h : 0.0;
    return ph->p[i] + (ph->p[i + 1] - ph->p[i]) * x;
}

double cu_phase_sample(const cu_phase *ph, double u)
{
    if (ph->kind == CU_PH_ISO || (ph->kind == CU_PH_HG && fabs(ph->g) < 1e-6)) return 2.0 * u - 1.0;
    if (ph->kind == CU_PH_HG) {
        /* inverse CDF of HG (VALIDATION.md closed form) */
        double g = ph->g, s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
        double c = (1.0 + g * g - s * s) / (2.0 * g);
        return c < -1.0 ? -1.0 : (c > 1.0 ? 1.0 : c);
    }
    /* binary search on the node CDF, then solve the quadratic CDF of the linear-in-mu piece exactly */
    int lo = 0, hi = ph->n - 1;
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (ph->cdf[mid] <= u) lo = mid; else hi = mid;
    }
    double h = ph->mu[lo] - ph->mu[lo + 1];
    double r = u - ph->cdf[lo];
    double a = M_PI * (ph->p[lo + 1] - ph->p[lo]) / h, b = 2.0 * M_PI * ph->p[lo];
    double disc = b * b + 4.0 * a * r;
    if (disc < 0) disc = 0;
    double den = b + sqrt(disc);
    double x = den > 0 ? 2.0 * r / den : h;
    if (x > h) x = h;
    if (x < 0) x = 0;
    return ph->mu[lo] - x;
}

void cu_phase_free(cu_phase *ph)
{
    free(ph->mu); free(ph->p); free(ph->cdf);
    ph->mu = ph->p = ph->cdf = NULL;
}

/* linear interpolation of the input table in theta (degrees) */
static double interp_deg(int n, const double *th, const double *P, double t)
{
    if (t <= th[0]) return P[0];
    if (t >= th[n - 1]) return P[n - 1];
    int lo = 0, hi = n - 1;
    while (hi - lo > 1) { int m = (lo + hi) / 2; if (th[m] <= t) lo = m; else hi = m; }
    double w = (t - th[lo]) / (th[hi] - th[lo]);
    return P[lo] + (P[hi] - P[lo]) * w;
}

/* integral of the piecewise-linear-in-mu density over the sphere, node by node (cumulative) */
static double cum_integral(int n, const double *mu, const double *p, double *cdf)
{
    double acc = 0;
    if (cdf) cdf[0] = 0;
    for (int i = 0; i + 1 < n; i++) {
        acc += 2.0 * M_PI * 0.5 * (p[i] + p[i + 1]) * (mu[i] - mu[i + 1]);
        if (cdf) cdf[i + 1] = acc;
    }
    return acc;
}

int cu_phase_from_table(cu_phase *ph, int n, const double *th, const double *P, double chop_deg, double f_hint,
                        char *msg, size_t msglen)
{
    memset(ph, 0, sizeof *ph);
    if (n < 2 || th[0] != 0.0 || th[n - 1] != 180.0) {
        snprintf(msg, msglen, "phase table must span 0..180 degrees with >= 2 angles");
        return -1;
    }
    for (int i = 0; i + 1 < n; i++)
        if (!(th[i + 1] > th[i])) { snprintf(msg, msglen, "phase table angles not ascending at line %d", i + 2); return -1; }
    for (int i = 0; i < n; i++)
        if (!(P[i] >= 0) || !isfinite(P[i])) { snprintf(msg, msglen, "phase table value %d is negative or not finite", i + 1); return -1; }
    /* Resample on 0.05-degree nodes (uniform in theta so that the glory and the chopped edge stay resolved), density
     * linear in mu between nodes. 3601 nodes keep the resampling error of smooth Mie tables far below MC noise. */
    int m = 3601;
    ph->kind = CU_PH_TAB; ph->n = m; ph->dth = M_PI / (m - 1);
    ph->mu = malloc(sizeof(double) * m); ph->p = malloc(sizeof(double) * m); ph->cdf = malloc(sizeof(double) * m);
    if (!ph->mu || !ph->p || !ph->cdf) { cu_phase_free(ph); snprintf(msg, msglen, "out of memory"); return -1; }
    for (int i = 0; i < m; i++) {
        double tdeg = 180.0 * i / (m - 1);
        ph->mu[i] = cos(ph->dth * i);
        ph->p[i] = interp_deg(n, th, P, tdeg);
    }
    ph->mu[0] = 1.0; ph->mu[m - 1] = -1.0;
    double full = cum_integral(m, ph->mu, ph->p, NULL);
    int prechopped = 0;
    if (fabs(full - 1.0) > 0.02) {
        if (f_hint > 0 && fabs(full - (1.0 - f_hint)) < 0.02) prechopped = 1;
        else {
            snprintf(msg, msglen, "phase table integrates to %.4f over the sphere, expected 1 (or 1-f)", full);
            cu_phase_free(ph); return -1;
        }
    }
    if (chop_deg > 0) {  /* eq. 3.64: flat at P(chop) inside the peak */
        double pc = interp_deg(n, th, P, chop_deg);
        for (int i = 0; i < m; i++)
            if (180.0 * i / (m - 1) < chop_deg) ph->p[i] = pc;
    }
    double chopped = cum_integral(m, ph->mu, ph->p, ph->cdf);
    ph->f = prechopped ? f_hint : 1.0 - chopped / full;
    for (int i = 0; i < m; i++) { ph->p[i] /= chopped; ph->cdf[i] /= chopped; }
    ph->cdf[m - 1] = 1.0;
    /* mean cosine of the sampling density (exact for the linear-in-mu pieces) */
    double gsum = 0;
    for (int i = 0; i + 1 < m; i++) {
        double a = ph->mu[i + 1], b = ph->mu[i], pa = ph->p[i + 1], pb = ph->p[i], h = b - a;
        /* integral of mu*(pa + (pb-pa)(mu-a)/h) over [a,b] */
        gsum += 2.0 * M_PI * (pa * (b * b - a * a) / 2.0 + (pb - pa) / h * ((b * b * b - a * a * a) / 3.0 - a * (b * b - a * a) / 2.0));
    }
    ph->g = gsum;
    return 0;
}

int cu_phase_read_mie(cu_phase *ph, const char *path, int channel, char *msg, size_t msglen)
{
    FILE *fp = fopen(path, "r");
    if (!fp) { snprintf(msg, msglen, "cannot open Mie table '%s': %s", path, strerror(errno)); return -1; }
    char line[1024];
    int nch = 0, nang = -1, got = 0;
    double chop = 0, fv[3] = { 0, 0, 0 };
    double *th = NULL, *P = NULL;
    int rc = -1, lineno = 0;
    while (fgets(line, sizeof line, fp)) {
        lineno++;
        char *s = line;
        while (*s == ' ' || *s == '\t') s++;
        if (*s == '#' || *s == '\n' || *s == 0) continue;
        char key[64];
        if (nang >= 0 && got < nang) {
            double a, v[3];
            if (sscanf(s, "%lf %lf %lf %lf", &a, &v[0], &v[1], &v[2]) != 1 + nch || nch != 3) {
                snprintf(msg, msglen, "%s:%d: expected 'theta P_r P_g P_b'", path, lineno); goto done;
            }
            th[got] = a; P[got] = v[channel]; got++;
            continue;
        }
        if (sscanf(s, "%63s", key) != 1) continue;
        if (!strcmp(key, "channels")) {
            if (sscanf(s, "%*s %d", &nch) != 1 || nch != 3) { snprintf(msg, msglen, "%s:%d: only 'channels 3' is supported", path, lineno); goto done; }
        } else if (!strcmp(key, "chop_deg")) {
            if (sscanf(s, "%*s %lf", &chop) != 1 || chop < 0 || chop >= 90) { snprintf(msg, msglen, "%s:%d: bad chop_deg", path, lineno); goto done; }
        } else if (!strcmp(key, "f")) {
            if (sscanf(s, "%*s %lf %lf %lf", &fv[0], &fv[1], &fv[2]) != 3) { snprintf(msg, msglen, "%s:%d: bad f line", path, lineno); goto done; }
        } else if (!strcmp(key, "angles")) {
            if (sscanf(s, "%*s %d", &nang) != 1 || nang < 2 || nang > 1000000) { snprintf(msg, msglen, "%s:%d: bad angles count", path, lineno); goto done; }
            th = malloc(sizeof(double) * nang); P = malloc(sizeof(double) * nang);
            if (!th || !P) { snprintf(msg, msglen, "out of memory"); goto done; }
        } else if (!strcmp(key, "lambda_nm") || !strcmp(key, "sigma_ext_um2") || !strcmp(key, "g")) {
            /* informative; the transport uses --ke and the tabulated P */
        } else {
            snprintf(msg, msglen, "%s:%d: unknown key '%s'", path, lineno, key); goto done;
        }
    }
    if (nch != 3) { snprintf(msg, msglen, "%s: missing 'channels 3'", path); goto done; }
    if (nang < 0 || got != nang) { snprintf(msg, msglen, "%s: expected %d angle lines, found %d", path, nang < 0 ? 0 : nang, got); goto done; }
    rc = cu_phase_from_table(ph, nang, th, P, chop, fv[channel], msg, msglen);
    if (rc == 0 && chop > 0 && fabs(ph->f - fv[channel]) > 0.01)
        fprintf(stderr, "cumulo-slab: warning: %s: chopped fraction recomputed as %.4f, file says %.4f; using %.4f\n",
                path, ph->f, fv[channel], ph->f);
done:
    free(th); free(P);
    fclose(fp);
    return rc;
}

