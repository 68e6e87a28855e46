/* tools/mie/mietable.c: size-distribution and spectral averaging of Mie results into the RGB phase table (grids in
 * mietable_grid.c, integrals, chop and the table file in mietable_out.c). */
#include "mietable.h"

#include "colour.h"
#include "mie.h"
#include "resonance.h"
#include "water.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

/* ---- one wavelength ------------------------------------------------------------------------------------------ */

/* Per-droplet averages at one wavelength. */
typedef struct {
    double lambda_nm;
    double complex m;
    double *dsdo; /* <d sigma_sca / d Omega>, um^2 sr^-1, at every output direction */
    double sext, ssca, sgsca, geo;
    int nsizes;
    long nsolves, npoles;
    double phase; /* grid offset in units of du, see spectral_point */
    int status;
} spectral;

/* Gamma distribution (Hansen 1971 eq. 2.56): alpha = (1-3v)/v, scale b = reff v. Returns the radius above the
 * peak of r^4 n(r) (the weight of the forward peak) where it has fallen by 10^decades. */
static double gamma_tail(double reff, double veff, double decades)
{
    double alpha = (1.0 - 3.0 * veff) / veff, b = reff * veff;
    double rpk = (alpha + 4.0) * b;
    double lpk = (alpha + 4.0) * log(rpk) - rpk / b;
    double r = rpk;
    while ((alpha + 4.0) * log(r) - r / b > lpk - decades * log(10.0))
        r += 0.01 * b;
    return r;
}

/* Radius nodes r = R(u) on a uniform grid u_j = j du, du = dx lambda / 2pi, so the size-parameter step is dx
 * where the droplets matter (a fixed x step resolves the same interference fringes at every wavelength).
 * Past r_t, where r^4 n(r) is below 1e-2 of its peak, R'(u) rises smoothly to tail_stretch: those radii cost
 * the most (N ~ x terms each) yet weigh least, and the sampling noise from unresolvable resonances scales
 * with the weight. R is smooth (softplus) and the integrand vanishes like r^(alpha+2) at 0 and is below 1e-9
 * of its peak at the top, so the trapezoid rule in u still converges faster than any power of du for the
 * smooth part (Euler-Maclaurin). */
typedef struct {
    double ut, ell, s1;
} rmap;

static double softplus(double z)
{
    return z > 0.0 ? z + log1p(exp(-z)) : log1p(exp(z));
}

static double rmap_r(const rmap *m, double u)
{
    return u + m->s1 * m->ell * softplus((u - m->ut) / m->ell);
}

static double rmap_drdu(const rmap *m, double u)
{
    return 1.0 + m->s1 / (1.0 + exp(-(u - m->ut) / m->ell));
}

/* Real u with x(u) = k R(u) = x, by Newton from u (R is increasing and convex). */
static double rmap_solve(const rmap *m, double k, double x, double u)
{
    for (int it = 0; it < 60; it++) {
        double step = (k * rmap_r(m, u) - x) / (k * rmap_drdu(m, u));
        u -= step;
        if (fabs(step) < 1e-15 * (1.0 + fabs(u)))
            break;
    }
    return u;
}

/* Per-wavelength state of the pole correction (see resonance.h). */
typedef struct {
    double complex *ap, *bp; /* coefficients at the previous node */
    int np;                  /* their count, 0 if there is no previous node */
    double xp;               /* previous node */
    double complex *ca, *cb, *cd; /* coefficients at a resonance, and scratch */
    double *pit, *taut;
    double complex *s1f, *s2f, *s1b, *s2b;
    long npoles, nevals;
} poles;

static double complex softplus_c(double complex v)
{
    return creal(v) > 30.0 ? v + cexp(-v) : clog(1.0 + cexp(v));
}

/* Complex u with k R(u) = z: Newton from the real solution for Re z. */
static double complex rmap_solve_c(const rmap *m, double k, double complex z)
{
    double u0 = rmap_solve(m, k, creal(z), creal(z) / k);
    double complex u = u0 + I * cimag(z) / (k * rmap_drdu(m, u0));
    for (int it = 0; it < 20; it++) {
        double complex v = (u - m->ut) / m->ell;
        double complex r = u + m->s1 * m->ell * softplus_c(v), dr = 1.0 + m->s1 / (1.0 + cexp(-v));
        double complex step = (k * r - z) / (k * dr);
        u -= step;
        if (cabs(step) < 1e-15 * (1.0 + cabs(u)))
            break;
    }
    return u;
}

