/* Size-distribution and spectral averaging of Mie results, angle grids, sphere integrals, chop and table output. */
#include "mietable.h"

#include "colour.h"
#include "mie.h"
#include "water.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

mt_params mt_params_default(void)
{
    mt_params p;
    memset(&p, 0, sizeof p);
    p.reff_um = 6.0;
    p.veff = 0.1;
    p.radius_um = 6.0;
    /* Smooth interference structure is resolved long before dx = 0.035; what is left is sampling noise from
     * Mie resonances far narrower than any affordable step (k ~ 1e-9), which falls only like sqrt(dx).
     * 0.035 keeps the default table near 20 s on two cores; data/mie_cloud.md gives the measured changes. */
    p.dx = 0.035;
    p.lambda_min_nm = 400.0;
    p.lambda_max_nm = 700.0;
    p.dlambda_nm = 10.0;
    p.tail_stretch = 4.0;
    p.threads = 2;
    return p;
}

/* ---- angle sets ---------------------------------------------------------------------------------------------- */

static int angles_alloc(mt_angles *a, int nhalf, int nang)
{
    a->nhalf = nhalf;
    a->nhalf_pad = (nhalf + MIE_JBLOCK - 1) / MIE_JBLOCK * MIE_JBLOCK;
    a->nang = nang;
    a->mu = calloc((size_t)a->nhalf_pad, sizeof *a->mu);
    a->theta_deg = calloc((size_t)nang, sizeof *a->theta_deg);
    a->src = calloc((size_t)nang, sizeof *a->src);
    if (!a->mu || !a->theta_deg || !a->src) {
        mt_angles_free(a);
        return -1;
    }
    return 0;
}

void mt_angles_free(mt_angles *a)
{
    free(a->mu);
    free(a->theta_deg);
    free(a->src);
    memset(a, 0, sizeof *a);
}

int mt_angles_table(mt_angles *a, double fine_deg, double fine_until_deg, double coarse_deg)
{
    /* Steps are given as counts so that every node is an exact multiple and 8 deg (the chop) is a node. */
    int nfine = (int)lround(fine_until_deg / fine_deg);
    int ncoarse = (int)lround((90.0 - fine_until_deg) / coarse_deg);
    if (nfine < 1 || ncoarse < 1 || fabs(nfine * fine_deg - fine_until_deg) > 1e-9 ||
        fabs(fine_until_deg + ncoarse * coarse_deg - 90.0) > 1e-9)
        return -1;
    int nhalf = nfine + ncoarse + 1; /* 0 .. 90 inclusive */
    if (angles_alloc(a, nhalf, 2 * nhalf - 1) != 0)
        return -1;
    for (int h = 0; h < nhalf; h++) {
        double t = h <= nfine ? h * fine_deg : fine_until_deg + (h - nfine) * coarse_deg;
        a->mu[h] = cos(t * PI / 180.0);
        a->theta_deg[h] = t;
        a->src[h] = h << 1;
        if (h < nhalf - 1) {
            int i = 2 * nhalf - 2 - h;
            a->theta_deg[i] = 180.0 - t;
            a->src[i] = (h << 1) | 1;
        }
    }
    a->mu[nhalf - 1] = 0.0; /* cos(90 deg) exactly, so both hemispheres give the same value there */
    for (int h = nhalf; h < a->nhalf_pad; h++)
        a->mu[h] = 1.0;
    return 0;
}

int mt_angles_list(mt_angles *a, const double *theta_deg, int n)
{
    if (n < 1 || angles_alloc(a, n, n) != 0)
        return -1;
    for (int i = 0; i < n; i++) {
        a->mu[i] = cos(theta_deg[i] * PI / 180.0);
        a->theta_deg[i] = theta_deg[i];
        a->src[i] = i << 1;
    }
    for (int h = n; h < a->nhalf_pad; h++)
        a->mu[h] = 1.0;
    return 0;
}

/* ---- one wavelength ------------------------------------------------------------------------------------------ */

