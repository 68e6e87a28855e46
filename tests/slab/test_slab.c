/* cmocka tests for the slab Monte Carlo: adding-doubling R/T, closed-form single scattering, reciprocity, samplers, determinism. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>
#include <gsl/gsl_cdf.h>
#include "slab.h"
#include "rng.h"
#include "fitlib.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static cu_slab_cfg base_cfg(const cu_phase *ph, double tau, double mu0, long long photons)
{
    cu_slab_cfg c;
    memset(&c, 0, sizeof c);
    c.tau = tau; c.mu0 = mu0; c.ph = ph; c.photons = photons;
    c.nbatch = 64; c.threads = 2; c.seed = 12345; c.quiet = 1; c.phi_deg = -1; c.nranks = 1;
    return c;
}

static void stat(const cu_acc *a, long long n, double *m, double *se) { cu_acc_stats(a, n, m, se); }

/* R vs Prahl's adding-doubling (VALIDATION.md) within 3 SE and 0.5 %; photon counts give SE <= ~0.15 % of R */
static void check_rt_t(const cu_phase *ph, double tau, double Rref, long long photons, int t_rel)
{
    cu_slab_cfg c = base_cfg(ph, tau, 1.0, photons);
    cu_slab_result r;
    assert_int_equal(cu_slab_run(&c, &r), 0);
    double R, sR, T, sT, RT, sRT;
    stat(&r.R, r.photons, &R, &sR);
    stat(&r.T, r.photons, &T, &sT);
    T += r.t_unscat;
    stat(&r.RTe, r.photons, &RT, &sRT);
    RT += r.t_unscat;
    double rel = fabs(R - Rref) / Rref;
    printf("  g=%.2f tau=%-5g R=%.5f +- %.5f ref %.5f (%.2f SE, %.3f%%)  T=%.5f  escape-estimator R+T=%.5f +- %.5f  "
           "[%lld photons, %.2fs]\n", ph->kind == CU_PH_HG ? ph->g : 0.0, tau, R, sR, Rref, fabs(R - Rref) / sR,
           100 * rel, T, RT, sRT, r.photons, r.seconds);
    assert_true(fabs(R - Rref) < 3 * sR);
    assert_true(rel < 0.005);
    assert_true(fabs(T - (1 - Rref)) < 3 * sT);
    /* T relative to 0.5 % as well where T > 0.3; for thick slabs (T = 0.10-0.19) a 0.5 % relative check needs
     * 10-50x more photons: that is the stress test (test_rt_thin_T, CUMULO_STRESS=1, make stress) */
    printf("    T relative deviation %.3f%% (T SE %.3f%% of T)\n", 100 * fabs(T - (1 - Rref)) / (1 - Rref),
           100 * sT / (1 - Rref));
    if (t_rel || 1 - Rref > 0.3) assert_true(fabs(T - (1 - Rref)) / (1 - Rref) < 0.005);
    assert_true(fabs(RT - 1.0) < 3 * sRT);   /* independent estimator: R + T = 1 to MC precision */
    cu_slab_result_free(&r);
}

static void check_rt(const cu_phase *ph, double tau, double Rref, long long photons)
{
    check_rt_t(ph, tau, Rref, photons, 0);
}

/* Stress test (CUMULO_STRESS=1): T = 1 - R_ref within 3 SE and 0.5 % relative also where T is small (g = 0.85,
 * tau = 50 and 100; g = 0, tau = 10). The exit count is kept as the estimator: its per-photon variance T(1 - T) is
 * the smallest of the unbiased estimators this code has for thick slabs (the escape-probability sum is ~2.5x worse in
 * SE at tau = 100), so the photon counts are chosen for SE(T) <= ~0.12 % of T, i.e. the 0.5 % criterion is > 4 SE. */
static void test_rt_thin_T(void **st)
{
    (void)st;
    cu_phase hg = { .kind = CU_PH_HG, .g = 0.85 }, iso = { .kind = CU_PH_ISO };
    check_rt_t(&hg, 50.0, 0.81012, 4000000, 1);
    check_rt_t(&hg, 100.0, 0.89681, 6000000, 1);
    check_rt_t(&iso, 10.0, 0.85300, 4000000, 1);
}

