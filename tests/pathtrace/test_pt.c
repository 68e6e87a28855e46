/* tests/pathtrace/test_pt.c: validation of the reference path tracer against closed forms and independent numbers
 * (VALIDATION.md): phase sampling, Beer-Lambert chords, furnace, plane-parallel slab R/T, determinism, camera. */
#include "pt.h"
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include <sys/stat.h>

/* A homogeneous ellipsoid seen in a white constant environment with no sun (VALIDATION.md's Beer-Lambert set-up). */
static const char homog_scene[] = "[output]\nsize = 12 9\n"
                                  "[camera]\nposition = 0 0 -100\nlook_at = 0 0 0\nfov = 15\n"
                                  "[sun]\nirradiance = 0 0 0\n"
                                  "[sky]\nmodel = constant\ncolor = 1 1 1\n"
                                  "[cloud]\nboundary = 0\nphase = hg\ng = 0.85\n"
                                  "[ellipsoid]\ncenter = 3 -2 1\nradii = 15 10 12\n"
                                  "[quality]\nnoise = off\n";

static pt_ctx *ctx_from_text(const char *text, const char *const *sets)
{
    cu_scene *s;
    cu_error e;
    if (cu_scene_parse(&s, "test.scene", text, strlen(text), &e))
        fail_msg("%s", e.msg);
    for (int i = 0; sets && sets[i]; i++)
        if (cu_scene_set(s, sets[i], &e))
            fail_msg("%s", e.msg);
    pt_ctx *c = malloc(sizeof *c);
    assert_non_null(c);
    if (pt_ctx_init(c, s, "data", &e))
        fail_msg("%s", e.msg);
    cu_scene_free(s);
    return c;
}

static pt_ctx *ctx_from_file(const char *path, const char *const *sets)
{
    cu_scene *s;
    cu_error e;
    if (cu_scene_load(&s, path, &e))
        fail_msg("%s", e.msg);
    for (int i = 0; sets && sets[i]; i++)
        if (cu_scene_set(s, sets[i], &e))
            fail_msg("%s", e.msg);
    pt_ctx *c = malloc(sizeof *c);
    assert_non_null(c);
    if (pt_ctx_init(c, s, "data", &e))
        fail_msg("%s", e.msg);
    cu_scene_free(s);
    return c;
}

static void ctx_free(pt_ctx *c)
{
    pt_ctx_free(c);
    free(c);
}

static void test_rng(void **state)
{
    (void)state;
    pt_rng a, b, d;
    pt_rng_seed(&a, 7, 123);
    pt_rng_seed(&b, 7, 123);
    pt_rng_seed(&d, 7, 124);
    int same = 0;
    double sum = 0;
    for (int i = 0; i < 100000; i++) {
        double u = pt_rng_uniform(&a);
        assert_true(u >= 0 && u < 1);
        assert_true(u == pt_rng_uniform(&b));
        same += u == pt_rng_uniform(&d);
        sum += u;
    }
    assert_int_equal(same, 0);
    /* mean 1/2 with SE sqrt(1/12/N) = 9.1e-4 */
    assert_true(fabs(sum / 100000 - 0.5) < 4 * 9.2e-4);
}

/* The tabulated sampler reproduces HG's closed form: values at several angles, and <cos> = g by sampling. */
static void test_phase_hg(void **state)
{
    (void)state;
    const char *sets[] = {"cloud.g=0.85", NULL};
    pt_ctx *c = ctx_from_text(homog_scene, sets);
    assert_true(c->phase.mono);
    assert_true(fabs(c->phase.norm[0] - 1) < 1e-3);
    const double ang[] = {0, 0.01, 0.3, 1.0, 2.0, 3.0, CU_PI};
    for (size_t i = 0; i < sizeof ang / sizeof ang[0]; i++) {
        double p = pt_phase_eval(&c->phase, 0, ang[i], sin(ang[i]) < 1e-15 ? 0 : sin(ang[i]));
        double q = cu_phase_hg(0.85, cos(ang[i]));
        print_message("HG g=0.85 theta %.3f: table %.6g closed form %.6g (rel %.2e)\n", ang[i], p, q, p / q - 1);
        assert_true(fabs(p / q - 1) < 2e-3);
    }
    pt_rng r;
    pt_rng_seed(&r, 1, 0);
    const int N = 400000;
    double s = 0, s2 = 0;
    vec3 d = v3_norm(v3(0.3, -0.5, 0.8));
    for (int i = 0; i < N; i++) {
        double w[3];
        double mu = v3_dot(d, pt_phase_sample(&c->phase, d, &r, w, NULL));
        assert_true(w[0] == 1 && w[1] == 1 && w[2] == 1);
        s += mu;
        s2 += mu * mu;
    }
    double m = s / N, se = sqrt((s2 / N - m * m) / N);
    print_message("HG g=0.85 sampled <cos> = %.5f +- %.5f\n", m, se);
    assert_true(fabs(m - 0.85) < 3 * se + 1e-4);
    ctx_free(c);
}

