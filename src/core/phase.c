/* src/core/phase.c: analytic phase functions and the tables the shader samples (see phase.h). */
#include "phase.h"
#include "error.h"
#include "textfile.h"
#include "vecmath.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

double cu_phase_hg(double g, double mu)
{
    double d = 1.0 + g * g - 2.0 * g * mu;
    return (1.0 - g * g) / (4.0 * CU_PI * d * sqrt(d));
}

double cu_phase_cornette_shanks(double g, double mu)
{
    double d = 1.0 + g * g - 2.0 * g * mu;
    return 3.0 * (1.0 - g * g) * (1.0 + mu * mu) / (8.0 * CU_PI * (2.0 + g * g) * d * sqrt(d));
}

/* Reads the n numbers of tokens tok[0..n-1] (ntok of them on the line) into v: 0 when there are exactly n and each is
 * finite, 1 otherwise; a number that is finite but not in float range fails with its own message (names[i]) and 2. */
static int read_numbers(const cu_textfile *f, char *const *tok, int ntok, double *v, int n, const char *const *names,
                        cu_error *err)
{
    if (ntok != n)
        return 1;
    for (int i = 0; i < n; i++) {
        cu_num_status s = cu_text_number(tok[i], &v[i]);
        if (s == CU_NUM_NOT_FLOAT)
            return 1 + cu_text_fail_float(f, err, names[i], tok[i]);
        if (s != CU_NUM_OK)
            return 1;
    }
    return 0;
}

/* 2 pi int P dmu and 2 pi int P mu dmu of channel c by the trapezoid rule in theta over the table's own rows, every
 * step-th one (the last row always included). */
static void row_moments(const double *th, const double *pv, int n, int c, int step, double *m0, double *m1)
{
    *m0 = *m1 = 0;
    for (int a = 0, b; a < n - 1; a = b) {
        b = a + step < n ? a + step : n - 1;
        double ta = th[a] * CU_PI / 180, tb = th[b] * CU_PI / 180, w = CU_PI * (tb - ta);
        double fa = pv[3 * a + c] * sin(ta), fb = pv[3 * b + c] * sin(tb);
        *m0 += w * (fa + fb);
        *m1 += w * (fa * cos(ta) + fb * cos(tb));
    }
}

/* The table must integrate to what it claims: P normalised over the sphere (the header's promise, and what the
 * shader assumes) and the g it states. The tolerance comes from the table's grid: the trapezoid error of the full
 * rows is about |T(h) - T(2h)| / 3 (Richardson; the rule is second order), so |T(h) - T(2h)| allows three times
 * that, plus 1e-6 for the 8 significant digits the rows are written with. It is capped at 1e-2: a table whose own
 * step halving moves its integral by more than 1% does not resolve its phase function. */
static int check_integrals(const double *th, const double *pv, int n, const double g[3], const char *path,
                           int ln_angles, int ln_g, cu_error *err)
{
    static const char *const names[3] = {"P_r", "P_g", "P_b"};
    for (int c = 0; c < 3; c++) {
        double a0, a1, b0, b1;
        row_moments(th, pv, n, c, 1, &a0, &a1);
        row_moments(th, pv, n, c, 2, &b0, &b1);
        double tol = fmin(1e-2, fabs(a0 - b0) + 1e-6);
        if (!(fabs(a0 - 1) <= tol))
            return cu_fail(err, "%s:%d: field '%s': 2 pi int P dmu is %.9g, not 1 (tolerance %.2g from the grid)",
                           path, ln_angles, names[c], a0, tol);
        double ga = a1 / a0, gb = b0 > 0 ? b1 / b0 : 0;
        tol = fmin(1e-2, fabs(ga - gb) + 1e-6);
        if (!(fabs(ga - g[c]) <= tol))
            return cu_fail(err, "%s:%d: field 'g': %.9g, but P gives %.9g (tolerance %.2g from the grid)", path, ln_g,
                           g[c], ga, tol);
    }
    return 0;
}

static int read_mie(cu_phase_table *t, cu_textfile f, cu_error *err);

int cu_phase_table_load_mie(cu_phase_table *t, const char *path, cu_error *err)
{
    memset(t, 0, sizeof *t);
    char hint[1100];
    snprintf(hint, sizeof hint, "make it with build/cumulo-mie --table %s", path);
    cu_textfile f;
    if (cu_textfile_open(&f, path, "the Mie table", hint, err))
        return 1;
    return read_mie(t, f, err);
}

int cu_phase_table_parse_mie(cu_phase_table *t, const char *name, const char *text, size_t len, cu_error *err)
{
    memset(t, 0, sizeof *t);
    cu_textfile f;
    if (cu_textfile_open_mem(&f, name, text, len, err))
        return 1;
    return read_mie(t, f, err);
}