/* Corrects the sums of spectral_point for the pole of mode n (b_n if isb) at z with residue r. The sums hold
 * sum_j wt_j F(x_j) = T / du, T the trapezoid rule in u for f(u) = n(R(u)) R'(u) F(k R(u)). Its error at the
 * pole u_z (k R(u_z) = z) is Res(f, u_z) E(w) plus the conjugate from conj(z), with
 * Res(f, u_z) = n(z/k) Res(F, z) / k (R' cancels). F = |S|^2 = S(x) conj(S(conj x)) has
 * Res(F, z) = rho conj(S(conj z)), rho the residue of S; everything is evaluated at the complex points, so
 * nothing but the trapezoid error of the remaining analytic part (exponentially small) is neglected. */
static int pole_correct(const mt_angles *a, const spectral *s, const rmap *map, double k, double du, double alpha,
                        double b, double rpk, poles *P, int n, int isb, double complex z, double complex r,
                        double *fwd, double *bwd, double *sext, double *ssca, double *sg)
{
    double complex uz = rmap_solve_c(map, k, z);
    double complex e = res_trap_error(uz / du - s->phase);
    double complex rz = z / k;
    double complex nrel = cexp(alpha * clog(rz / rpk) - (rz - rpk) / b);
    /* Every sum gets -(1/du) 2 Re[Res_u E] = Re[cfac Res(F, z)]. */
    double complex cfac = -2.0 * nrel * e / (k * du);
    double complex zc = conj(z);
    int nt = mie_nterms(creal(z));
    if (nt < n + 1)
        nt = n + 1;
    if (res_coefs(conj(s->m), zc, nt, P->cd, P->ca, P->cb) != 0)
        return -1;
    P->nevals++;
    const double complex *A = isb ? P->cb : P->ca, *B = isb ? P->ca : P->cb;
    double fn = n;
    double k2 = k * k;
    /* sigma_ext = 2pi/k^2 sum (2n+1) Re(a + b); sigma_sca = 2pi/k^2 sum (2n+1)(|a|^2 + |b|^2);
     * g sigma_sca = 4pi/k^2 [sum n(n+2)/(n+1) Re(a_n a_n+1* + b_n b_n+1*) + (2n+1)/(n(n+1)) Re(a_n b_n*)].
     * Re(c Y*) = (c Y# + c# Y)/2 has the residue r Y#(z)/2 = r conj(Y(conj z))/2 at z. */
    *sext += creal(cfac * (2.0 * PI / k2 * (2.0 * fn + 1.0) * 0.5 * r));
    *ssca += creal(cfac * (2.0 * PI / k2 * (2.0 * fn + 1.0) * r * conj(A[n - 1])));
    double complex y = (2.0 * fn + 1.0) / (fn * (fn + 1.0)) * B[n - 1] + fn * (fn + 2.0) / (fn + 1.0) * A[n];
    if (n >= 2)
        y += (fn - 1.0) * (fn + 1.0) / fn * A[n - 2];
    *sg += creal(cfac * (4.0 * PI / k2 * 0.5 * r * conj(y)));
    res_amplitudes(P->ca, P->cb, nt, a->mu, a->nhalf, n, P->pit, P->taut, P->s1f, P->s2f, P->s1b, P->s2b);
    double cn = (2.0 * fn + 1.0) / (fn * (fn + 1.0));
    double sp = (n & 1) ? 1.0 : -1.0; /* pi_n(-mu) = sp pi_n(mu), tau_n(-mu) = -sp tau_n(mu) */
    double complex c0 = cfac * 0.5 / k2 * cn * r;
    for (int h = 0; h < a->nhalf; h++) {
        for (int hemi = 0; hemi < 2; hemi++) {
            double pi_ = hemi ? sp * P->pit[h] : P->pit[h], tau_ = hemi ? -sp * P->taut[h] : P->taut[h];
            double complex S1 = hemi ? P->s1b[h] : P->s1f[h], S2 = hemi ? P->s2b[h] : P->s2f[h];
            /* F = (|S1|^2 + |S2|^2)/2 / k^2; the pole's residue in S1 is cn r pi (a_n) or cn r tau (b_n). */
            double complex t = isb ? tau_ * conj(S1) + pi_ * conj(S2) : pi_ * conj(S1) + tau_ * conj(S2);
            (hemi ? bwd : fwd)[h] += creal(c0 * t);
        }
    }
    P->npoles++;
    return 0;
}