static void test_rt_hg085(void **st)
{
    (void)st;
    cu_phase ph = { .kind = CU_PH_HG, .g = 0.85 };
    static const double tau[] = { 0.5, 1, 2, 5, 10, 20, 50, 100 };
    static const double R[] = { 0.01993, 0.04232, 0.09102, 0.23787, 0.42228, 0.61717, 0.81012, 0.89681 };
    static const long long N[] = { 12000000, 7000000, 4000000, 1500000, 600000, 500000, 200000, 100000 };
    for (int i = 0; i < 8; i++) check_rt(&ph, tau[i], R[i], N[i]);
}

static void test_rt_iso(void **st)
{
    (void)st;
    cu_phase ph = { .kind = CU_PH_ISO };
    check_rt(&ph, 1.0, 0.34133, 1000000);
    check_rt(&ph, 10.0, 0.85300, 100000);
}

/* single scattering (group 1, escape-probability estimator, walks stopped after the first scattering) */
static void check_single(const cu_phase *ph, double tau, double R1, double T1)
{
    cu_slab_cfg c = base_cfg(ph, tau, 1.0, 2000000);
    c.max_order = 1;
    cu_slab_result r;
    assert_int_equal(cu_slab_run(&c, &r), 0);
    double m, se;
    stat(&r.Ren[0], r.photons, &m, &se);
    printf("  R1 tau=%g: %.6f +- %.6f ref %.5f (%.2f SE)\n", tau, m, se, R1, fabs(m - R1) / se);
    assert_true(fabs(m - R1) < 3 * se + 5e-6);   /* + half a unit of the reference's last digit */
    if (T1 >= 0) {
        stat(&r.Ten[0], r.photons, &m, &se);
        printf("  T1 tau=%g: %.6f +- %.6f ref %.5f (%.2f SE)\n", tau, m, se, T1, fabs(m - T1) / se);
        assert_true(fabs(m - T1) < 3 * se + 5e-6);
    }
    cu_slab_result_free(&r);
}

static void test_single_scattering(void **st)
{
    (void)st;
    cu_phase hg = { .kind = CU_PH_HG, .g = 0.85 }, iso = { .kind = CU_PH_ISO };
    check_single(&hg, 1.0, 0.00895, 0.32926);
    check_single(&iso, 1.0, 0.14202, 0.10617);
    check_single(&iso, 60.0, 0.153426, -1);   /* semi-infinite: (1 - ln 2)/2; e^-60 is negligible */
}

/* reflected radiance (pi I / (mu0 F)) is symmetric in (mu, mu0): azimuth-averaged and at a fixed azimuth */
static void test_reciprocity(void **st)
{
    (void)st;
    cu_phase ph = { .kind = CU_PH_HG, .g = 0.85 };
    for (int k = 0; k < 2; k++) {
        double v[2], s[2];
        for (int i = 0; i < 2; i++) {
            cu_slab_cfg c = base_cfg(&ph, 4.0, i == 0 ? 0.5 : 0.8, 150000);
            c.nmu = 1; c.mu[0] = i == 0 ? 0.8 : 0.5; c.phi_deg = k == 0 ? -1 : 60.0;
            c.seed = 77 + i;
            cu_slab_result r;
            assert_int_equal(cu_slab_run(&c, &r), 0);
            stat(&r.rad_r[0], r.photons, &v[i], &s[i]);
            cu_slab_result_free(&r);
        }
        double z = fabs(v[0] - v[1]) / sqrt(s[0] * s[0] + s[1] * s[1]);
        printf("  reciprocity %s: rho(0.8,0.5)=%.5f +- %.5f rho(0.5,0.8)=%.5f +- %.5f (%.2f sigma)\n",
               k == 0 ? "azimuth mean" : "phi=60", v[0], s[0], v[1], s[1], z);
        assert_true(z < 3.0);
    }
}

/* the radiance estimator's normalisation: R = 2 int_0^1 rho(mu) mu dmu (Gauss-Legendre, 8 nodes on [0,1]) */
static void test_radiance_flux(void **st)
{
    (void)st;
    static const double x[] = { 0.0198550717512319, 0.1016667612931866, 0.2372337950418355, 0.4082826787521751,
                                0.5917173212478249, 0.7627662049581645, 0.8983332387068134, 0.9801449282487681 };
    static const double w[] = { 0.0506142681451881, 0.1111905172266872, 0.1568533229389436, 0.1813418916891810,
                                0.1813418916891810, 0.1568533229389436, 0.1111905172266872, 0.0506142681451881 };
    cu_phase ph = { .kind = CU_PH_ISO };
    cu_slab_cfg c = base_cfg(&ph, 2.0, 1.0, 200000);
    c.nmu = 8;
    for (int j = 0; j < 8; j++) c.mu[j] = x[j];
    cu_slab_result r;
    assert_int_equal(cu_slab_run(&c, &r), 0);
    double q = 0, qv = 0, R, sR;
    for (int j = 0; j < 8; j++) {
        double m, se;
        stat(&r.rad_r[j], r.photons, &m, &se);
        q += 2 * w[j] * x[j] * m; qv += pow(2 * w[j] * x[j] * se, 2);  /* upper-bound-ish: ignores correlation */
    }
    stat(&r.R, r.photons, &R, &sR);
    printf("  flux from radiance %.5f +- %.5f vs R %.5f +- %.5f\n", q, sqrt(qv), R, sR);
    assert_true(fabs(q - R) < 3 * sqrt(qv + sR * sR) + 0.002);
    cu_slab_result_free(&r);
}