/* Cornette-Shanks: table values against the closed form, and its mean cosine 3g(4+g^2)/(5(2+g^2)) (not g). */
static void test_phase_cs(void **state)
{
    (void)state;
    pt_ctx *c = ctx_from_text(homog_scene, (const char *[]){"cloud.phase=cornette-shanks", "cloud.g=0.8", NULL});
    assert_true(c->phase.mono);
    for (double th = 0.05; th < 3.1; th += 0.5) {
        double p = pt_phase_eval(&c->phase, 0, th, sin(th)), q = cu_phase_cornette_shanks(0.8, cos(th));
        assert_true(fabs(p / q - 1) < 2e-3);
    }
    pt_rng r;
    pt_rng_seed(&r, 4, 0);
    const int N = 400000;
    double s = 0, s2 = 0, w[3];
    for (int i = 0; i < N; i++) {
        double mu = pt_phase_sample(&c->phase, v3(0, 1, 0), &r, w, NULL).y;
        s += mu;
        s2 += mu * mu;
    }
    double m = s / N, se = sqrt((s2 / N - m * m) / N), g = 0.8, expect = 3 * g * (4 + g * g) / (5 * (2 + g * g));
    print_message("Cornette-Shanks g=0.8 sampled <cos> = %.5f +- %.5f (closed form %.5f)\n", m, se, expect);
    assert_true(fabs(m - expect) < 3 * se + 1e-4);
    ctx_free(c);
}

/* Mie: the full function (P~ + P_p) has the table's g, and the spectral weights have mean 1 in every channel. */
static void test_phase_mie(void **state)
{
    (void)state;
    pt_ctx *c = ctx_from_text(homog_scene, (const char *[]){"cloud.phase=mie", NULL});
    assert_false(c->phase.mono);
    pt_rng r;
    pt_rng_seed(&r, 2, 0);
    const int N = 400000;
    double sw[3] = {0}, sw2[3] = {0}, sg[3] = {0};
    vec3 d = v3(0, 0, 1);
    for (int i = 0; i < N; i++) {
        double w[3];
        double mu = pt_phase_sample(&c->phase, d, &r, w, NULL).z;
        for (int k = 0; k < 3; k++) {
            sw[k] += w[k];
            sw2[k] += w[k] * w[k];
            sg[k] += w[k] * mu;
        }
    }
    for (int k = 0; k < 3; k++) {
        double m = sw[k] / N, se = sqrt((sw2[k] / N - m * m) / N);
        print_message("Mie channel %d: norm before scaling %.6f, mean weight %.5f +- %.5f, <cos> %.5f (table g %.5f)\n",
                      k, c->phase.norm[k], m, se, sg[k] / N, c->table.g_full[k]);
        assert_true(fabs(m - 1) < 4 * se);
        assert_true(fabs(sg[k] / N - c->table.g_full[k]) < 0.003);
    }
    ctx_free(c);
}

/* Chord length through an ellipsoid (VALIDATION.md "Beer-Lambert through an ellipsoid"); 0 on a miss. */
static double chord(vec3 o, vec3 d, vec3 cen, vec3 a)
{
    double A = 0, B = 0, C = -1;
    double oo[3] = {o.x - cen.x, o.y - cen.y, o.z - cen.z}, dd[3] = {d.x, d.y, d.z}, aa[3] = {a.x, a.y, a.z};
    for (int i = 0; i < 3; i++) {
        A += dd[i] * dd[i] / (aa[i] * aa[i]);
        B += 2 * oo[i] * dd[i] / (aa[i] * aa[i]);
        C += oo[i] * oo[i] / (aa[i] * aa[i]);
    }
    double disc = B * B - 4 * A * C;
    return disc > 0 ? sqrt(disc) / A : 0;
}

