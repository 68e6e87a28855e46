/* Monte Carlo transport in a non-absorbing plane-parallel slab (Bouthors 2008 slab study): phase functions, estimators, API. */
#ifndef CU_SLAB_H
#define CU_SLAB_H
#include <stdint.h>
#include <stdio.h>

/* Scattering-order groups n = 1, 2, 3, 4, 5-6, 7-9, 10-15, 16+ (Bouthors' sets plus single scattering). */
#define CU_NGROUP 8
int cu_slab_group(int order);              /* order >= 1 -> group index 0..7 */
const char *cu_slab_group_name(int g);     /* "1", "5-6", "16+", ... */

enum { CU_PH_ISO, CU_PH_HG, CU_PH_TAB };

/* Phase function used for *sampling and for the local estimators*, normalised to integrate to 1 over the sphere (sr^-1).
 * For a Mie table this is the chopped, renormalised function P~/(1-f); f is the removed forward-peak fraction. */
typedef struct {
    int kind;
    double g;          /* HG asymmetry; for a table the mean cosine of the (chopped) sampling function */
    double f;          /* removed peak fraction (0 unless chopped) */
    int n;             /* table: nodes uniform in theta, 0..180 deg */
    double dth;        /* node spacing, radians */
    double *mu;        /* cos(theta_i), descending from 1 to -1 */
    double *p;         /* density at the nodes, piecewise linear in mu between nodes */
    double *cdf;       /* integral of p dOmega from mu = 1 down to mu_i */
} cu_phase;

double cu_phase_eval(const cu_phase *ph, double cost);          /* p(cos Theta), sr^-1 */
double cu_phase_sample(const cu_phase *ph, double u);           /* cos Theta from a uniform u in [0,1) */
void cu_phase_free(cu_phase *ph);
/* Builds a tabulated phase function from (theta_deg, P) pairs, ascending 0..180, P with integral 1 over the sphere.
 * chop_deg > 0 applies Bouthors' chop (eq. 3.64, P~ = P(chop) below chop) and stores f = 1 - integral(P~).
 * If the input already integrates to 1 - f_hint (a pre-chopped table), f = f_hint. Returns 0 or -1 with msg set. */
int cu_phase_from_table(cu_phase *ph, int n, const double *th_deg, const double *P, double chop_deg, double f_hint,
                        char *msg, size_t msglen);
/* Reads the Mie table text format (tools/slab/README.md); channel 0..2. Returns 0 or -1 with msg set. */
int cu_phase_read_mie(cu_phase *ph, const char *path, int channel, char *msg, size_t msglen);

#define CU_MAXMU 32
#define CU_MAXGRID 64

typedef struct {
    double tau;        /* optical thickness actually transported (already multiplied by 1-f for chopped phase) */
    double mu0;        /* cos theta_L */
    double metres_per_tau; /* 1/k_e,eff, to express depths and collector moments in metres; 0 = optical units */
    const cu_phase *ph;
    long long photons;
    int nbatch;        /* fixed work units; results do not depend on the thread count */
    int threads;
    uint64_t seed;
    int quiet;
    /* radiance at outgoing cosines (local estimate), azimuth-averaged unless phi_deg >= 0 */
    int nmu; double mu[CU_MAXMU]; double phi_deg;
    /* interior BSDF table C(n, d, thetaV, phiV) (eq. 3.25) with collector moments (eqs. 3.29-3.31) */
    int table; int nd; double d_tau[CU_MAXGRID]; int nv; double thv_deg[CU_MAXGRID]; int nphi; double phv_deg[CU_MAXGRID];
    int max_order;     /* >0: stop each walk after this many scatterings (exact for orders <= max_order; tests) */
    int rank, nranks;  /* MPI: this process runs batches rank, rank+nranks, ... */
} cu_slab_cfg;

/* Sums over photons of a per-photon score and its square: mean and standard error. */
typedef struct { double s, s2; } cu_acc;

typedef struct {
    long long photons;
    double t_unscat;                    /* exp(-tau/mu0), exact */
    cu_acc R, T;                        /* diffuse reflected / transmitted flux per photon (analog exit count) */
    cu_acc Rn[CU_NGROUP], Tn[CU_NGROUP];
    /* escape-probability estimator (independent of the exit count; see README): per group and R+T */
    cu_acc Re, Te, Ren[CU_NGROUP], Ten[CU_NGROUP], RTe;
    cu_acc rad_r[CU_MAXMU], rad_t[CU_MAXMU];                   /* pi I/(mu0 F) */
    cu_acc rad_rn[CU_MAXMU][CU_NGROUP], rad_tn[CU_MAXMU][CU_NGROUP];
    long long collisions;
    /* table: per batch sums, 5 quantities per cell: sum C, sum C x', sum C z', sum C (x'^2+z'^2), (unused) */
    int ncell; double *tab;             /* [nbatch][ncell][4] */
    double seconds;
} cu_slab_result;

int cu_slab_ncell(const cu_slab_cfg *c);
int cu_slab_cell(const cu_slab_cfg *c, int grp, int id, int iv, int ip);
int cu_slab_run(const cu_slab_cfg *cfg, cu_slab_result *res);   /* 0 ok */
void cu_slab_result_free(cu_slab_result *res);
void cu_acc_stats(const cu_acc *a, long long n, double *mean, double *se);
/* Table cell statistics from batch means: C = I/F_sun (sr^-1); collector mean (cx, cz) and sigma, each with SE. */
typedef struct { double C, C_se, cx, cx_se, cz, cz_se, sigma, sigma_se; } cu_cell_stats;
void cu_slab_cell_stats(const cu_slab_cfg *cfg, const cu_slab_result *res, int cell, cu_cell_stats *st);
#endif