/* Finds the poles of every mode in the cell from the previous node to x (coefficients in w) and corrects. */
static int cell_poles(const mt_angles *a, const spectral *s, const rmap *map, double k,
                      double du, double alpha, double b, double rpk, poles *P, const mie_work *w, int nterms,
                      double x, double *fwd, double *bwd, double *sext, double *ssca, double *sg)
{
    int nmax = nterms < P->np ? nterms : P->np;
    double hx = x - P->xp;
    double complex mb = conj(s->m);
    /* Narrow resonances are those of the edge modes, n > x - c x^(1/3) (c from tools/mie/README.md); 3.5
     * leaves a margin and keeps the broad low modes, whose 1/a_n is not linear across a cell, out of the pole
     * search. */
    int nlo = (int)(P->xp - 3.5 * cbrt(P->xp));
    if (nlo < 1)
        nlo = 1;
    for (int n = nlo; n <= nmax; n++) {
        for (int isb = 0; isb < 2; isb++) {
            double complex cp = isb ? P->bp[n - 1] : P->ap[n - 1], cc = isb ? w->b[n - 1] : w->a[n - 1];
            if (cp == 0.0 || cc == 0.0)
                continue;
            /* 1/a_n is nearly linear across a cell near a narrow resonance: its zero predicts the pole. */
            double complex hp = 1.0 / cp, hc = 1.0 / cc;
            if (hp == hc)
                continue;
            double complex t = hp / (hp - hc);
            if (!(creal(t) > -0.5 && creal(t) < 1.5 && fabs(cimag(t)) < 4.0))
                continue;
            /* h ~ (x - z)/r predicts the residue too. A pole adds ~pi |r| (in units of the cell's own
             * contribution hx); below 1e-7 hx it is not worth the search (what skipping them costs:
             * tools/mie/README.md). */
            if (cabs(hx / (hc - hp)) < 1e-7 * hx)
                continue;
            double complex z, r;
            if (res_find_pole(mb, n, isb, P->xp + t * hx, 4.0 * hx, &z, &r) != 0)
                continue;
            if (!(creal(z) >= P->xp && creal(z) < x && fabs(cimag(z)) < 3.0 * hx))
                continue;
            /* Resonances far narrower than absorption allows carry no weight (r ~ radiative width). */
            if (cabs(r) < 1e-12 * hx)
                continue;
            if (pole_correct(a, s, map, k, du, alpha, b, rpk, P, n, isb, z, r, fwd, bwd, sext, ssca, sg) != 0)
                return -1;
        }
    }
    return 0;
}