static void beer_lambert(double majorant_scale)
{
    pt_ctx *c = ctx_from_text(homog_scene, NULL);
    c->majorant = c->cloud.ke * majorant_scale;
    pt_render_opts o = {c->width, c->height, 1000, 2, 11, 0, PT_MODE_TRANSMITTANCE, 0};
    size_t np = 3 * (size_t)o.width * o.height;
    float *mean = malloc(sizeof(float) * np), *se = malloc(sizeof(float) * np);
    pt_counters k;
    cu_error e;
    assert_int_equal(pt_render(c, &o, mean, se, &k, &e), 0);
    double sum_d = 0, sum_v = 0, zmax = 0, tmin = 1;
    int hit = 0;
    for (int y = 0; y < o.height; y++)
        for (int x = 0; x < o.width; x++) {
            vec3 ro, rd;
            pt_camera_ray(c, x + 0.5, y + 0.5, &ro, &rd);
            /* world-space chord with the scene's own numbers: camera (0,0,-100), centre (3,-2,1) */
            double L = chord(v3(0, 0, -100), rd, v3(3, -2, 1), v3(15, 10, 12));
            double T = exp(-c->cloud.ke * L), est = mean[3 * (y * o.width + x)], s = se[3 * (y * o.width + x)];
            if (L == 0) {
                assert_true(est == 1.0f); /* a miss is exact */
                continue;
            }
            hit++;
            tmin = fmin(tmin, T);
            assert_true(s > 0);
            double z = (est - T) / s;
            zmax = fmax(zmax, fabs(z));
            sum_d += est - T;
            sum_v += (double)s * s;
        }
    double ztot = sum_d / sqrt(sum_v);
    print_message("Beer-Lambert (majorant %.0fx k_e): %d pixels hit, min T %.3f, max |z| %.2f, mean difference "
                  "%.2e (z = %.2f)\n", majorant_scale, hit, tmin, zmax, sum_d / hit, ztot);
    assert_true(hit > 40);
    assert_true(zmax < 4.5);
    assert_true(fabs(ztot) < 3);
    free(mean);
    free(se);
    ctx_free(c);
}

static void test_beer_lambert_delta(void **state)
{
    (void)state;
    beer_lambert(1.0);
}

/* With a majorant twice k_e, ratio tracking gives non-binary weights (and the Russian roulette below T = 0.1). */
static void test_beer_lambert_ratio(void **state)
{
    (void)state;
    beer_lambert(2.0);
}

/* Furnace: albedo 1, constant environment c, no sun: with HG every path returns exactly c. The real cumulus
 * density (noise, boundary) is used, so this checks that the tracker neither loses nor creates paths. */
static void furnace(const char *color, const double expect[3])
{
    char setc[64];
    snprintf(setc, sizeof setc, "sky.color=%s", color);
    const char *sets[] = {"cloud.phase=hg",  "sky.model=constant", setc, "sun.irradiance=0 0 0", "output.size=8 6",
                          "camera.fov=25", "camera.look_at=0 260 0", NULL};
    pt_ctx *c = ctx_from_file("scenes/cumulus.scene", sets);
    pt_render_opts o = {8, 6, 2, 2, 5, 0, PT_MODE_RADIANCE, 0};
    float mean[8 * 6 * 3], se[8 * 6 * 3];
    pt_counters k;
    cu_error e;
    assert_int_equal(pt_render(c, &o, mean, se, &k, &e), 0);
    double dmax = 0;
    for (int i = 0; i < 8 * 6; i++)
        for (int ch = 0; ch < 3; ch++)
            dmax = fmax(dmax, fabs(mean[3 * i + ch] - expect[ch]) / expect[ch]);
    print_message("furnace sky %s: %llu paths, %.1f scattering events per path, max relative deviation %.2e\n", color,
                  (unsigned long long)k.paths, (double)k.scatters / k.paths, dmax);
    assert_true(k.scatters > 10 * k.paths / 4); /* the rays did go through the cloud */
    assert_int_equal(k.truncated, 0);
    assert_true(dmax < 1e-6);
    ctx_free(c);
}