/* The table from f, an open reader that this closes. */
static int read_mie(cu_phase_table *t, cu_textfile f, cu_error *err)
{
    const char *path = f.path;
    static const char *const row_names[4] = {"theta_deg", "P_r", "P_g", "P_b"};
    int have = 0, nang = -1, got = 0, rc = 0, r;
    double chop = -1, lam[3], g[3] = {0};
    int ln_angles = 0, ln_g = 0;
    double *th = NULL, *pv = NULL;
    while (!rc && (r = cu_textfile_next(&f, err)) != 0) {
        if (r < 0) {
            rc = 1;
            break;
        }
        int ln = f.line;
        if (nang >= 0) { /* angle rows */
            double v[4];
            if (got >= nang) {
                rc = cu_fail(err, "%s:%d: more angle rows than 'angles' says", path, ln);
                break;
            }
            int bad = read_numbers(&f, f.tok, f.ntok, v, 4, row_names, err);
            if (bad) {
                if (bad == 1)
                    cu_fail(err, "%s:%d: angle row needs 4 finite numbers: theta_deg P_r P_g P_b", path, ln);
                rc = 1;
                break;
            }
            if (v[0] < 0 || v[0] > 180 || (got > 0 && v[0] <= th[got - 1]) || (got == 0 && v[0] != 0) ||
                v[1] < 0 || v[2] < 0 || v[3] < 0) {
                rc = cu_fail(err, "%s:%d: angles must rise from 0 to 180 degrees and P must be >= 0", path, ln);
                break;
            }
            th[got] = v[0];
            for (int c = 0; c < 3; c++)
                pv[3 * got + c] = v[1 + c];
            got++;
            continue;
        }
        /* header keys: how many numbers each takes, and the message when they are missing or out of range */
        enum { K_CHANNELS, K_LAMBDA, K_SIGMA, K_G, K_CHOP, K_F, K_ANGLES, K_COUNT };
        static const struct { const char *name; int n; const char *need; } keys[K_COUNT] = {
            {"channels", 1, "'channels' must be 3"},
            {"lambda_nm", 3, "'lambda_nm' needs 3 numbers"},
            {"sigma_ext_um2", 3, "'sigma_ext_um2' needs 3 positive numbers"},
            {"g", 3, "'g' needs 3 numbers"},
            {"chop_deg", 1, "'chop_deg' must be in (0, 90)"},
            {"f", 3, "'f' needs 3 numbers"},
            {"angles", 1, "'angles' must be a count from 2 to 1000000"},
        };
        int k = 0;
        while (k < K_COUNT && strcmp(f.tok[0], keys[k].name) != 0)
            k++;
        if (k == K_COUNT) {
            rc = cu_fail(err, "%s:%d: unknown key '%.31s'", path, ln, f.tok[0]);
            break;
        }
        const char *const names[3] = {keys[k].name, keys[k].name, keys[k].name};
        double v[3];
        int bad = read_numbers(&f, f.tok + 1, f.ntok - 1, v, keys[k].n, names, err);
        if (!bad)
            switch (k) {
            case K_CHANNELS: bad = v[0] != 3; break;
            case K_SIGMA: bad = v[0] <= 0 || v[1] <= 0 || v[2] <= 0; break;
            case K_CHOP: bad = v[0] <= 0 || v[0] >= 90; break;
            case K_ANGLES: bad = v[0] < 2 || v[0] > 1e6 || v[0] != floor(v[0]); break;
            default: break;
            }
        if (bad) {
            rc = bad == 2 ? 1 : cu_fail(err, "%s:%d: %s", path, ln, keys[k].need);
            break;
        }
        switch (k) {
        case K_LAMBDA: memcpy(lam, v, sizeof v); have |= 1; break;
        case K_SIGMA: memcpy(t->sigma_ext_um2, v, sizeof v); have |= 2; break;
        case K_G: memcpy(g, v, sizeof v); ln_g = ln; have |= 4; break;
        case K_CHOP: chop = v[0]; break;
        case K_F: have |= 8; break;
        case K_ANGLES:
            nang = (int)v[0];
            ln_angles = ln;
            th = malloc(sizeof(double) * (size_t)nang);
            pv = malloc(sizeof(double) * 3 * (size_t)nang);
            if (!th || !pv)
                rc = cu_fail(err, "%s:%d: out of memory", path, ln);
            break;
        default: break;
        }
    }
    int ln = f.line;
    cu_textfile_close(&f);
    if (!rc && (have != 15 || chop < 0 || nang < 0))
        rc = cu_fail(err, "%s:%d: incomplete table: needs lambda_nm, sigma_ext_um2, g, chop_deg, f and angles", path,
                     ln);
    if (!rc && got != nang)
        rc = cu_fail(err, "%s:%d: fewer angle rows than 'angles' says (truncated file?)", path, ln);
    if (!rc && th[nang - 1] != 180)
        rc = cu_fail(err, "%s:%d: the last angle row must be 180 degrees", path, ln);
    if (!rc)
        rc = check_integrals(th, pv, nang, g, path, ln_angles, ln_g, err);
    if (rc) {
        free(th);
        free(pv);
        return 1;
    }
    /* Resample onto the engine's uniform grid (linear in theta; the table is at least as fine everywhere), then
     * chop: P~ = P(chop) below the chop angle (eq. 3.64), P_p = P - P~ (eq. 3.65). */
    t->n = CU_PHASE_N;
    t->rgb = malloc(sizeof(float) * 3 * (size_t)t->n);
    t->peak = malloc(sizeof(float) * 3 * (size_t)t->n);
    double *full = malloc(sizeof(double) * 3 * (size_t)t->n);
    if (!t->rgb || !t->peak || !full) {
        free(th); free(pv); free(full);
        cu_phase_table_free(t);
        return cu_fail(err, "%s: out of memory", path);
    }
    int j = 0;
    for (int i = 0; i < t->n; i++) {
        double deg = 180.0 * i / (t->n - 1);
        while (j < nang - 2 && th[j + 1] < deg)
            j++;
        double u = (deg - th[j]) / (th[j + 1] - th[j]);
        u = u < 0 ? 0 : u > 1 ? 1 : u;
        for (int c = 0; c < 3; c++)
            full[3 * i + c] = pv[3 * j + c] + u * (pv[3 * (j + 1) + c] - pv[3 * j + c]);
    }
    int ichop = (int)ceil(chop / 180.0 * (t->n - 1));
    for (int i = 0; i < t->n; i++)
        for (int c = 0; c < 3; c++) {
            double chopped = i < ichop ? full[3 * ichop + c] : full[3 * i + c];
            t->rgb[3 * i + c] = (float)chopped;
            t->peak[3 * i + c] = (float)(full[3 * i + c] - chopped > 0 ? full[3 * i + c] - chopped : 0);
        }
    /* g of the full function and f = integral of P_p, both on the engine's grid (trapezoid in theta). */
    double h = CU_PI / (t->n - 1);
    for (int c = 0; c < 3; c++) {
        double s0 = 0, s1 = 0, sp = 0;
        for (int i = 0; i < t->n; i++) {
            double w = (i == 0 || i == t->n - 1) ? 0.5 : 1.0, st = sin(h * i) * w * h * 2 * CU_PI;
            s0 += full[3 * i + c] * st;
            s1 += full[3 * i + c] * st * cos(h * i);
            sp += t->peak[3 * i + c] * st;
        }
        t->g_full[c] = s1 / s0;
        t->f[c] = sp;
    }
    free(th);
    free(pv);
    free(full);
    cu_phase_table_moments(t);
    return 0;
}

