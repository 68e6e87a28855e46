/* Narrow Mie resonances as poles in the complex size-parameter plane, and the trapezoid rule's error at a pole.
 *
 * Near a resonance of mode n, a_n(x) (or b_n) = R / (x - z) + (analytic), with z = x0 - i gamma just below the real
 * axis. The composite trapezoid rule on a uniform grid of step h integrates analytic integrands to exponential
 * accuracy, except for the poles of the integrand closer than ~h to the real axis: there its error is exactly
 * Res(f, z) E_h(z) with E_h(z) = -pi cot(pi (z - u0) / h) - i pi sgn(Im z) (grid u0 + j h). Poles of
 * |S|^2 = S(x) conj(S(conj x)) come in pairs z, conj z, so the correction is real. mietable.c finds every pole
 * with gamma < 3 h and subtracts these errors, which removes the sampling noise of resonances narrower than the
 * step (it falls only like sqrt(h) otherwise). */
#ifndef CUMULO_MIE_RESONANCE_H
#define CUMULO_MIE_RESONANCE_H

#include <complex.h>

/* 1/a_n(z) (isb = 0) or 1/b_n(z) (isb = 1) at complex size parameter z, for m in Bohren-Huffman sign (mb = n + ik,
 * as used inside mie_solve). Returns 0, or -1 if the continued fraction for D_n does not converge. */
int res_inv_coef(double complex mb, int n, int isb, double complex z, double complex *h);

/* Newton iteration from z0 for the pole of a_n / b_n; on success z is the pole and r the residue of the
 * coefficient there (dx units). Returns 0 on convergence, -1 if it fails or leaves the disc |z - z0| < radius. */
int res_find_pole(double complex mb, int n, int isb, double complex z0, double radius, double complex *z,
                  double complex *r);

/* Trapezoid error at a simple pole w in grid units (w = (z - u0) / h for nodes u0 + j h): the rule's sum
 * h sum_j f(u_j) minus the integral of f is Res(f, z) E(w), E(w) = -pi cot(pi w) - i pi sgn(Im w). */
double complex res_trap_error(double complex w);

/* a_n, b_n (n = 1..nterms, index n-1) at complex z, as mie_solve computes them on the real axis; d needs
 * nterms + 2 entries of scratch. Returns 0, or -1 if the continued fraction for D_n does not converge. */
int res_coefs(double complex mb, double complex z, int nterms, double complex *d, double complex *a,
              double complex *b);

/* Complex amplitudes S1, S2 (Bohren-Huffman sign) at mu_j and -mu_j from coefficients a, b (n = 1..nterms),
 * and pi_n, tau_n at mu_j for n = ntarget. Outputs have nmu entries each. */
void res_amplitudes(const double complex *a, const double complex *b, int nterms, const double *mu, int nmu,
                    int ntarget, double *pit, double *taut, double complex *s1f, double complex *s2f,
                    double complex *s1b, double complex *s2b);

#endif