static void test_furnace_white(void **state)
{
    (void)state;
    furnace("1 1 1", (const double[]){1, 1, 1});
}

static void test_furnace_colour(void **state)
{
    (void)state;
    furnace("0.2 0.5 0.9", (const double[]){0.2, 0.5, 0.9});
}

/* Mie furnace: the spectral weights vary per path, but every channel's expectation is exactly 1. */
static void test_furnace_mie(void **state)
{
    (void)state;
    const char *sets[] = {"sky.model=constant", "sky.color=1 1 1", "sun.irradiance=0 0 0", "output.size=4 3",
                          "camera.look_at=0 260 0", "camera.fov=25", NULL};
    pt_ctx *c = ctx_from_file("scenes/cumulus.scene", sets);
    pt_render_opts o = {4, 3, 100, 2, 9, 0, PT_MODE_RADIANCE, 0};
    float mean[4 * 3 * 3], se[4 * 3 * 3];
    pt_counters k;
    cu_error e;
    assert_int_equal(pt_render(c, &o, mean, se, &k, &e), 0);
    for (int ch = 0; ch < 3; ch++) {
        double d = 0, v = 0;
        for (int i = 0; i < 12; i++) {
            d += mean[3 * i + ch] - 1.0;
            v += (double)se[3 * i + ch] * se[3 * i + ch];
        }
        print_message("Mie furnace channel %d: mean %.5f +- %.5f (%.1f events per path)\n", ch, 1 + d / 12,
                      sqrt(v) / 12, (double)k.scatters / k.paths);
        assert_true(fabs(d) < 4 * sqrt(v) + 1e-9);
    }
    ctx_free(c);
}

/* Mie furnace with many events: a tau = 10 slab in a white environment (about 20 events per path), so the hero
 * channel's path-level weights are exercised over long paths; every channel's expectation is exactly 1. */
static void test_furnace_mie_slab(void **state)
{
    (void)state;
    pt_ctx *c = ctx_from_text(homog_scene, (const char *[]){"cloud.phase=mie", NULL});
    pt_ctx_use_slab(c, 10.0);
    c->env = PT_ENV_HEMISPHERES;
    for (int i = 0; i < 3; i++)
        c->env_up[i] = c->env_down[i] = 1;
    pt_rng r;
    pt_rng_seed(&r, 6, 0);
    pt_counters k = {0};
    const int N = 100000;
    double s1[3] = {0}, s2[3] = {0};
    for (int i = 0; i < N; i++) {
        double L[3];
        pt_radiance(c, v3(0, 1, 0), v3(0, -1, 0), &r, L, &k);
        for (int j = 0; j < 3; j++) {
            s1[j] += L[j];
            s2[j] += L[j] * L[j];
            assert_true(L[j] >= 0 && L[j] <= 3.0 + 1e-9); /* the path-level weight is bounded by 3 */
        }
    }
    for (int j = 0; j < 3; j++) {
        double m = s1[j] / N, se = sqrt((s2[j] / N - m * m) / (N - 1));
        print_message("Mie slab furnace tau=10 channel %d: %.5f +- %.5f (%.1f events per path)\n", j, m, se,
                      (double)k.scatters / N);
        assert_true(fabs(m - 1) < 4 * se); /* 4 SE: three channels, and the SE itself is estimated */
    }
    ctx_free(c);
}

/* Plane-parallel slab (VALIDATION.md): looking straight down at a slab lit by a uniform sky of radiance 1 from above
 * gives, by reciprocity, the plane albedo R for normal incidence; light from below gives T. One path lands in
 * exactly one of the two channels, so R + T = 1 per path. */
typedef struct slab_case {
    double g, tau, R;
    int paths;
} slab_case;

