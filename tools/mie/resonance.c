/* Poles of the Mie coefficients in the complex size-parameter plane and the trapezoid error they cause. */
#include "resonance.h"
#include "mie.h"

#include <math.h>
#include <stddef.h>

static const double PI = 3.14159265358979323846;

/* 1/z without the special-case handling of the C library's complex division (finite, nonzero z here). */
static double complex cinv(double complex z)
{
    double re = creal(z), im = cimag(z), s = 1.0 / (re * re + im * im);
    return re * s - I * (im * s);
}

/* D_n(z) by Lentz's method, the same continued fraction as mie.c (private there); norms without hypot. */
static int lentz(int n, double complex z, double complex *out)
{
    const double tiny = 1e-300;
    double nu = n + 0.5;
    double complex iz = cinv(z);
    double complex f = 2.0 * nu * iz;
    double complex c = f, dd = 0.0;
    long kmax = (long)(2.0 * cabs(z)) + 10000;
    for (long k = 1; k < kmax; k++) {
        double complex b = 2.0 * (nu + k) * iz;
        dd = b - dd;
        if (fabs(creal(dd)) + fabs(cimag(dd)) < tiny)
            dd = tiny;
        c = b - cinv(c);
        if (fabs(creal(c)) + fabs(cimag(c)) < tiny)
            c = tiny;
        dd = cinv(dd);
        double complex delta = c * dd;
        f *= delta;
        double complex dm = delta - 1.0;
        if (creal(dm) * creal(dm) + cimag(dm) * cimag(dm) < 1e-32) {
            *out = f - n * iz;
            return 0;
        }
    }
    return -1;
}

/* h = 1/a_n (or 1/b_n) and dh/dz at complex z. */
static int inv_coef_d(double complex mb, int n, int isb, double complex z, double complex *h, double complex *dh)
{
    double complex w = mb * z, dn;
    if (lentz(n, w, &dn) != 0)
        return -1;
    /* psi_{-1} = cos, psi_0 = sin, chi_{-1} = -sin, chi_0 = cos, upward as in mie_solve. */
    double complex iz = cinv(z);
    double complex psi0 = ccos(z), psi1 = csin(z), chi0 = -csin(z), chi1 = ccos(z);
    for (int k = 1; k <= n; k++) {
        double complex psi = (2.0 * k - 1.0) * iz * psi1 - psi0;
        double complex chi = (2.0 * k - 1.0) * iz * chi1 - chi0;
        psi0 = psi1;
        psi1 = psi;
        chi0 = chi1;
        chi1 = chi;
    }
    double fn = n;
    double complex xi = psi1 - I * chi1, xim = psi0 - I * chi0;
    /* Riccati-Bessel derivatives: f_n' = f_{n-1} - n f_n / z, f_{n-1}' = -f_n + n f_{n-1} / z; and
     * D_n'(w) = n(n+1)/w^2 - 1 - D_n^2. */
    double complex dpsi = psi0 - fn * iz * psi1, dpsim = -psi1 + fn * iz * psi0;
    double complex dxi = xim - fn * iz * xi, dxim = -xi + fn * iz * xim;
    double complex dD = fn * (fn + 1.0) / (w * w) - 1.0 - dn * dn; /* dD/dw */
    double complex d, dd;
    if (isb) {
        d = mb * dn + fn * iz;
        dd = mb * mb * dD - fn * iz * iz;
    } else {
        d = dn / mb + fn * iz;
        dd = dD - fn * iz * iz;
    }
    double complex num = d * psi1 - psi0, den = d * xi - xim;
    if (num == 0.0)
        return -1;
    double complex dnum = dd * psi1 + d * dpsi - dpsim, dden = dd * xi + d * dxi - dxim;
    *h = den / num;
    if (dh)
        *dh = (dden * num - den * dnum) / (num * num);
    return 0;
}

int res_inv_coef(double complex mb, int n, int isb, double complex z, double complex *h)
{
    return inv_coef_d(mb, n, isb, z, h, NULL);
}