/* histogram of sampled cos(theta) vs the density integrated per bin (chi-square), and the mean cosine */
static void check_sampler(const cu_phase *ph, double gref, double gtol)
{
    enum { NB = 60, NS = 400000 };
    double hist[NB] = { 0 }, sum = 0, sum2 = 0;
    cu_rng r;
    cu_rng_seed(&r, 99);
    for (int i = 0; i < NS; i++) {
        double c = cu_phase_sample(ph, cu_rng_u01(&r));
        assert_true(c >= -1 && c <= 1);
        int b = (int)((c + 1) / 2 * NB);
        if (b == NB) b = NB - 1;
        hist[b]++; sum += c; sum2 += c * c;
    }
    double chi = 0;
    int df = 0;
    for (int b = 0; b < NB; b++) {
        /* expected count: 2 pi int p dmu over the bin (Simpson, 64 panels) */
        double a = -1 + 2.0 * b / NB, h = 2.0 / NB / 64, e = 0;
        for (int k = 0; k <= 64; k++) e += (k == 0 || k == 64 ? 1 : (k % 2 ? 4 : 2)) * cu_phase_eval(ph, a + k * h);
        e *= 2 * M_PI * h / 3 * NS;
        if (e < 5) continue;
        chi += (hist[b] - e) * (hist[b] - e) / e;
        df++;
    }
    double pval = gsl_cdf_chisq_Q(chi, df - 1);
    double mean = sum / NS, se = sqrt((sum2 / NS - mean * mean) / NS);
    printf("  sampler kind=%d: chi2=%.1f df=%d p=%.3f  <cos>=%.5f +- %.5f (ref %.5f)\n", ph->kind, chi, df - 1, pval, mean,
           se, gref);
    assert_true(pval > 1e-3);
    assert_true(fabs(mean - gref) < 4 * se + gtol);
}

static void make_hg_table(double g, int n, double *th, double *P)
{
    for (int i = 0; i < n; i++) {
        th[i] = 180.0 * i / (n - 1);
        cu_phase hg = { .kind = CU_PH_HG, .g = g };
        P[i] = cu_phase_eval(&hg, cos(th[i] * M_PI / 180));
    }
}

static void test_samplers(void **st)
{
    (void)st;
    cu_phase hg = { .kind = CU_PH_HG, .g = 0.85 }, hgb = { .kind = CU_PH_HG, .g = -0.3 }, iso = { .kind = CU_PH_ISO };
    check_sampler(&hg, 0.85, 0);
    check_sampler(&hgb, -0.3, 0);
    check_sampler(&iso, 0, 0);
    enum { N = 721 };
    double th[N], P[N];
    char msg[256];
    make_hg_table(0.85, N, th, P);
    cu_phase tab;
    assert_int_equal(cu_phase_from_table(&tab, N, th, P, 0, 0, msg, sizeof msg), 0);
    printf("  table from HG 0.85 (0.25 deg): f=%.2e g=%.5f\n", tab.f, tab.g);
    assert_true(fabs(tab.f) < 2e-3 && fabs(tab.g - 0.85) < 2e-3);
    check_sampler(&tab, tab.g, 0);
    cu_phase_free(&tab);
}