static void slab_rt(pt_ctx *c, double tau, int n, int max_depth, double *R, double *seR, double *T, double *seT)
{
    pt_ctx_use_slab(c, tau);
    c->env = PT_ENV_HEMISPHERES;
    c->env_up[0] = 1;
    c->env_down[1] = 1;
    c->max_depth = max_depth;
    pt_rng r;
    pt_rng_seed(&r, 42, (uint64_t)(tau * 1000));
    pt_counters k = {0};
    double sr = 0, st = 0;
    for (int i = 0; i < n; i++) {
        double L[3];
        pt_radiance(c, v3(0, 1, 0), v3(0, -1, 0), &r, L, &k);
        if (max_depth > 1000)
            assert_true(L[0] + L[1] == 1.0);
        sr += L[0];
        st += L[1];
    }
    *R = sr / n;
    *T = st / n;
    *seR = sqrt(*R * (1 - *R) / (n - 1));
    *seT = sqrt(*T * (1 - *T) / (n - 1));
}

static void test_slab(void **state)
{
    (void)state;
    const slab_case cases[] = {
        {0.85, 1, 0.04232, 4000000}, {0.85, 2, 0.09102, 1500000}, {0.85, 10, 0.42228, 300000},
        {0.0, 1, 0.34133, 300000},   {0.0, 10, 0.85300, 60000},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const slab_case *sc = &cases[i];
        char g[32];
        snprintf(g, sizeof g, "cloud.g=%g", sc->g);
        pt_ctx *c = ctx_from_text(homog_scene, (const char *[]){g, NULL});
        double R, seR, T, seT;
        slab_rt(c, sc->tau, sc->paths, 1000000, &R, &seR, &T, &seT);
        double z = (R - sc->R) / seR, rel = R / sc->R - 1;
        print_message("slab g=%.2f tau=%4.1f: R = %.5f +- %.5f (reference %.5f, z = %+.2f, rel %+.2f%%), "
                      "T = %.5f +- %.5f (1 - R_ref = %.5f), %d paths\n",
                      sc->g, sc->tau, R, seR, sc->R, z, 100 * rel, T, seT, 1 - sc->R, sc->paths);
        assert_true(fabs(z) < 3);
        assert_true(fabs(rel) < 0.01);
        assert_true(fabs((T - (1 - sc->R)) / seT) < 3);
        ctx_free(c);
    }
}

/* Single scattering only (max depth 1): R1 and T1 (+ the unscattered e^-tau) from VALIDATION.md's closed forms. */
static void test_slab_single(void **state)
{
    (void)state;
    const struct {
        double g, R1, T1;
    } cases[] = {{0.85, 0.00895, 0.32926}, {0.0, 0.14202, 0.10617}};
    for (int i = 0; i < 2; i++) {
        char g[32];
        snprintf(g, sizeof g, "cloud.g=%g", cases[i].g);
        pt_ctx *c = ctx_from_text(homog_scene, (const char *[]){g, NULL});
        double R, seR, T, seT;
        slab_rt(c, 1.0, 1000000, 1, &R, &seR, &T, &seT);
        double T1 = T - exp(-1.0);
        print_message("slab single scattering g=%.2f tau=1: R1 = %.5f +- %.5f (ref %.5f, z %+.2f), "
                      "T1 = %.5f +- %.5f (ref %.5f, z %+.2f)\n",
                      cases[i].g, R, seR, cases[i].R1, (R - cases[i].R1) / seR, T1, seT, cases[i].T1,
                      (T1 - cases[i].T1) / seT);
        assert_true(fabs(R - cases[i].R1) < 3 * seR);
        assert_true(fabs(T1 - cases[i].T1) < 3 * seT);
        ctx_free(c);
    }
}

/* Next-event estimation and ratio tracking through the slab: sun at the zenith (irradiance 1), black sky, views
 * cosine-distributed over the lower hemisphere from above: pi * <L> is the plane albedo R at normal incidence. */