int res_find_pole(double complex mb, int n, int isb, double complex z0, double radius, double complex *z,
                  double complex *r)
{
    double complex zz = z0;
    /* From the linear prediction Newton converges in 3-5 steps; more mean a wrong start or a pole so narrow
     * that rounding (psi_n upward, ~eps chi/psi) stalls it, and such poles carry no weight. */
    for (int it = 0; it < 10; it++) {
        double complex h, dh;
        if (inv_coef_d(mb, n, isb, zz, &h, &dh) != 0)
            return -1;
        if (!(cabs(dh) > 0.0) || !isfinite(creal(dh)) || !isfinite(cimag(dh)))
            return -1;
        double complex step = h / dh;
        zz -= step;
        if (!isfinite(creal(zz)) || !isfinite(cimag(zz)) || creal(zz) <= 0.0 || cabs(zz - z0) > radius)
            return -1;
        if (cabs(step) < 1e-14 * cabs(zz) + 1e-7 * fabs(cimag(zz))) {
            /* The residue of a_n = 1/h at its pole is 1/h'; one more derivative at the converged point. */
            if (inv_coef_d(mb, n, isb, zz, &h, &dh) != 0)
                return -1;
            *z = zz;
            *r = 1.0 / dh;
            return 0;
        }
    }
    return -1;
}

double complex res_trap_error(double complex w)
{
    /* sum_j 1/(j - w) = -pi cot(pi w); the integral over the line of dt/(t - w) is i pi sgn(Im w). */
    double a = PI * creal(w), b = PI * cimag(w);
    double s = b > 0.0 ? 1.0 : -1.0;
    double complex cot;
    if (fabs(b) > 18.0)
        cot = 2.0 * sin(2.0 * a) * exp(-2.0 * fabs(b)) - I * s;
    else
        cot = (sin(2.0 * a) - I * sinh(2.0 * b)) / (cosh(2.0 * b) - cos(2.0 * a));
    return -PI * cot - I * PI * s;
}

int res_coefs(double complex mb, double complex z, int nterms, double complex *d, double complex *a,
              double complex *b)
{
    /* As mie_solve, at complex z: D_n(mb z) downward from Lentz's fraction, psi_n and chi_n upward. */
    double complex w = mb * z;
    int nmx = nterms + 1;
    if (lentz(nmx, w, &d[nmx]) != 0)
        return -1;
    double complex iw = cinv(w);
    for (int n = nmx; n >= 1; n--) {
        double complex r = n * iw;
        d[n - 1] = r - cinv(d[n] + r);
    }
    double complex iz = cinv(z);
    double complex psi0 = ccos(z), psi1 = csin(z), chi0 = -csin(z), chi1 = ccos(z);
    for (int n = 1; n <= nterms; n++) {
        double fn = n;
        double complex psi = (2.0 * fn - 1.0) * iz * psi1 - psi0;
        double complex chi = (2.0 * fn - 1.0) * iz * chi1 - chi0;
        double complex xi = psi - I * chi, xi1 = psi1 - I * chi1;
        double complex da = d[n] / mb + fn * iz, db = mb * d[n] + fn * iz;
        a[n - 1] = (da * psi - psi1) / (da * xi - xi1);
        b[n - 1] = (db * psi - psi1) / (db * xi - xi1);
        psi0 = psi1;
        psi1 = psi;
        chi0 = chi1;
        chi1 = chi;
    }
    return 0;
}

void res_amplitudes(const double complex *a, const double complex *b, int nterms, const double *mu, int nmu,
                    int ntarget, double *pit, double *taut, double complex *s1f, double complex *s2f,
                    double complex *s1b, double complex *s2b)
{
    enum { J = MIE_JBLOCK };
    for (int j0 = 0; j0 < nmu; j0 += J) {
        double acc[2][8][J], m[J];
        int nj = nmu - j0 < J ? nmu - j0 : J;
        for (int j = 0; j < J; j++)
            m[j] = j < nj ? mu[j0 + j] : 1.0; /* padding: any direction, its sums are not read */
        mie_series_block(a, b, nterms, m, ntarget, nj, pit + j0, taut + j0, acc);
        /* pi_n(-mu) = (-1)^(n-1) pi_n(mu), tau_n(-mu) = (-1)^n tau_n(mu): odd n keep pi and flip tau. */
        double(*o)[J] = acc[0];
        double(*e)[J] = acc[1];
        for (int j = 0; j < nj; j++) {
            s1f[j0 + j] = (o[0][j] + e[0][j] + o[2][j] + e[2][j]) + I * (o[1][j] + e[1][j] + o[3][j] + e[3][j]);
            s2f[j0 + j] = (o[4][j] + e[4][j] + o[6][j] + e[6][j]) + I * (o[5][j] + e[5][j] + o[7][j] + e[7][j]);
            s1b[j0 + j] = (o[0][j] - e[0][j] - o[2][j] + e[2][j]) + I * (o[1][j] - e[1][j] - o[3][j] + e[3][j]);
            s2b[j0 + j] =
                (-o[4][j] + e[4][j] + o[6][j] - e[6][j]) + I * (-o[5][j] + e[5][j] + o[7][j] - e[7][j]);
        }
    }
}