/* chopped table (eq. 3.64) read from the Mie text format: f = int (P - P(chop)) over the peak */
static void test_mie_table_and_chop(void **st)
{
    (void)st;
    enum { N = 721 };
    double th[N], P[N];
    make_hg_table(0.85, N, th, P);
    char path[] = "/tmp/cumulo_slab_test_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    FILE *fp = fdopen(fd, "w");
    fprintf(fp, "# HG 0.85 stand-in for a Mie table\nchannels 3\nlambda_nm 680 550 440\nsigma_ext_um2 1 1 1\n"
                "g 0.85 0.85 0.85\nchop_deg 8\nf 0.3 0.3 0.3\nangles %d\n", N);
    for (int i = 0; i < N; i++) fprintf(fp, "%.6f %.9e %.9e %.9e\n", th[i], P[i], P[i], P[i]);
    fclose(fp);
    cu_phase ph;
    char msg[256];
    int rc = cu_phase_read_mie(&ph, path, 1, msg, sizeof msg);
    unlink(path);
    assert_int_equal(rc, 0);
    /* reference f by direct quadrature of the analytic HG over the 8-degree cap */
    cu_phase hg = { .kind = CU_PH_HG, .g = 0.85 };
    double c8 = cos(8 * M_PI / 180), p8 = cu_phase_eval(&hg, c8), f = 0;
    int K = 20000;
    for (int k = 0; k < K; k++) {
        double mu = c8 + (1 - c8) * (k + 0.5) / K;
        f += 2 * M_PI * (cu_phase_eval(&hg, mu) - p8) * (1 - c8) / K;
    }
    printf("  chopped HG at 8 deg: f=%.5f (quadrature %.5f), sampling g=%.5f\n", ph.f, f, ph.g);
    assert_true(fabs(ph.f - f) < 2e-3);
    check_sampler(&ph, ph.g, 0);
    /* the renormalised chopped density must equal P/(1-f) beyond the chop angle */
    double c30 = cos(30 * M_PI / 180);
    assert_true(fabs(cu_phase_eval(&ph, c30) * (1 - ph.f) / cu_phase_eval(&hg, c30) - 1) < 2e-3);
    cu_phase_free(&ph);
}

/* the tabulated sampler in transport: R from an HG-generated table vs analytic HG */
static void test_table_transport(void **st)
{
    (void)st;
    enum { N = 721 };
    double th[N], P[N];
    char msg[256];
    make_hg_table(0.85, N, th, P);
    cu_phase tab, hg = { .kind = CU_PH_HG, .g = 0.85 };
    assert_int_equal(cu_phase_from_table(&tab, N, th, P, 0, 0, msg, sizeof msg), 0);
    double v[2], s[2];
    for (int i = 0; i < 2; i++) {
        cu_slab_cfg c = base_cfg(i ? &tab : &hg, 5.0, 0.6, 300000);
        c.seed = 5 + i;
        cu_slab_result r;
        assert_int_equal(cu_slab_run(&c, &r), 0);
        stat(&r.R, r.photons, &v[i], &s[i]);
        cu_slab_result_free(&r);
    }
    double z = fabs(v[0] - v[1]) / sqrt(s[0] * s[0] + s[1] * s[1]);
    printf("  tau=5 mu0=0.6: R(HG)=%.5f +- %.5f R(table)=%.5f +- %.5f (%.2f sigma)\n", v[0], s[0], v[1], s[1], z);
    assert_true(z < 3.0);
    cu_phase_free(&tab);
}

static void run_small(int threads, uint64_t seed, cu_slab_result *r, cu_phase *ph)
{
    cu_slab_cfg c = base_cfg(ph, 3.0, 0.7, 100000);
    c.threads = threads; c.seed = seed;
    c.nmu = 2; c.mu[0] = 1; c.mu[1] = 0.3;
    c.table = 1; c.nd = 3; c.d_tau[0] = 0; c.d_tau[1] = 1.5; c.d_tau[2] = 3;
    c.nv = 2; c.thv_deg[0] = 30; c.thv_deg[1] = 150; c.nphi = 2; c.phv_deg[0] = 0; c.phv_deg[1] = 180;
    assert_int_equal(cu_slab_run(&c, r), 0);
}

/* batches have fixed photon ranges and RNG streams, reduced in batch order: results are bit-identical for any
 * thread count (stronger than "statistically equal"); another seed differs but agrees within errors */
