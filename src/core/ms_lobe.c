/* src/core/ms_lobe.c: the table of lobe-only light for ms.lobe (see ms_lobe.h).
 * Why: diffusion's delta-M medium counts the phase function's forward lobe (f = g^2 = 0.73 of all scattering at
 * g = 0.853) as unscattered, so a photon the lobe deflects by 10-30 degrees stays on the sun's line. Where a lit
 * face is seen near the sun's direction (toward the sun, a lit rim from below) that light is what the eye sees, and
 * without it those faces came out 15-30 % dark (README "Where the light goes"). The lobe's own scatterings are
 * counted here in closed form, in the small-angle picture (every lobe-only photon at a point has crossed the sun's
 * optical depth ts there): n lobe scatterings on the way are Poisson with mean f_d ts (delta-M's rate, the rate the
 * scaled beam keeps its photons at), their directions the lobe
 * convolved n times with itself, whose Legendre coefficients are the lobe's to the power n; the last scattering,
 * toward the eye, is the lobe once more. Summed over n >= 1 per order l:
 *   sum_n e^-ts (c_0 ts)^n / n! c_0 (c_l / c_0)^(n+1) = c_l (e^-(1 - c_l) ts - e^-ts)
 * with c_l = 2 pi int lobe P_l dmu scaled so that c_0 = f_d. n = 0 is the exact single scattering the shader already has. The shader
 * attenuates this light toward the eye by the chopped (not the scaled) optical depth: a lobe scattering on the way
 * out would make it a path with one lobe scattering more, which the table counts at that later point. */
#include "ms_lobe.h"
#include "vecmath.h"
#include <math.h>
#include <stdlib.h>

#define COARSE 512 /* angles the series is summed at (0.35 deg apart), then interpolated onto the table's */

static double *legendre(double mu, double *p, int n) /* P_0 .. P_{n-1} at mu */
{
    p[0] = 1.0;
    if (n > 1)
        p[1] = mu;
    for (int l = 1; l + 1 < n; l++)
        p[l + 1] = ((2.0 * l + 1.0) * mu * p[l] - l * p[l - 1]) / (l + 1.0);
    return p;
}

int cu_ms_lobe_table(const cu_phase_table *t, double one_minus_fd, double gp, float *out)
{
    const int n = t->n, L = CU_LOBE_L;
    double *c = calloc(3 * (size_t)L, sizeof(double));         /* the lobe's coefficients, per channel */
    double *a = malloc(sizeof(double) * COARSE * (size_t)L);    /* (2l + 1) / 4 pi P_l(cos theta_k) */
    double *coarse = malloc(sizeof(double) * COARSE * 3);
    double pl[CU_LOBE_L];
    if (!c || !a || !coarse) {
        free(c);
        free(a);
        free(coarse);
        return -1;
    }
    /* c_l by the trapezoidal rule in theta on the table's own grid (0.088 deg): int f dmu = int f sin(theta) dtheta */
    const double dth = CU_PI / (n - 1);
    for (int i = 0; i < n; i++) {
        double th = i * dth, mu = cos(th), w = (i == 0 || i == n - 1 ? 0.5 : 1.0) * dth * sin(th);
        double q0 = one_minus_fd * cu_phase_hg(gp, mu);
        legendre(mu, pl, L);
        for (int ch = 0; ch < 3; ch++) {
            double p = t->rgb[3 * i + ch] / (1.0 - t->f[ch]);
            double lobe = p - fmin(q0, p);
            if (lobe > 0.0)
                for (int l = 0; l < L; l++)
                    c[ch * L + l] += 2.0 * CU_PI * w * lobe * pl[l];
        }
    }
    /* the orders that matter: the lobe's coefficients fall off; beyond 1e-7 of c_0 they change nothing in 16 bits */
    int used = 1;
    for (int ch = 0; ch < 3; ch++)
        for (int l = 0; l < L; l++)
            if (fabs(c[ch * L + l]) > 1e-7 * fmax(c[ch * L], 1e-30) && l + 1 > used)
                used = l + 1;
    /* The lobe scatters at delta-M's rate f_d, the rate the scaled beam keeps its photons at, in its own shape: the
     * clamp above leaves it a little more weight (0.752 against f_d = 0.728 at g = 0.853) where the scaled phase
     * function rises above the true one */
    for (int ch = 0; ch < 3; ch++) {
        double s = c[ch * L] > 0.0 ? (1.0 - one_minus_fd) / c[ch * L] : 0.0;
        for (int l = 0; l < L; l++)
            c[ch * L + l] *= s;
    }
    for (int k = 0; k < COARSE; k++) {
        legendre(cos(k * CU_PI / (COARSE - 1)), pl, used);
        for (int l = 0; l < used; l++)
            a[(size_t)k * L + l] = (2.0 * l + 1.0) / (4.0 * CU_PI) * pl[l];
    }
    for (int r = 0; r < CU_LOBE_ROWS; r++) {
        double x = (double)r / (CU_LOBE_ROWS - 1), ts = CU_LOBE_TS_MAX * x * x;
        for (int ch = 0; ch < 3; ch++) {
            double m[CU_LOBE_L];
            for (int l = 0; l < used; l++) /* c_l (e^-(1 - c_l) ts - e^-ts): no overflow for any sign of c_l <= c_0 */
                m[l] = c[ch * L + l] * (exp(-(1.0 - c[ch * L + l]) * ts) - exp(-ts));
            for (int k = 0; k < COARSE; k++) {
                double s = 0.0;
                for (int l = 0; l < used; l++)
                    s += a[(size_t)k * L + l] * m[l];
                /* the truncated series rings a little about zero far from the lobe: the light is not negative */
                coarse[k * 3 + ch] = fmax(s, 0.0) * (1.0 - t->f[ch]);
            }
        }
        for (int i = 0; i < n; i++) {
            double xk = (double)i * (COARSE - 1) / (n - 1);
            int k = xk >= COARSE - 1 ? COARSE - 2 : (int)xk;
            double f = xk - k;
            for (int ch = 0; ch < 3; ch++)
                out[((size_t)r * n + i) * 3 + ch] =
                    (float)((1.0 - f) * coarse[k * 3 + ch] + f * coarse[(k + 1) * 3 + ch]);
        }
    }
    free(c);
    free(a);
    free(coarse);
    return 0;
}
