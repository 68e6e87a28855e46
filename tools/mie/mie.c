/* Lorenz-Mie solver: Wiscombe's (1980) recurrences, written after Bohren & Huffman's BHMIE layout. */
#include "mie.h"

#include <math.h>
#include <stdlib.h>

void mie_work_init(mie_work *w)
{
    w->cap = 0;
    w->dcap = 0;
    w->a = w->b = w->d = NULL;
}

void mie_work_free(mie_work *w)
{
    free(w->a);
    free(w->b);
    free(w->d);
    mie_work_init(w);
}

int mie_nterms(double x)
{
    /* Wiscombe (1980) eq. for the series cut-off; enough for |a_n|, |b_n| < 1e-14 beyond it. */
    return (int)(x + 4.05 * cbrt(x) + 2.0);
}

static int grow(mie_work *w, int nterms, int nd)
{
    if (nterms > w->cap) {
        double complex *a = realloc(w->a, (size_t)nterms * sizeof *a);
        if (!a)
            return -1;
        w->a = a;
        double complex *b = realloc(w->b, (size_t)nterms * sizeof *b);
        if (!b)
            return -1;
        w->b = b;
        w->cap = nterms;
    }
    if (nd + 1 > w->dcap) {
        double complex *d = realloc(w->d, (size_t)(nd + 1) * sizeof *d);
        if (!d)
            return -1;
        w->d = d;
        w->dcap = nd + 1;
    }
    return 0;
}

/* D_n(z) = -n/z + J_{n-1/2}(z)/J_{n+1/2}(z), the Bessel ratio from its continued fraction
 * a_k = 2(n + 1/2 + k - 1)/z, partial numerators -1, evaluated by the modified Lentz method (Lentz 1976). */
static int lentz_logderiv(int n, double complex z, double complex *out)
{
    const double tiny = 1e-300;
    double nu = n + 0.5;
    double complex f = 2.0 * nu / z;
    double complex c = f, dd = 0.0;
    /* The fraction needs about |z| - n terms before it converges when n < |z|. */
    long kmax = (long)(2.0 * cabs(z)) + 10000;
    for (long k = 1; k < kmax; k++) {
        double complex b = 2.0 * (nu + k) / z;
        dd = b - dd;
        if (cabs(dd) < tiny)
            dd = tiny;
        c = b - 1.0 / c;
        if (cabs(c) < tiny)
            c = tiny;
        dd = 1.0 / dd;
        double complex delta = c * dd;
        f *= delta;
        if (cabs(delta - 1.0) < 1e-16) {
            *out = f - n / z;
            return 0;
        }
    }
    return -1;
}

int mie_solve(double complex m, double x, mie_work *w, mie_q *q)
{
    if (!(x > 0.0) || !isfinite(x) || !(creal(m) > 0.0) || !(cimag(m) <= 0.0) || !isfinite(creal(m)) ||
        !isfinite(cimag(m)))
        return -1;
    /* Internally Bohren & Huffman's sign (m = n + ik, exp(-iwt)); only S1, S2 get conjugated by this, and
     * |S|^2, Re S(0) and every efficiency are the same in both conventions. */
    double complex mb = conj(m);
    double complex mx = mb * x;
    int nterms = mie_nterms(x);
    /* D_n(mx) is unstable upward when Im(m)x is large, so it is recurred downward (Wiscombe 1980, sec. 4)
     * from a start value given exactly by Lentz's continued fraction. Starting from D = 0 instead (BHMIE)
     * leaves errors in Q_ext at large x (tools/mie/README.md), because the recurrence damps the wrong start
     * only slowly while n < |mx|. */
    int nmx = nterms + 1;
    if (grow(w, nterms, nmx) != 0)
        return -1;
    double complex *d = w->d;
    if (lentz_logderiv(nmx, mx, &d[nmx]) != 0)
        return -1;
    for (int n = nmx; n >= 1; n--) {
        double complex r = n / mx;
        d[n - 1] = r - 1.0 / (d[n] + r);
    }

    /* psi_n and chi_n go upward: psi is stable up to N ~ x + O(x^(1/3)), which is where the series stops. */
    double psi0 = cos(x), psi1 = sin(x);
    double chi0 = -sin(x), chi1 = cos(x);
    double complex xi1 = psi1 - I * chi1;
    double sext = 0.0, ssca = 0.0, sg = 0.0;
    double complex sback = 0.0;
    double complex aprev = 0.0, bprev = 0.0;
    for (int n = 1; n <= nterms; n++) {
        double fn = n;
        double psi = (2.0 * fn - 1.0) * psi1 / x - psi0;
        double chi = (2.0 * fn - 1.0) * chi1 / x - chi0;
        double complex xi = psi - I * chi;
        double complex da = d[n] / mb + fn / x;
        double complex db = mb * d[n] + fn / x;
        double complex an = (da * psi - psi1) / (da * xi - xi1);
        double complex bn = (db * psi - psi1) / (db * xi - xi1);
        w->a[n - 1] = an;
        w->b[n - 1] = bn;
        sext += (2.0 * fn + 1.0) * creal(an + bn);
        ssca += (2.0 * fn + 1.0) * (creal(an) * creal(an) + cimag(an) * cimag(an) + creal(bn) * creal(bn) +
                                    cimag(bn) * cimag(bn));
        /* Asymmetry: Bohren & Huffman eq. 4.62 split into the (n-1, n) cross term and the (n, n) term. */
        if (n > 1) {
            double fm = fn - 1.0;
            sg += fm * (fm + 2.0) / (fm + 1.0) * creal(aprev * conj(an) + bprev * conj(bn));
        }
        sg += (2.0 * fn + 1.0) / (fn * (fn + 1.0)) * creal(an * conj(bn));
        sback += (2.0 * fn + 1.0) * ((n & 1) ? -1.0 : 1.0) * (an - bn);
        aprev = an;
        bprev = bn;
        psi0 = psi1;
        psi1 = psi;
        chi0 = chi1;
        chi1 = chi;
        xi1 = psi1 - I * chi1;
    }
    double x2 = x * x;
    q->nterms = nterms;
    q->qext = 2.0 * sext / x2;
    q->qsca = 2.0 * ssca / x2;
    q->g = 4.0 * sg / (x2 * q->qsca);
    q->qback = (creal(sback) * creal(sback) + cimag(sback) * cimag(sback)) / x2;
    return 0;
}