static void test_determinism(void **st)
{
    (void)st;
    cu_phase ph = { .kind = CU_PH_HG, .g = 0.85 };
    cu_slab_result a, b, c, d;
    run_small(2, 42, &a, &ph);
    run_small(2, 42, &b, &ph);
    run_small(1, 42, &c, &ph);
    run_small(2, 43, &d, &ph);
    assert_memory_equal(&a.R, &b.R, sizeof a.R);
    assert_memory_equal(a.rad_r, b.rad_r, sizeof a.rad_r);
    assert_memory_equal(a.tab, b.tab, sizeof(double) * 4 * 64 * a.ncell);
    assert_memory_equal(&a.R, &c.R, sizeof a.R);
    assert_memory_equal(&a.Re, &c.Re, sizeof a.Re);
    assert_memory_equal(a.rad_r, c.rad_r, sizeof a.rad_r);
    assert_memory_equal(a.tab, c.tab, sizeof(double) * 4 * 64 * a.ncell);
    double m1, s1, m2, s2;
    stat(&a.R, a.photons, &m1, &s1);
    stat(&d.R, d.photons, &m2, &s2);
    printf("  seed 42: R=%.5f +- %.5f, seed 43: R=%.5f +- %.5f\n", m1, s1, m2, s2);
    assert_true(m1 != m2);
    assert_true(fabs(m1 - m2) < 4 * sqrt(s1 * s1 + s2 * s2));
    cu_slab_result_free(&a); cu_slab_result_free(&b); cu_slab_result_free(&c); cu_slab_result_free(&d);
}

/* interior table: single-scattering C at the top towards zenith equals p(pi) mu0/(mu+mu0) (1 - e^{-tau(1/mu+1/mu0)})
 * (here mu = mu0 = 1), and with the sun at zenith the collector mean is mirror-symmetric in phi_V:
 * c_z(phi_V = 0) = -c_z(180), c_x(0) = 0, sigma(0) = sigma(180) */
static void test_table_single_and_collector(void **st)
{
    (void)st;
    cu_phase ph = { .kind = CU_PH_HG, .g = 0.85 };
    cu_slab_cfg c = base_cfg(&ph, 2.0, 1.0, 200000);
    c.metres_per_tau = 1 / 0.0905;
    c.table = 1; c.nd = 2; c.d_tau[0] = 0; c.d_tau[1] = 1.0;
    c.nv = 2; c.thv_deg[0] = 180; c.thv_deg[1] = 40; c.nphi = 2; c.phv_deg[0] = 0; c.phv_deg[1] = 180;
    cu_slab_result r;
    assert_int_equal(cu_slab_run(&c, &r), 0);
    cu_cell_stats a, b, z;
    cu_slab_cell_stats(&c, &r, cu_slab_cell(&c, 0, 0, 0, 0), &z);
    double ref = cu_phase_eval(&ph, -1.0) / 2.0 * (1 - exp(-4.0));
    printf("  C1(d=0, thetaV=180, thetaL=0) = %.6e +- %.1e, closed form %.6e (%.2f SE)\n", z.C, z.C_se, ref,
           fabs(z.C - ref) / z.C_se);
    assert_true(fabs(z.C - ref) < 3 * z.C_se);
    for (int g = 0; g < 8; g += 7) {
        cu_slab_cell_stats(&c, &r, cu_slab_cell(&c, g, 1, 1, 0), &a);
        cu_slab_cell_stats(&c, &r, cu_slab_cell(&c, g, 1, 1, 1), &b);
        printf("  group %s d=11 m thetaV=40: phi 0: cx=%.3f+-%.3f cz=%.3f+-%.3f sigma=%.3f+-%.3f | phi 180: cz=%.3f+-%.3f "
               "sigma=%.3f+-%.3f (m)\n", cu_slab_group_name(g), a.cx, a.cx_se, a.cz, a.cz_se, a.sigma, a.sigma_se, b.cz,
               b.cz_se, b.sigma, b.sigma_se);
        assert_true(fabs(a.cx) < 3 * a.cx_se + 1e-9);
        assert_true(fabs(a.cz + b.cz) < 3 * sqrt(a.cz_se * a.cz_se + b.cz_se * b.cz_se));
        assert_true(fabs(a.sigma - b.sigma) < 3 * sqrt(a.sigma_se * a.sigma_se + b.sigma_se * b.sigma_se));
        assert_true(a.cz > 0);   /* light reaching p going towards -z entered on the +z side */
        if (g == 0) {
            /* single scattering: entry straight above the scattering depth z, offset (d-z) tan(thetaV), weight
             * e^{-z} e^{-(d-z)/cos(thetaV)} on [0, d] (quadrature): c_z = 4.40030 m, sigma = 1.88820 m */
            printf("  group 1 collector vs quadrature: cz %.2f SE, sigma %.2f SE\n", fabs(a.cz - 4.40030) / a.cz_se,
                   fabs(a.sigma - 1.88820) / a.sigma_se);
            assert_true(fabs(a.cz - 4.40030) < 3 * a.cz_se);
            assert_true(fabs(a.sigma - 1.88820) < 3 * a.sigma_se);
        }
    }
    cu_slab_result_free(&r);
}