static void test_slab_nee(void **state)
{
    (void)state;
    const struct {
        double tau, R;
        int n;
    } cases[] = {{1, 0.04232, 300000}, {10, 0.42228, 60000}};
    for (int i = 0; i < 2; i++) {
        pt_ctx *c = ctx_from_text(homog_scene, (const char *[]){"sky.color=0 0 0", NULL});
        pt_ctx_use_slab(c, cases[i].tau);
        c->majorant *= 1.5; /* non-binary ratio tracking on the shadow rays */
        c->sun_dir = v3(0, 1, 0);
        c->sun_irr[0] = c->sun_irr[1] = c->sun_irr[2] = 1;
        pt_rng r;
        pt_rng_seed(&r, 3, (uint64_t)i);
        pt_counters k = {0};
        double s = 0, s2 = 0;
        for (int j = 0; j < cases[i].n; j++) {
            double u = pt_rng_uniform(&r), phi = 2 * CU_PI * pt_rng_uniform(&r);
            double ct = sqrt(1 - u), st = sqrt(u); /* cosine-weighted about -y */
            double L[3];
            pt_radiance(c, v3(0, 1, 0), v3(st * cos(phi), -ct, st * sin(phi)), &r, L, &k);
            double v = CU_PI * L[1];
            s += v;
            s2 += v * v;
        }
        double m = s / cases[i].n, se = sqrt((s2 / cases[i].n - m * m) / (cases[i].n - 1));
        print_message("slab NEE g=0.85 tau=%.0f: pi<L> = %.5f +- %.5f (reference R %.5f, z %+.2f, rel %+.2f%%)\n",
                      cases[i].tau, m, se, cases[i].R, (m - cases[i].R) / se, 100 * (m / cases[i].R - 1));
        assert_true(fabs(m - cases[i].R) < 3 * se);
        assert_true(fabs(m / cases[i].R - 1) < 0.02);
        ctx_free(c);
    }
}

/* The forward-peak MIS (strategy B) changes the variance, not the expectation: a Mie slab lit by a zenith sun, seen
 * from below 12 degrees off the sun, with and without it. */
static void test_peak_mis(void **state)
{
    (void)state;
    pt_ctx *c = ctx_from_text(homog_scene, (const char *[]){"cloud.phase=mie", "sky.color=0 0 0", NULL});
    pt_ctx_use_slab(c, 2.0);
    c->sun_dir = v3(0, 1, 0);
    c->sun_irr[0] = c->sun_irr[1] = c->sun_irr[2] = 1;
    vec3 d = v3(sin(12 * CU_PI / 180), cos(12 * CU_PI / 180), 0);
    double m[2], se[2];
    const int n[2] = {400000, 100000};
    for (int g = 0; g < 2; g++) {
        c->guide = g ? 1.0 : 0.0;
        pt_rng r;
        pt_rng_seed(&r, 8, (uint64_t)g);
        pt_counters k = {0};
        double s = 0, s2 = 0;
        for (int j = 0; j < n[g]; j++) {
            double L[3];
            pt_radiance(c, v3(0, -1001, 0), d, &r, L, &k);
            s += L[1];
            s2 += L[1] * L[1];
        }
        m[g] = s / n[g];
        se[g] = sqrt((s2 / n[g] - m[g] * m[g]) / (n[g] - 1));
    }
    double z = (m[1] - m[0]) / sqrt(se[0] * se[0] + se[1] * se[1]);
    print_message("Mie slab tau=2 seen from below: without peak MIS %.5f +- %.5f (%d paths), with %.5f +- %.5f "
                  "(%d paths), z = %+.2f\n", m[0], se[0], n[0], m[1], se[1], n[1], z);
    assert_true(fabs(z) < 3);
    ctx_free(c);
}

/* Same seed: bit-identical images for 1 and 2 threads (one random stream per pixel); another seed differs. */
static void test_determinism(void **state)
{
    (void)state;
    pt_ctx *c = ctx_from_file("scenes/cumulus.scene", (const char *[]){"output.size=10 8", NULL});
    enum { NP = 10 * 8 * 3 };
    float m1[NP], s1[NP], m2[NP], s2[NP], m3[NP];
    pt_render_opts o = {10, 8, 2, 1, 77, 1, PT_MODE_RADIANCE, 0};
    pt_counters k;
    cu_error e;
    assert_int_equal(pt_render(c, &o, m1, s1, &k, &e), 0);
    o.threads = 2;
    assert_int_equal(pt_render(c, &o, m2, s2, &k, &e), 0);
    assert_memory_equal(m1, m2, sizeof m1);
    assert_memory_equal(s1, s2, sizeof s1);
    o.seed = 78;
    assert_int_equal(pt_render(c, &o, m3, NULL, &k, &e), 0);
    assert_true(memcmp(m1, m3, sizeof m1) != 0);
    for (int i = 0; i < NP; i++)
        assert_true(isfinite(m1[i]) && m1[i] >= 0);
    ctx_free(c);
}

