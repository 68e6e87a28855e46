/* src/core/phase.h: phase functions as RGB tables over the scattering angle for the shader (one texture row each):
 * Henyey-Greenstein, Cornette-Shanks, and (from data/) tabulated Mie. */
#ifndef CU_PHASE_H
#define CU_PHASE_H
#include "scene.h"

#define CU_PHASE_N 2048 /* theta_i = i * pi / (N - 1): 0.088 deg steps */

typedef struct cu_phase_table {
    int n;
    float *rgb;     /* n * 3 values, sr^-1: the phase function, chopped below chop_deg for Mie (P~, eq. 3.64) */
    float *peak;    /* n * 3 values: the removed peak P_p = P - P~ (eq. 3.65); NULL for analytic phases */
    double f[3];         /* weight of the removed peak, integral of P_p (eq. 3.68); 0 for analytic phases */
    double sigma_ext_um2[3]; /* extinction cross-section per droplet from the table; 0 = use 2 pi r_e^2 */
    double g_full[3];    /* <cos theta> of the full phase function (with the peak) */
    double integral[3];  /* 2 pi * integral of p sin(theta) dtheta: 1 up to the quadrature error */
    double mean_cos[3];  /* <cos theta>, the g used for similarity scaling */
} cu_phase_table;

/* Fills integral and mean_cos by the trapezoidal rule over the table's grid. */
void cu_phase_table_moments(cu_phase_table *t);

double cu_phase_hg(double g, double cos_theta);
double cu_phase_cornette_shanks(double g, double cos_theta);
int cu_phase_table_build(cu_phase_table *t, const cu_scene *s, const char *data_dir, cu_error *err);
/* Reads a Mie table (format in tools/mie; written by build/cumulo-mie --table) and resamples it onto the engine's
 * grid, split into P~ and P_p at the table's chop angle. Errors name file:line. */
int cu_phase_table_load_mie(cu_phase_table *t, const char *path, cu_error *err);
/* The same reader over text[0..len), named name in messages. */
int cu_phase_table_parse_mie(cu_phase_table *t, const char *name, const char *text, size_t len, cu_error *err);
void cu_phase_table_free(cu_phase_table *t);
/* Core extinction k_e in m^-1 for scene s with this table: rho_0 * sigma_ext (the table's green channel, one scalar
 * so opacity stays a scalar; the channels differ by ~1%) when the table has one, else rho_0 * 2 pi r_e^2 (Kol eq.
 * 3.3). Renderer and path tracer both take k_e from here. */
double cu_phase_table_extinction(const cu_phase_table *t, const cu_scene *s);
#endif