static void spectral_point(const mt_params *p, const mt_angles *a, spectral *s)
{
    mie_work w;
    mie_work_init(&w);
    poles P;
    memset(&P, 0, sizeof P);
    double *fwd = calloc((size_t)a->nhalf_pad, sizeof *fwd);
    double *bwd = calloc((size_t)a->nhalf_pad, sizeof *bwd);
    s->status = -1;
    if (!fwd || !bwd)
        goto done;
    double lum = s->lambda_nm * 1e-3;
    double k = 2.0 * PI / lum;
    int nr = 1;
    double du = 0.0, rmax = 0.0, alpha = 0.0, b = 1.0, rpk = 1.0;
    rmap map = {0.0, 1.0, 0.0};
    if (!p->monodisperse) {
        alpha = (1.0 - 3.0 * p->veff) / p->veff;
        b = p->reff_um * p->veff;
        rpk = alpha * b;
        du = p->dx / k;
        rmax = gamma_tail(p->reff_um, p->veff, 9.0);
        map.ut = gamma_tail(p->reff_um, p->veff, 2.0);
        map.ell = 0.1 * p->reff_um;
        map.s1 = p->tail_stretch - 1.0;
        nr = 0;
        while (rmap_r(&map, (nr + s->phase) * du) <= rmax)
            nr++;
    }
    int use_poles = p->poles && !p->monodisperse;
    if (use_poles) {
        int cap = mie_nterms(k * rmax) + 2;
        P.ap = malloc((size_t)cap * sizeof *P.ap);
        P.bp = malloc((size_t)cap * sizeof *P.bp);
        P.pit = malloc((size_t)a->nhalf_pad * sizeof *P.pit);
        P.taut = malloc((size_t)a->nhalf_pad * sizeof *P.taut);
        P.s1f = malloc((size_t)a->nhalf_pad * 4 * sizeof *P.s1f);
        P.ca = malloc((size_t)cap * sizeof *P.ca);
        P.cb = malloc((size_t)cap * sizeof *P.cb);
        P.cd = malloc((size_t)(cap + 2) * sizeof *P.cd);
        if (!P.ap || !P.bp || !P.pit || !P.taut || !P.s1f || !P.ca || !P.cb || !P.cd)
            goto done;
        P.s2f = P.s1f + a->nhalf_pad;
        P.s1b = P.s2f + a->nhalf_pad;
        P.s2b = P.s1b + a->nhalf_pad;
    }
    double wsum = 0.0, sext = 0.0, ssca = 0.0, sg = 0.0, geo = 0.0;
    long nsolves = 0;
    for (int j = 1; j <= nr; j++) {
        double r, wt;
        if (p->monodisperse) {
            r = p->radius_um;
            wt = 1.0;
        } else {
            double u = (j - 1 + s->phase) * du;
            r = rmap_r(&map, u);
            /* n(r)/n(rpk) dr/du: relative weights keep exp() in range for any r_eff, v_eff. */
            wt = exp(alpha * log(r / rpk) - (r - rpk) / b) * rmap_drdu(&map, u);
            if (wt < 1e-14) {
                P.np = 0;
                continue;
            }
        }
        mie_q q;
        if (mie_solve(s->m, k * r, &w, &q) != 0)
            goto done;
        nsolves++;
        mie_s11_pairs(&w, q.nterms, a->mu, a->nhalf_pad, wt / (k * k), fwd, bwd);
        double area = PI * r * r;
        wsum += wt;
        sext += wt * q.qext * area;
        ssca += wt * q.qsca * area;
        sg += wt * q.g * q.qsca * area;
        geo += wt * area;
        if (use_poles) {
            if (P.np > 0 && cell_poles(a, s, &map, k, du, alpha, b, rpk, &P, &w, q.nterms, k * r, fwd, bwd,
                                       &sext, &ssca, &sg) != 0)
                goto done;
            memcpy(P.ap, w.a, (size_t)q.nterms * sizeof *P.ap);
            memcpy(P.bp, w.b, (size_t)q.nterms * sizeof *P.bp);
            P.np = q.nterms;
            P.xp = k * r;
        }
    }
    if (!(wsum > 0.0)) /* a distribution narrower than the radius step: nothing sampled */
        goto done;
    for (int i = 0; i < a->nang; i++) {
        int h = a->src[i] >> 1;
        s->dsdo[i] = ((a->src[i] & 1) ? bwd[h] : fwd[h]) / wsum;
    }
    s->sext = sext / wsum;
    s->ssca = ssca / wsum;
    s->sgsca = sg / wsum;
    s->geo = geo / wsum;
    s->nsizes = nr;
    s->nsolves = nsolves + P.nevals;
    s->npoles = P.npoles;
    s->status = 0;
done:
    free(fwd);
    free(bwd);
    free(P.ap);
    free(P.bp);
    free(P.pit);
    free(P.taut);
    free(P.s1f);
    free(P.ca);
    free(P.cb);
    free(P.cd);
    mie_work_free(&w);
}

typedef struct {
    const mt_params *p;
    const mt_angles *a;
    spectral *s;
    int ns, first, stride;
} worker;

static void *worker_run(void *arg)
{
    worker *wk = arg;
    for (int i = wk->first; i < wk->ns; i += wk->stride)
        spectral_point(wk->p, wk->a, &wk->s[i]);
    return NULL;
}

/* ---- channels ------------------------------------------------------------------------------------------------ */

static void set_err(char *err, size_t len, const char *msg)
{
    if (err && len) {
        strncpy(err, msg, len - 1);
        err[len - 1] = '\0';
    }
}

void mt_result_free(mt_result *r)
{
    for (int c = 0; c < 3; c++)
        free(r->p[c]);
    memset(r, 0, sizeof *r);
}