/* the fitter: eq. 3.32 fitted with phi_V = 90 deg held out reproduces the held-out cells within the error it reports
 * on its training cells (held-out median <= training p90, held-out p90 <= 2 x training p90) */
static void test_fit_holdout(void **st)
{
    (void)st;
    cu_phase ph = { .kind = CU_PH_HG, .g = 0.85 };
    static const double thl[] = { 0, 40, 65 };
    int cap = 3 * 8 * 6 * 10 * 5, n = 0;
    cu_cell *cells = malloc(sizeof(cu_cell) * cap);
    int *use = malloc(sizeof(int) * cap);
    for (int l = 0; l < 3; l++) {
        cu_slab_cfg c = base_cfg(&ph, 9.05, cos(thl[l] * M_PI / 180), 30000);
        c.metres_per_tau = 1 / 0.0905; c.seed = 500 + l;
        c.table = 1; c.nd = 6;
        for (int j = 0; j < 6; j++) c.d_tau[j] = c.tau * j / 5;
        c.nv = 10; c.nphi = 5;
        for (int k = 0; k < 10; k++) c.thv_deg[k] = k < 5 ? 20 * k : 20 * k + 20;
        for (int k = 0; k < 5; k++) c.phv_deg[k] = 45 * k;
        cu_slab_result r;
        assert_int_equal(cu_slab_run(&c, &r), 0);
        for (int g = 0; g < 8; g++)
            for (int jd = 0; jd < 6; jd++)
                for (int iv = 0; iv < 10; iv++)
                    for (int ip = 0; ip < 5; ip++) {
                        cu_cell_stats s;
                        cu_slab_cell_stats(&c, &r, cu_slab_cell(&c, g, jd, iv, ip), &s);
                        cu_cell *e = &cells[n];
                        e->group = g + 1; e->t = 100; e->d = c.d_tau[jd] / 0.0905; e->thv = c.thv_deg[iv];
                        e->phv = c.phv_deg[ip]; e->thl = thl[l]; e->C = s.C; e->Cse = s.C_se;
                        use[n++] = ip != 2;
                    }
        cu_slab_result_free(&r);
    }
    double *err = malloc(sizeof(double) * n);
    static const int groups[] = { 3, 8 };
    for (int k = 0; k < 2; k++) {
        cu_fit f;
        assert_int_equal(cu_fit_slice(&f, CU_MODEL_BOUTHORS, groups[k], 100, cells, n, use), 0);
        double noise;
        int nt = cu_fit_errors(&f, cells, n, use, 1, 0.01, err, n, &noise);
        double med = cu_quantile(err, nt, 0.5), p90 = cu_quantile(err, nt, 0.9);
        int nh = cu_fit_errors(&f, cells, n, use, 0, 0.01, err, n, NULL);
        double hmed = cu_quantile(err, nh, 0.5), hp90 = cu_quantile(err, nh, 0.9);
        printf("  fit group %d t=100 m: training %d cells median %.4f p90 %.4f (MC noise %.4f); held-out %d cells "
               "median %.4f p90 %.4f (%d LM iterations)\n", groups[k], nt, med, p90, noise, nh, hmed, hp90, f.iter);
        assert_true(nt > 20 && nh > 5);
        assert_true(hmed <= p90);
        assert_true(hp90 <= 2 * p90);
    }
    free(err); free(cells); free(use);
}

int main(void)
{
    /* make stress (tools/slab/slab.mk): only the long tests */
    const char *stress = getenv("CUMULO_STRESS");
    if (stress && !strcmp(stress, "1")) {
        const struct CMUnitTest long_tests[] = {
            cmocka_unit_test(test_rt_thin_T),
        };
        return cmocka_run_group_tests_name("test_slab stress", long_tests, NULL, NULL);
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_samplers),
        cmocka_unit_test(test_mie_table_and_chop),
        cmocka_unit_test(test_single_scattering),
        cmocka_unit_test(test_rt_hg085),
        cmocka_unit_test(test_rt_iso),
        cmocka_unit_test(test_reciprocity),
        cmocka_unit_test(test_radiance_flux),
        cmocka_unit_test(test_table_transport),
        cmocka_unit_test(test_determinism),
        cmocka_unit_test(test_table_single_and_collector),
        cmocka_unit_test(test_fit_holdout),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