/* Per-droplet averages at one wavelength. */
typedef struct {
    double lambda_nm;
    double complex m;
    double *dsdo; /* <d sigma_sca / d Omega>, um^2 sr^-1, at every output direction */
    double sext, ssca, sgsca, geo;
    int nsizes;
    long nsolves;
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

static void spectral_point(const mt_params *p, const mt_angles *a, spectral *s)
{
    mie_work w;
    mie_work_init(&w);
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
            if (wt < 1e-14)
                continue;
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
    s->nsolves = nsolves;
    s->status = 0;
done:
    free(fwd);
    free(bwd);
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
        /* In the bulk every wavelength would sample the same size parameters x_j = j dx, and m changes so little
         * between neighbours (2.5e-4 per 10 nm) that they would hit the same narrow resonances: the noise would
         * not average out over the band. Golden-ratio offsets of the grid decorrelate them; each grid is still
         * uniform in u, so the trapezoid rule keeps its accuracy. A single wavelength gets the midpoint rule. */
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
        /* Channel weight per wavelength: sRGB response x trapezoid weight, for an equal-energy illuminant.
         * Radiance adds over wavelength, so the channel phase function is sum w <dsigma/dOmega> over
         * sum w <sigma_sca>: each wavelength's phase function weighted by its scattering cross-section. */
        double wsum = 0.0, wl = 0.0, wext = 0.0, wsca = 0.0, wg = 0.0, wgeo = 0.0, wm = 0.0;
        for (int i = 0; i < ns; i++) {
            double wt = 1.0;
            if (band) {
                double rgb[3];
                srgb_response(s[i].lambda_nm, rgb);
                wt = rgb[c] * ((i == 0 || i == ns - 1) ? 0.5 : 1.0);
            }
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
        if (s[i].nsizes > r->nsizes)
            r->nsizes = s[i].nsizes;
    }
    free(buf);
    free(s);
    if (rc != 0)
        mt_result_free(r);
    return rc;
}

/* ---- integrals and the chop ---------------------------------------------------------------------------------- */

double mt_sphere_integral(const double *theta_deg, const double *v, int n, int cosw)
{
    double total = 0.0;
    int i = 0;
    while (i < n - 1) {
        /* Longest run of equal steps starting at i. */
        double h = theta_deg[i + 1] - theta_deg[i];
        int j = i + 1;
        while (j < n - 1 && fabs((theta_deg[j + 1] - theta_deg[j]) - h) < 1e-9 * (1.0 + fabs(h)))
            j++;
        int m = j - i; /* intervals in the run */
        double hr = h * PI / 180.0;
        double f[4];
#define F(k)                                                                                                         \
    (v[k] * (cosw ? cos(theta_deg[k] * PI / 180.0) : 1.0) * sin(theta_deg[k] * PI / 180.0) * 2.0 * PI)
        int simp_end = (m % 2 == 0) ? j : j - 3;
        if (m == 1) {
            total += 0.5 * hr * (F(i) + F(j));
        } else {
            for (int k = i; k + 2 <= simp_end; k += 2)
                total += hr / 3.0 * (F(k) + 4.0 * F(k + 1) + F(k + 2));
            if (simp_end != j) { /* Simpson's 3/8 rule on the last three intervals of an odd run */
                for (int q = 0; q < 4; q++)
                    f[q] = F(simp_end + q);
                total += 3.0 * hr / 8.0 * (f[0] + 3.0 * f[1] + 3.0 * f[2] + f[3]);
            }
        }
#undef F
        i = j;
    }
    return total;
}

int mt_chop(const double *theta_deg, const double *p, int n, double chop_deg, double *f, double *ptilde)
{
    int ic = -1;
    for (int i = 0; i < n; i++)
        if (fabs(theta_deg[i] - chop_deg) < 1e-9)
            ic = i;
    if (ic < 0)
        return -1;
    double *pp = malloc((size_t)(ic + 1) * sizeof *pp);
    if (!pp)
        return -1;
    for (int i = 0; i < n; i++) {
        double pt = i < ic ? p[ic] : p[i];
        if (ptilde)
            ptilde[i] = pt;
        if (i <= ic)
            pp[i] = p[i] - pt;
    }
    /* P_p is zero from the chop angle on; integrating only [0, chop] keeps its kink at a run boundary. */
    *f = mt_sphere_integral(theta_deg, pp, ic + 1, 0);
    free(pp);
    return 0;
}

/* ---- output -------------------------------------------------------------------------------------------------- */

int mt_write_table(FILE *out, const mt_result *r, const double *theta_deg, const char *command, const mt_params *p)
{
    if (r->nchan != 3)
        return -1;
    double f[3];
    for (int c = 0; c < 3; c++)
        if (mt_chop(theta_deg, r->p[c], r->nang, 8.0, &f[c], NULL) != 0)
            return -1;
    fprintf(out, "# cumulo mie table v1\n");
    fprintf(out, "# command: %s\n", command);
    if (p->monodisperse)
        fprintf(out, "# droplets: monodisperse r = %g um\n", p->radius_um);
    else
        fprintf(out, "# droplets: gamma distribution r_eff = %g um, v_eff = %g; radius step dx = %g in size "
                     "parameter, x%g past r^4 n(r) < 1e-2 of peak, golden-ratio grid offset per wavelength\n",
                p->reff_um, p->veff, p->dx, p->tail_stretch);
    fprintf(out, "# spectrum: %g-%g nm every %g nm, equal-energy, linear-sRGB weights from the Wyman-Sloan-Shirley "
                 "CIE fit (negative lobes clipped)\n",
            p->lambda_min_nm, p->lambda_max_nm, p->dlambda_nm);
    if (p->use_m)
        fprintf(out, "# refractive index: %.6f - %.3ei (fixed)\n", creal(p->m), -cimag(p->m));
    else
        fprintf(out, "# refractive index: water, Daimon-Masumura 2007 (20 degC) n, Hale-Querry 1973 k\n");
    fprintf(out, "# P(theta) in sr^-1 with integral over the sphere = 1 (composite Simpson on the equal-step runs);"
                 " sigma_ext in um^2 per droplet\n");
    fprintf(out, "# angles: 0.05 deg steps on [0, 10] and [170, 180], 0.25 deg on [10, 170]; g from the Mie "
                 "coefficients; f = integral of P_p = P - P~, P~ = P(8 deg) below 8 deg\n");
    fprintf(out, "# Mie evaluations: %ld\n", r->nsolves);
    /* No run time or date in the file: it must regenerate byte for byte (the time goes to stderr). */
    fprintf(out, "channels 3\n");
    fprintf(out, "lambda_nm %.2f %.2f %.2f\n", r->lambda_nm[0], r->lambda_nm[1], r->lambda_nm[2]);
    fprintf(out, "sigma_ext_um2 %.7e %.7e %.7e\n", r->sigma_ext[0], r->sigma_ext[1], r->sigma_ext[2]);
    fprintf(out, "g %.7e %.7e %.7e\n", r->g[0], r->g[1], r->g[2]);
    fprintf(out, "chop_deg 8\n");
    fprintf(out, "f %.7e %.7e %.7e\n", f[0], f[1], f[2]);
    fprintf(out, "angles %d\n", r->nang);
    for (int i = 0; i < r->nang; i++)
        fprintf(out, "%.2f %.7e %.7e %.7e\n", theta_deg[i], r->p[0][i], r->p[1][i], r->p[2][i]);
    return ferror(out) ? -1 : 0;
}