int mt_compute(const mt_params *p, const mt_angles *a, mt_result *r, char *err, size_t errlen)
{
    memset(r, 0, sizeof *r);
    int band = p->lambda_max_nm > p->lambda_min_nm;
    int ns = band ? (int)lround((p->lambda_max_nm - p->lambda_min_nm) / p->dlambda_nm) + 1 : 1;
    if (band && fabs(p->lambda_min_nm + (ns - 1) * p->dlambda_nm - p->lambda_max_nm) > 1e-9) {
        set_err(err, errlen, "band width is not a multiple of the wavelength step");
        return -1;
    }
    spectral *s = calloc((size_t)ns, sizeof *s);
    double *buf = calloc((size_t)ns * (size_t)a->nang, sizeof *buf);
    if (!s || !buf) {
        free(s);
        free(buf);
        set_err(err, errlen, "out of memory");
        return -1;
    }
    for (int i = 0; i < ns; i++) {
        s[i].lambda_nm = p->lambda_min_nm + i * p->dlambda_nm;
        /* Golden-ratio offsets of each wavelength's grid: without the pole correction (--poles 0) every wavelength
         * would sample the same size parameters x_j = j dx and, m changing little between neighbours, hit the
         * same narrow resonances, so their noise would not average out over the band. With the correction they
         * do not matter; each grid is still uniform in u. A single wavelength gets the midpoint rule. */
        s[i].phase = fmod(0.5 + i * 0.6180339887498949, 1.0);
        s[i].m = p->use_m ? p->m : water_m(s[i].lambda_nm);
        s[i].dsdo = buf + (size_t)i * (size_t)a->nang;
    }
    int nt = p->threads < 1 ? 1 : p->threads > ns ? ns : p->threads;
    enum { MAXT = 8 };
    if (nt > MAXT)
        nt = MAXT;
    worker wk[MAXT];
    pthread_t th[MAXT];
    int started[MAXT] = {0};
    for (int t = 0; t < nt; t++)
        wk[t] = (worker){p, a, s, ns, t, nt};
    for (int t = 1; t < nt; t++)
        started[t] = pthread_create(&th[t], NULL, worker_run, &wk[t]) == 0;
    /* Any share a thread could not take is done here, so the result never depends on thread creation. */
    for (int t = 0; t < nt; t++)
        if (t == 0 || !started[t])
            worker_run(&wk[t]);
    for (int t = 1; t < nt; t++)
        if (started[t])
            pthread_join(th[t], NULL);

    int rc = 0;
    double *bw[3] = {NULL, NULL, NULL};
    if (band) {
        for (int c = 0; c < 3; c++)
            bw[c] = calloc((size_t)ns, sizeof *bw[c]);
        if (!bw[0] || !bw[1] || !bw[2]) {
            set_err(err, errlen, "out of memory");
            rc = -1;
        } else
            mt_band_weights(p->lambda_min_nm, p->dlambda_nm, ns, bw);
    }
    for (int i = 0; i < ns; i++)
        if (s[i].status != 0) {
            set_err(err, errlen, "Mie evaluation failed (size parameter or refractive index out of range)");
            rc = -1;
        }
    r->nchan = band ? 3 : 1;
    r->nang = a->nang;
    for (int c = 0; c < r->nchan && rc == 0; c++) {
        r->p[c] = calloc((size_t)a->nang, sizeof *r->p[c]);
        if (!r->p[c]) {
            set_err(err, errlen, "out of memory");
            rc = -1;
            break;
        }
        /* Channel weight per wavelength (mt_band_weights), for an equal-energy illuminant. Radiance adds over
         * wavelength, so the channel phase function is int w <dsigma/dOmega> over int w <sigma_sca>: each
         * wavelength's phase function weighted by its scattering cross-section. */
        double wsum = 0.0, wl = 0.0, wext = 0.0, wsca = 0.0, wg = 0.0, wgeo = 0.0, wm = 0.0;
        for (int i = 0; i < ns; i++) {
            double wt = band ? bw[c][i] : 1.0;
            wsum += wt;
            wl += wt * s[i].lambda_nm;
            wm += wt * creal(s[i].m);
            wext += wt * s[i].sext;
            wsca += wt * s[i].ssca;
            wg += wt * s[i].sgsca;
            wgeo += wt * s[i].geo;
            for (int j = 0; j < a->nang; j++)
                r->p[c][j] += wt * s[i].dsdo[j];
        }
        for (int j = 0; j < a->nang; j++)
            r->p[c][j] /= wsca;
        r->lambda_nm[c] = wl / wsum;
        r->m_re[c] = wm / wsum;
        r->sigma_ext[c] = wext / wsum;
        r->sigma_sca[c] = wsca / wsum;
        r->geo[c] = wgeo / wsum;
        r->g[c] = wg / wsca;
    }
    for (int i = 0; i < ns; i++) {
        r->nsolves += s[i].nsolves;
        r->npoles += s[i].npoles;
        if (s[i].nsizes > r->nsizes)
            r->nsizes = s[i].nsizes;
    }
    free(buf);
    free(s);
    for (int c = 0; c < 3; c++)
        free(bw[c]);
    if (rc != 0)
        mt_result_free(r);
    return rc;
}
