/* Lorenz-Mie scattering by one homogeneous sphere: efficiencies and amplitude functions (Wiscombe 1980 scheme). */
#ifndef CUMULO_MIE_H
#define CUMULO_MIE_H

#include <complex.h>

/* Results for one sphere. The refractive index follows Wiscombe: m = n - ik, k >= 0 absorbs. */
typedef struct {
    double qext, qsca, qback, g;
    int nterms; /* N = x + 4.05 x^(1/3) + 2, the series length actually summed */
} mie_q;

/* Scratch space reused between spheres so that the size-distribution loop does not allocate per droplet. */
typedef struct {
    int cap;              /* terms the arrays below can hold */
    double complex *a, *b; /* Mie coefficients a_n, b_n for n = 1..N (index n-1) */
    double complex *d;     /* logarithmic derivative D_n(mx), n = 0..nmx */
    int dcap;
} mie_work;

void mie_work_init(mie_work *w);
void mie_work_free(mie_work *w);

/* Series length recommended by Wiscombe (1980) for x up to 2e4: x + 4.05 x^(1/3) + 2. */
int mie_nterms(double x);

/* Computes a_n, b_n into w (returns 0, or -1 on allocation failure or bad input) and the efficiencies. */
int mie_solve(double complex m, double x, mie_work *w, mie_q *q);

/* Amplitude functions S1, S2 at cos(theta) = mu from the coefficients left in w by mie_solve. */
void mie_amplitude(const mie_work *w, int nterms, double mu, double complex *s1, double complex *s2);

/* Block size of mie_s11_pairs: mu arrays are padded to a multiple of this so the inner loop vectorises. */
enum { MIE_JBLOCK = 32 };

/* Adds weight * (|S1|^2 + |S2|^2)/2 at both mu_j and -mu_j (mu_j >= 0) into fwd[j] and bwd[j].
 * The parity relations pi_n(-mu) = (-1)^(n-1) pi_n(mu), tau_n(-mu) = (-1)^n tau_n(mu) give the backward
 * hemisphere from the same Legendre recurrence, halving the work of the size-distribution loop.
 * nmu must be a multiple of MIE_JBLOCK (pad with any mu, ignore the results). */
void mie_s11_pairs(const mie_work *w, int nterms, const double *mu, int nmu, double weight, double *fwd,
                   double *bwd);

#endif
