/* src/phase.c: analytic phase functions and the tables the shader samples (see phase.h). */
#include "phase.h"
#include "vecmath.h"
#include <stdio.h>
#include <stdlib.h>

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

int cu_phase_table_build(cu_phase_table *t, const cu_scene *s, const char *data_dir, cu_error *err)
{
    (void)data_dir;
    t->n = CU_PHASE_N;
    t->rgb = malloc(sizeof(float) * 3 * (size_t)t->n);
    if (!t->rgb) {
        snprintf(err->msg, sizeof err->msg, "phase table: out of memory");
        return 1;
    }
    if (s->phase == CU_PHASE_MIE) {
        free(t->rgb);
        t->rgb = NULL;
        snprintf(err->msg, sizeof err->msg,
                 "%s: phase = mie needs the Mie table, which this build does not load yet; use hg or cornette-shanks",
                 s->name);
        return 1;
    }
    for (int i = 0; i < t->n; i++) {
        double mu = cos(CU_PI * i / (t->n - 1));
        double p = s->phase == CU_PHASE_HG ? cu_phase_hg(s->phase_g, mu) : cu_phase_cornette_shanks(s->phase_g, mu);
        t->rgb[3 * i] = t->rgb[3 * i + 1] = t->rgb[3 * i + 2] = (float)p;
    }
    cu_phase_table_moments(t);
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
    t->rgb = NULL;
}
