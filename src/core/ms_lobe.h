/* src/core/ms_lobe.h: the light the phase function's forward lobe alone carries to the eye over several scatterings,
 * which delta-M diffusion counts as unscattered (ms.lobe; ms_lobe.c, shaders_gles/ms_diffusion.glsl). */
#ifndef CU_MS_LOBE_H
#define CU_MS_LOBE_H
#include "phase.h"

#define CU_LOBE_ROWS 48      /* optical depths toward the sun, ts = CU_LOBE_TS_MAX (r / (ROWS - 1))^2 */
#define CU_LOBE_TS_MAX 40.0  /* beyond it the lobe's light is under e^-(1 - f) 40, below 1e-4 of the sun's */
#define CU_LOBE_L 384        /* Legendre orders summed: an HG 0.95 lobe's coefficients fall below 1e-6 by ~300 */

/* The source per unit extinction, per unit sun irradiance, of light scattered by the lobe alone, n >= 1 times on the
 * way in and once more toward the eye, at chopped optical depth ts from the sun, as a table over the phase table's
 * angles (t->n columns, theta_i = i pi / (n - 1)) and CU_LOBE_ROWS depths: out[(r * t->n + i) * 3 + c].
 * The medium is delta-M's (ms_diffusion.glsl): of the chopped phase function p = P~ / (1 - f_chop), the part
 * q = min(one_minus_fd HG(gp), p) scatters as itself and the lobe p - q counts as unscattered. Lobe-only light after
 * n scatterings has the lobe's Legendre coefficients to the power n + 1, and a Poisson number of them at delta-M's
 * rate f_d = 1 - one_minus_fd along the sun's path (the coefficients scaled so that c_0 = f_d): per order l,
 * c_l e^-ts (e^(c_l ts) - 1) (see ms_lobe.c). Values are
 * per unit true extinction: multiplied by 1 - f_chop, as the shader's sources are. Returns 0, or -1 out of memory. */
int cu_ms_lobe_table(const cu_phase_table *t, double one_minus_fd, double gp, float *out);
#endif