/* The camera matches the renderer's: centre pixel along the look direction, top edge at fov/2 above it. */
static void test_camera(void **state)
{
    (void)state;
    pt_ctx *c = ctx_from_text(homog_scene, (const char *[]){"output.size=9 7", "camera.fov=40", NULL});
    vec3 o, d;
    pt_camera_ray(c, 4.5, 3.5, &o, &d);
    assert_true(v3_len(v3_sub(d, v3(0, 0, 1))) < 1e-12);
    assert_true(v3_len(v3_sub(v3_add(o, c->cloud.origin), v3(0, 0, -100))) < 1e-9);
    pt_camera_ray(c, 4.5, 0.0, &o, &d);
    assert_true(fabs(atan2(d.y, d.z) - 20 * CU_PI / 180) < 1e-12);
    pt_camera_ray(c, 9.0, 3.5, &o, &d); /* right edge (-x here: right = forward x up) */
    assert_true(fabs(fabs(atan2(d.x, d.z)) - atan(tan(20 * CU_PI / 180) * 9.0 / 7.0)) < 1e-12);
    ctx_free(c);
}

/* The dump holds exactly the extinction the tracer sees, little-endian, x fastest, at voxel centres. */
static void test_dump_density(void **state)
{
    (void)state;
    pt_ctx *c = ctx_from_file("scenes/cumulus.scene", NULL);
    const char *path = "build/test-output/pathtrace_dump.raw";
    cu_error e;
    mkdir("build", 0777); /* may exist: then this fails harmlessly */
    mkdir("build/test-output", 0777);
    if (pt_dump_density(c, path, 7, 5, 3, PT_NOISE_SEED, &e))
        fail_msg("%s", e.msg);
    FILE *fp = fopen(path, "rb");
    assert_non_null(fp);
    unsigned char b[7 * 5 * 3 * 4];
    assert_int_equal(fread(b, 1, sizeof b, fp), sizeof b);
    assert_int_equal(fgetc(fp), EOF);
    fclose(fp);
    vec3 lo = c->cloud.bounds_min, hi = c->cloud.bounds_max;
    int nonzero = 0;
    for (int z = 0; z < 3; z++)
        for (int y = 0; y < 5; y++)
            for (int x = 0; x < 7; x++) {
                const unsigned char *q = b + 4 * (x + 7 * (y + 5 * z));
                uint32_t u = q[0] | (uint32_t)q[1] << 8 | (uint32_t)q[2] << 16 | (uint32_t)q[3] << 24;
                float v;
                memcpy(&v, &u, 4);
                vec3 p = v3(lo.x + (x + 0.5) * (hi.x - lo.x) / 7, lo.y + (y + 0.5) * (hi.y - lo.y) / 5,
                            lo.z + (z + 0.5) * (hi.z - lo.z) / 3);
                assert_true(v == (float)pt_extinction(c, p));
                nonzero += v > 0;
            }
    assert_true(nonzero > 10);
    ctx_free(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rng),           cmocka_unit_test(test_phase_hg),
        cmocka_unit_test(test_phase_cs),
        cmocka_unit_test(test_phase_mie),     cmocka_unit_test(test_camera),
        cmocka_unit_test(test_beer_lambert_delta), cmocka_unit_test(test_beer_lambert_ratio),
        cmocka_unit_test(test_furnace_white), cmocka_unit_test(test_furnace_colour),
        cmocka_unit_test(test_furnace_mie),
        cmocka_unit_test(test_furnace_mie_slab),   cmocka_unit_test(test_slab),
        cmocka_unit_test(test_slab_single),   cmocka_unit_test(test_slab_nee),
        cmocka_unit_test(test_determinism),   cmocka_unit_test(test_dump_density),
        cmocka_unit_test(test_peak_mis),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
