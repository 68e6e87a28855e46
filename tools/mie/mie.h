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

/* The Mie series of S1 and S2 (Bohren-Huffman sign) at one block of MIE_JBLOCK directions mu[0..MIE_JBLOCK-1] from
 * the coefficients a, b (n = 1..nterms, index n-1), the one loop mie_s11_pairs and res_amplitudes share. The sums
 * are split by the parity of n, acc[0] odd and acc[1] even, so that the same pass gives -mu as well (see
 * mie_s11_pairs); acc[.][k]: k = 0,1 Re/Im of sum c_n a_n pi_n; 2,3 c b tau; 4,5 c a tau; 6,7 c b pi, with
 * c_n = (2n+1)/(n(n+1)). Fixed-size blocks keep the working set in L1 and give the compiler a constant trip count.
 * When ntarget is in 1..nterms, pi_n and tau_n of n = ntarget at the first nj directions go to pit and taut. */
void mie_series_block(const double complex *a, const double complex *b, int nterms, const double *mu, int ntarget,
                      int nj, double *pit, double *taut, double acc[2][8][MIE_JBLOCK]);

/* Adds weight * (|S1|^2 + |S2|^2)/2 at both mu_j and -mu_j (mu_j >= 0) into fwd[j] and bwd[j].
 * The parity relations pi_n(-mu) = (-1)^(n-1) pi_n(mu), tau_n(-mu) = (-1)^n tau_n(mu) give the backward
 * hemisphere from the same Legendre recurrence, halving the work of the size-distribution loop.
 * nmu must be a multiple of MIE_JBLOCK (pad with any mu, ignore the results). */
void mie_s11_pairs(const mie_work *w, int nterms, const double *mu, int nmu, double weight, double *fwd,
                   double *bwd);

#endif
