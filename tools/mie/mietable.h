/* Size- and spectrum-averaged Mie phase functions for cloud droplets, and the engine's RGB table built from them. */
#ifndef CUMULO_MIE_TABLE_H
#define CUMULO_MIE_TABLE_H

#include <complex.h>
#include <stdio.h>

/* What to average over. Zero is not a valid value for every field: start from mt_params_default(). */
typedef struct {
    int monodisperse;     /* 1: every droplet has radius radius_um */
    double radius_um;     /* monodisperse radius */
    double reff_um, veff; /* gamma distribution n(r) ~ r^((1-3v)/v) exp(-r/(reff v)) (Hansen 1971) */
    double dx;            /* size-parameter step of the radius quadrature where the droplets matter */
    double tail_stretch;  /* step multiplier in the large-radius tail (1 = uniform grid), see mietable.c */
    double lambda_min_nm, lambda_max_nm, dlambda_nm; /* band; min == max means one wavelength, one channel */
    int use_m;            /* 1: use m below instead of water at each wavelength */
    double complex m;     /* Wiscombe convention n - ik */
    int threads;          /* worker threads over wavelengths (results do not depend on it) */
    int poles;            /* 1: correct the radius quadrature for resonances narrower than the step (resonance.h) */
} mt_params;

mt_params mt_params_default(void);

/* Directions at which phase functions are sampled. The table grid is symmetric about 90 deg so that every
 * Mie evaluation serves theta and 180 - theta (mie_s11_pairs). */
typedef struct {
    int nhalf, nhalf_pad; /* cosines evaluated; padded to MIE_JBLOCK */
    double *mu;           /* nhalf_pad cosines */
    int nang;             /* output directions, theta ascending */
    double *theta_deg;    /* nang */
    int *src;             /* output i comes from mu index src[i] >> 1, backward hemisphere if src[i] & 1 */
} mt_angles;

/* The table grid: fine_deg steps on [0, fine_until] and [180 - fine_until, 180] (forward peak, glory), coarse_deg
 * between; the default table uses 0.05, 10, 0.25. Both step counts must be whole. */
int mt_angles_table(mt_angles *a, double fine_deg, double fine_until_deg, double coarse_deg);
/* Arbitrary directions (degrees, any order), for the command line. */
int mt_angles_list(mt_angles *a, const double *theta_deg, int n);
/* Adds to bw[c][i] (c = R, G, B; i < ns) the weight of wavelength node lo + i step in channel c's band integral
 * (mietable_grid.c explains the quadrature). */
void mt_band_weights(double lo, double step, int ns, double *bw[3]);
void mt_angles_free(mt_angles *a);

/* Channel results. p[c][i] is the phase function (sr^-1, integral over the sphere = 1) at theta_deg[i]. */
typedef struct {
    int nchan, nang;
    double *p[3];
    double lambda_nm[3];   /* response-weighted centroid wavelength (band) or the wavelength (single) */
    double sigma_ext[3];   /* <Q_ext pi r^2>, um^2 per droplet */
    double sigma_sca[3];   /* <Q_sca pi r^2>, um^2 per droplet */
    double geo[3];         /* <pi r^2>, um^2 per droplet */
    double g[3];           /* asymmetry from the Mie coefficients, not from the sampled p */
    double m_re[3];        /* refractive index at lambda_nm (informational) */
    int nsizes;            /* most radius nodes used at any one wavelength (informational) */
    long nsolves;          /* Mie evaluations made (grid nodes and resonances) */
    long npoles;           /* resonance poles corrected for */
} mt_result;

/* Averages over sizes (and, for a band, over wavelength with linear-sRGB weights); err gets a message. */
int mt_compute(const mt_params *p, const mt_angles *a, mt_result *r, char *err, size_t errlen);
void mt_result_free(mt_result *r);

/* Integral over the sphere of v(theta), theta_deg ascending: 2 pi int v sin(theta) dtheta, composite Simpson on
 * every run of equal steps (3/8 rule for an odd run). cosw != 0 integrates v cos(theta) instead. */
double mt_sphere_integral(const double *theta_deg, const double *v, int n, int cosw);

/* Chopped-peak split (Kol 2013 eqs. 3.64-3.69, after Bouthors): P~ = P(chop) below chop, P elsewhere;
 * f = int (P - P~) dOmega. chop_deg must be a grid angle; returns -1 if it is not. */
int mt_chop(const double *theta_deg, const double *p, int n, double chop_deg, double *f, double *ptilde);

/* Writes the engine table (format v1, see data/mie_cloud.md); command is recorded in the header. */
int mt_write_table(FILE *out, const mt_result *r, const double *theta_deg, const char *command, const mt_params *p);

#endif