int cu_phase_table_build(cu_phase_table *t, const cu_scene *s, const char *data_dir, cu_error *err)
{
    if (s->phase == CU_PHASE_MIE) {
        char path[1024];
        snprintf(path, sizeof path, "%s/mie_cloud.tbl", data_dir);
        return cu_phase_table_load_mie(t, path, err);
    }
    memset(t, 0, sizeof *t);
    t->n = CU_PHASE_N;
    t->rgb = malloc(sizeof(float) * 3 * (size_t)t->n);
    if (!t->rgb) {
        return cu_fail(err, "phase table: out of memory");
    }
    for (int i = 0; i < t->n; i++) {
        double mu = cos(CU_PI * i / (t->n - 1));
        double p = s->phase == CU_PHASE_HG ? cu_phase_hg(s->phase_g, mu) : cu_phase_cornette_shanks(s->phase_g, mu);
        t->rgb[3 * i] = t->rgb[3 * i + 1] = t->rgb[3 * i + 2] = (float)p;
    }
    cu_phase_table_moments(t);
    for (int c = 0; c < 3; c++)
        t->g_full[c] = t->mean_cos[c];
    return 0;
}

void cu_phase_table_moments(cu_phase_table *t)
{
    for (int c = 0; c < 3; c++) {
        double s0 = 0, s1 = 0, h = CU_PI / (t->n - 1);
        for (int i = 0; i < t->n; i++) {
            double th = h * i, w = (i == 0 || i == t->n - 1) ? 0.5 : 1.0;
            double v = t->rgb[3 * i + c] * sin(th) * w * h * 2.0 * CU_PI;
            s0 += v;
            s1 += v * cos(th);
        }
        t->integral[c] = s0;
        t->mean_cos[c] = s0 > 0 ? s1 / s0 : 0;
    }
}

void cu_phase_table_free(cu_phase_table *t)
{
    free(t->rgb);
    free(t->peak);
    t->rgb = NULL;
    t->peak = NULL;
}

double cu_phase_table_extinction(const cu_phase_table *t, const cu_scene *s)
{
    if (t->sigma_ext_um2[1] > 0)
        return s->density_cm3 * 1e6 * t->sigma_ext_um2[1] * 1e-12;
    return cu_scene_core_extinction(s);
}
