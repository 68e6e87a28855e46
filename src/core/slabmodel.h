/* src/core/slabmodel.h: Bouthors' phenomenological multiple-scattering model of a plane-parallel slab (Kol eq. 3.32),
 * loaded from the fitted tables of tools/slab (data/slab_fit_bouthors.txt), evaluated on the CPU (the shader's twin,
 * for tests) and packed into the texture the shader samples (shaders_gles/ms_slab.glsl). */
#ifndef CU_SLABMODEL_H
#define CU_SLABMODEL_H
#include "cumulo.h"

#define CU_SLAB_GROUPS 8   /* scattering-order groups 1, 2, 3, 4, 5-6, 7-9, 10-15, 16+ */
#define CU_SLAB_MAX_T 16   /* thickness nodes */
#define CU_SLAB_MAX_V 32   /* theta_V nodes */
#define CU_SLAB_MAX_L 16   /* theta_L nodes */
#define CU_SLAB_MAX_P 32   /* Theta nodes of P* */
#define CU_SLAB_KE_REF 0.0905 /* m^-1: the extinction the tables' metres refer to (tools/slab: --ke default) */

/* Per (group, thickness) the eq. 3.32 functions on their nodes. C = I/F_sun (sr^-1); lengths in metres at
 * CU_SLAB_KE_REF. C = P*(Theta) A1*(thV) A2*(thL) cos thL log^2(d + D*)/log^2(B* + D*) exp(-(d - B*)^2/(2 C*^2)),
 * B* = B1*(thV) - B2*(thL). */
typedef struct cu_slab_model {
    int nt, nv, nl, np;
    double t[CU_SLAB_MAX_T];                 /* slab thickness nodes, m, ascending */
    double thv[CU_SLAB_MAX_V], thl[CU_SLAB_MAX_L], th[CU_SLAB_MAX_P]; /* degrees, ascending */
    double a1[CU_SLAB_GROUPS][CU_SLAB_MAX_T][CU_SLAB_MAX_V], b1[CU_SLAB_GROUPS][CU_SLAB_MAX_T][CU_SLAB_MAX_V];
    double c[CU_SLAB_GROUPS][CU_SLAB_MAX_T][CU_SLAB_MAX_V], d[CU_SLAB_GROUPS][CU_SLAB_MAX_T][CU_SLAB_MAX_V];
    double a2[CU_SLAB_GROUPS][CU_SLAB_MAX_T][CU_SLAB_MAX_L], b2[CU_SLAB_GROUPS][CU_SLAB_MAX_T][CU_SLAB_MAX_L];
    double p[CU_SLAB_GROUPS][CU_SLAB_MAX_T][CU_SLAB_MAX_P];
    double log_bound[CU_SLAB_GROUPS][CU_SLAB_MAX_T]; /* cap of each fit (slabmodel.c: bound_groups) */
    double kappa[CU_SLAB_MAX_T][CU_SLAB_MAX_L];      /* energy scaling <= 1 (slabmodel.c: conserve_energy) */
    double ms_up[CU_SLAB_MAX_T][CU_SLAB_MAX_L];      /* flux of orders 2+ out of the top and the bottom per unit */
    double ms_down[CU_SLAB_MAX_T][CU_SLAB_MAX_L];    /* flux received, after kappa (conserve_energy) */
} cu_slab_model;

/* The transport the tables were simulated with, for the energy check: single-scattering anisotropy g and the
 * factor from the tables' optical depth to the transported one (1, or 1 - f for a chopped Mie table, delta-M). */
typedef struct cu_slab_transport {
    double g, tau_scale;
} cu_slab_transport;

/* Reads the table; every (name, group, thickness, node) must be present exactly once, on the same node grids for
 * every group and thickness, with finite values (and positive where the model takes a logarithm). Errors read
 * "path:line: ...". */
int cu_slab_model_load(cu_slab_model *m, const char *path, cu_slab_transport tr, cu_error *err);
/* The same reader over text[0..len), named name in messages. */
int cu_slab_model_parse(cu_slab_model *m, const char *name, const char *text, size_t len, cu_slab_transport tr,
                        cu_error *err);

/* The transport of the tables committed in data/ (which phase function tools/slab/gen_tables.sh used for them). */
#define CU_SLAB_TABLES_MIE 1
int cu_slab_committed_transport(const char *data_dir, cu_slab_transport *tr, cu_error *err);

/* Multiply scattered radiance I/F_sun (sr^-1) at depth d (m, below the lit face) in a slab of thickness t (m), both
 * at CU_SLAB_KE_REF, toward view altitude thV (deg, 0 = light going down, 180 = up, Kol Fig. 3.6) with the sun at
 * thL (deg from the normal) and scattering angle Theta (deg): the sum over groups first_group..7 (0-based; 1 skips
 * single scattering). Interpolation, clamping and extrapolation exactly as the shader does them (see slabmodel.c). */
double cu_slab_model_eval(const cu_slab_model *m, int first_group, double t, double d, double thv, double thl,
                          double theta);

/* The texture the shader reads: RGBA32F, width nv + nl + np, height (CU_SLAB_GROUPS - 1) * nt (groups 2..16+):
 * texel (iv, row) = (log A1, B1, C, D), (nv + il, row) = (log A2, B2, kappa, 0), (nv + nl + ip, row) = (log P, 0, 0, 0)
 * and log_bound in the y of the first P texel. Logarithms: A1* reaches 5e53 (beyond fp32). */
void cu_slab_model_pack(const cu_slab_model *m, float *rgba);
/* Shares of the sunlight a slab of thickness t (table metres) lit at thl degrees receives that the model sends out
 * of its top (up) and bottom (down) by two or more scatterings (their sum is at most 1 - e^-tau'/mu0 - single
 * scattering, conserve_energy): linear in log t and in thl between the nodes, constant beyond the last nodes,
 * falling like t^2 (second order) below the first thickness. */
void cu_slab_model_ms_budget(const cu_slab_model *m, double t, double thl, double *up, double *down);
int cu_slab_model_tex_width(const cu_slab_model *m);
int cu_slab_model_tex_height(const cu_slab_model *m);
#endif