void mie_amplitude(const mie_work *w, int nterms, double mu, double complex *s1, double complex *s2)
{
    double pim1 = 0.0, pin = 1.0;
    double complex a1 = 0.0, a2 = 0.0;
    for (int n = 1; n <= nterms; n++) {
        double fn = n;
        double tau = fn * mu * pin - (fn + 1.0) * pim1;
        double cn = (2.0 * fn + 1.0) / (fn * (fn + 1.0));
        a1 += cn * (w->a[n - 1] * pin + w->b[n - 1] * tau);
        a2 += cn * (w->a[n - 1] * tau + w->b[n - 1] * pin);
        double pnext = ((2.0 * fn + 1.0) * mu * pin - (fn + 1.0) * pim1) / fn;
        pim1 = pin;
        pin = pnext;
    }
    /* Back to Wiscombe's sign convention (see mie_solve). */
    *s1 = conj(a1);
    *s2 = conj(a2);
}

void mie_series_block(const double complex *a, const double complex *b, int nterms, const double *mu, int ntarget,
                      int nj, double *pit, double *taut, double acc[2][8][MIE_JBLOCK])
{
    enum { J = MIE_JBLOCK };
    double pim1[J], pin[J], m[J];
    for (int j = 0; j < J; j++) {
        m[j] = mu[j];
        pim1[j] = 0.0;
        pin[j] = 1.0;
        for (int k = 0; k < 8; k++)
            acc[0][k][j] = acc[1][k][j] = 0.0;
    }
    for (int n = 1; n <= nterms; n++) {
        double fn = n;
        double cn = (2.0 * fn + 1.0) / (fn * (fn + 1.0));
        double car = cn * creal(a[n - 1]), cai = cn * cimag(a[n - 1]);
        double cbr = cn * creal(b[n - 1]), cbi = cn * cimag(b[n - 1]);
        double c1 = (2.0 * fn + 1.0) / fn, c2 = (fn + 1.0) / fn, np1 = fn + 1.0;
        double(*A)[J] = acc[(n & 1) ? 0 : 1];
        if (n == ntarget)
            for (int j = 0; j < nj; j++) {
                pit[j] = pin[j];
                taut[j] = fn * m[j] * pin[j] - np1 * pim1[j];
            }
        for (int j = 0; j < J; j++) {
            double p = pin[j], pm = pim1[j];
            double tau = fn * m[j] * p - np1 * pm;
            A[0][j] += car * p;
            A[1][j] += cai * p;
            A[2][j] += cbr * tau;
            A[3][j] += cbi * tau;
            A[4][j] += car * tau;
            A[5][j] += cai * tau;
            A[6][j] += cbr * p;
            A[7][j] += cbi * p;
            pim1[j] = p;
            pin[j] = c1 * m[j] * p - c2 * pm;
        }
    }
}

void mie_s11_pairs(const mie_work *w, int nterms, const double *mu, int nmu, double weight, double *fwd,
                   double *bwd)
{
    enum { J = MIE_JBLOCK };
    for (int j0 = 0; j0 < nmu; j0 += J) {
        double acc[2][8][J];
        mie_series_block(w->a, w->b, nterms, mu + j0, 0, J, NULL, NULL, acc);
        for (int j = 0; j < J && j0 + j < nmu; j++) {
            double(*O)[J] = acc[0];
            double(*E)[J] = acc[1];
            double s1fr = O[0][j] + E[0][j] + O[2][j] + E[2][j], s1fi = O[1][j] + E[1][j] + O[3][j] + E[3][j];
            double s2fr = O[4][j] + E[4][j] + O[6][j] + E[6][j], s2fi = O[5][j] + E[5][j] + O[7][j] + E[7][j];
            double s1br = O[0][j] - E[0][j] - O[2][j] + E[2][j], s1bi = O[1][j] - E[1][j] - O[3][j] + E[3][j];
            double s2br = -O[4][j] + E[4][j] + O[6][j] - E[6][j], s2bi = -O[5][j] + E[5][j] + O[7][j] - E[7][j];
            fwd[j0 + j] += weight * 0.5 * (s1fr * s1fr + s1fi * s1fi + s2fr * s2fr + s2fi * s2fi);
            bwd[j0 + j] += weight * 0.5 * (s1br * s1br + s1bi * s1bi + s2br * s2br + s2bi * s2bi);
        }
    }
}
