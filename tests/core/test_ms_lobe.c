/* tests/core/test_ms_lobe.c: ms.lobe's table (src/core/ms_lobe.c) against closed forms: a lobe that is the whole of
 * a Henyey-Greenstein function, whose n-fold self-convolution is HG(g^n) exactly; the energy the lobe-only light
 * carries against the scaled beam's share; and the extremes (isotropic, g = 0.99, the chopped Mie table). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "ms_lobe.h"
#include "vecmath.h"

static double row_ts(int r)
{
    double x = (double)r / (CU_LOBE_ROWS - 1);
    return CU_LOBE_TS_MAX * x * x;
}

static float *table(const cu_phase_table *t, double one_minus_fd, double gp)
{
    float *out = malloc(sizeof(float) * 3 * CU_LOBE_ROWS * (size_t)t->n);
    assert_non_null(out);
    assert_int_equal(cu_ms_lobe_table(t, one_minus_fd, gp, out), 0);
    return out;
}

static cu_phase_table hg_table(double g)
{
    cu_scene s;
    cu_scene_defaults(&s);
    s.phase = CU_PHASE_HG;
    s.phase_g = g;
    cu_phase_table t;
    cu_error e;
    assert_int_equal(cu_phase_table_build(&t, &s, "data", &e), 0);
    return t;
}

/* 2 pi int M dmu over the table's columns (trapezoid in theta), channel c of row r */
static double energy(const cu_phase_table *t, const float *m, int r, int c)
{
    double s = 0.0, dth = CU_PI / (t->n - 1);
    for (int i = 0; i < t->n; i++)
        s += (i == 0 || i == t->n - 1 ? 0.5 : 1.0) * dth * sin(i * dth) * m[((size_t)r * t->n + i) * 3 + c];
    return 2.0 * CU_PI * s;
}

/* With nothing left to the scaled phase function (1 - f_d -> 0) the lobe is HG(g) itself and scatters at rate 1:
 * M(theta, ts) = sum_{n >= 1} e^-ts ts^n / n! HG(g^(n+1), theta). */
static void test_hg_lobe_closed_form(void **st)
{
    (void)st;
    const double g = 0.8;
    cu_phase_table t = hg_table(g);
    float *m = table(&t, 1e-12, 0.5);
    const double deg[] = {0.0, 5.0, 12.0, 30.0, 60.0, 120.0, 180.0};
    double worst = 0.0;
    for (int r = 0; r < CU_LOBE_ROWS; r += 3) {
        double ts = row_ts(r);
        for (int k = 0; k < 7; k++) {
            int i = (int)lround(deg[k] / 180.0 * (t.n - 1));
            double mu = cos(i * CU_PI / (t.n - 1)), want = 0.0, pn = exp(-ts), gn = g;
            for (int n = 1; n < 200; n++) {
                pn *= ts / n;
                gn *= g;
                want += pn * cu_phase_hg(gn, mu);
            }
            double got = m[((size_t)r * t.n + i) * 3 + 1];
            double err = fabs(got - want) / (want + 1e-4);
            worst = fmax(worst, err);
            if (err > 2e-3)
                fail_msg("ts %.3f, %.0f deg: table %.6g, closed form %.6g", ts, deg[k], got, want);
        }
    }
    printf("HG 0.8 as the whole lobe: worst relative difference from the closed form %.2e\n", worst);
    free(m);
    cu_phase_table_free(&t);
}

/* Delta-M's split (f_d = g^2, g' = g / (1 + g)): the lobe-only light over all directions is the lobe's share of the
 * scaled beam's scattered photons, f_d (e^-(1 - f_d) ts - e^-ts); none at ts = 0; never negative. */
static void check_energy(const cu_phase_table *t, double g, double tol)
{
    double fd = g * g;
    float *m = table(t, 1.0 - fd, g / (1.0 + g));
    double worst = 0.0;
    for (int c = 0; c < 3; c++)
        for (int r = 0; r < CU_LOBE_ROWS; r++) {
            double ts = row_ts(r), want = fd * (exp(-(1.0 - fd) * ts) - exp(-ts)) * (1.0 - t->f[c]);
            double got = energy(t, m, r, c);
            for (int i = 0; i < t->n; i++) {
                float v = m[((size_t)r * t->n + i) * 3 + c];
                assert_true(isfinite(v) && v >= 0.0f);
                if (r == 0)
                    assert_true(v == 0.0f);
            }
            if (want > 1e-4) {
                worst = fmax(worst, fabs(got / want - 1.0));
                if (fabs(got / want - 1.0) > tol)
                    fail_msg("g %.3f channel %d ts %.3f: energy %.6g, expected %.6g", g, c, ts, got, want);
            }
        }
    printf("g %.3f: energy within %.2e of f_d (e^-(1 - f_d) ts - e^-ts)\n", g, worst);
    free(m);
}

static void test_energy_hg(void **st)
{
    (void)st;
    const double gs[] = {0.5, 0.853, 0.95};
    for (int k = 0; k < 3; k++) {
        cu_phase_table t = hg_table(gs[k]);
        check_energy(&t, gs[k], 0.02);
        cu_phase_table_free(&t);
    }
}

/* The chopped Mie table: its own mean cosine as g, the same energy per channel */
static void test_energy_mie(void **st)
{
    (void)st;
    cu_phase_table t;
    cu_error e;
    if (cu_phase_table_load_mie(&t, "data/mie_cloud.tbl", &e))
        fail_msg("%s", e.msg);
    check_energy(&t, t.mean_cos[1], 0.02);
    cu_phase_table_free(&t);
}

/* Isotropic scattering has no lobe: the table is zero. g = 0.99 (a lobe a few degrees wide): finite, not negative. */
static void test_extremes(void **st)
{
    (void)st;
    cu_phase_table t = hg_table(0.0);
    float *m = table(&t, 1.0, 0.0);
    for (size_t i = 0; i < 3 * CU_LOBE_ROWS * (size_t)t.n; i++)
        assert_true(m[i] == 0.0f);
    free(m);
    cu_phase_table_free(&t);
    t = hg_table(0.99);
    check_energy(&t, 0.99, 0.05);
    cu_phase_table_free(&t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hg_lobe_closed_form),
        cmocka_unit_test(test_energy_hg),
        cmocka_unit_test(test_energy_mie),
        cmocka_unit_test(test_extremes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
