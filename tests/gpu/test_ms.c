/* tests/gpu/test_ms.c: the multiple-scattering slab model: its table loader against hostile input, and renders read
 * back as float: the brightness of a lit cloud never exceeds the sunlight it intercepts, and small sun steps give small
 * image changes. (Agreement with the Monte Carlo slab simulator is tests/test_ms_slab.sh.) */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "collector.h"
#include "density.h"
#include "noise.h"
#include "phase.h"
#include "scene.h"
#include "slabmodel.h"
#include "sunmap.h"
#include "vecmath.h"
#include "render_util.h"

#define T_DIR "build/test-output/ms"

/* Copies the committed table src to dst with line `drop` removed (0: none), the first `replace_from` replaced by
 * `replace_to` and `extra` appended. */
static void write_variant(const char *src, const char *dst, int drop, const char *replace_from, const char *replace_to,
                          const char *extra)
{
    FILE *in = fopen(src, "r");
    assert_non_null(in);
    FILE *out = fopen(dst, "w");
    assert_non_null(out);
    char line[512];
    int ln = 0, replaced = 0;
    while (fgets(line, sizeof line, in)) {
        ln++;
        if (ln == drop)
            continue;
        char *at = replace_from && !replaced ? strstr(line, replace_from) : NULL;
        if (at) {
            fprintf(out, "%.*s%s%s", (int)(at - line), line, replace_to, at + strlen(replace_from));
            replaced = 1;
        } else {
            fputs(line, out);
        }
    }
    if (extra)
        fputs(extra, out);
    fclose(in);
    fclose(out);
}

/* Writes the real slab model table changed as write_variant does, then loads it. */
static int load_variant(int drop, const char *replace_from, const char *replace_to, const char *extra, cu_error *e)
{
    write_variant("data/slab_fit_bouthors.txt", T_DIR "/variant.txt", drop, replace_from, replace_to, extra);
    cu_slab_model *m = malloc(sizeof *m);
    cu_slab_transport tr;
    assert_int_equal(cu_slab_committed_transport("data", &tr, e), 0);
    int rc = cu_slab_model_load(m, T_DIR "/variant.txt", tr, e);
    free(m);
    return rc;
}

static void expect_error(int rc, const cu_error *e, const char *what)
{
    if (!rc || !strstr(e->msg, what))
        fail_msg("expected an error containing '%s', got rc %d: %s", what, rc, rc ? e->msg : "");
}

static void test_table_loader_rejects_bad_input(void **st)
{
    (void)st;
    cu_error e;
    assert_int_equal(load_variant(0, NULL, NULL, NULL, &e), 0);
    expect_error(load_variant(0, "P 1 25 Theta=0 ", "P 1 25 Theta=0 nan", NULL, &e), &e, "variant.txt:3: field 'value'");
    expect_error(load_variant(0, "P 1 25 Theta=15 ", "P 1 25 Theta=15 -", NULL, &e), &e, "variant.txt:4: field 'value'");
    /* finite as doubles, but they would be inf in the float textures */
    expect_error(load_variant(0, "P 1 25 Theta=0 353.248", "P 1 25 Theta=0 1e39", NULL, &e), &e,
                 "variant.txt:3: field 'value': '1e39' does not fit in a float");
    expect_error(load_variant(0, "A1 1 25 thetaV=0 0.0013594", "A1 1 25 thetaV=0 1e300", NULL, &e), &e,
                 "variant.txt:16: field 'value': '1e300' does not fit in a float");
    expect_error(load_variant(0, "P 1 25 Theta=0 ", "P 1 1e39 Theta=0 ", NULL, &e), &e,
                 "variant.txt:3: field 't_m': '1e39' does not fit in a float");
    expect_error(load_variant(0, "A1 1 25", "Q1 1 25", NULL, &e), &e, "unknown function 'Q1'");
    expect_error(load_variant(0, "B1 1 25", "B1 17 25", NULL, &e), &e, "unknown group '17'");
    expect_error(load_variant(0, "C 1 25 thetaV=0", "C 1 0 thetaV=0", NULL, &e), &e, "field 't_m'");
    expect_error(load_variant(0, "D 1 25 thetaV=0", "D 1 25 thetaV=400", NULL, &e), &e, "field 'node'");
    expect_error(load_variant(0, "D 1 25 thetaV=0", "D 1 25 Theta=0", NULL, &e), &e, "expected thetaV=");
    expect_error(load_variant(0, NULL, NULL, "P 1 25 Theta=0 1\n", &e), &e, "duplicate entry for P");
    expect_error(load_variant(0, NULL, NULL, "P 1 25 Theta=0 1 2\n", &e), &e, "more fields");
    expect_error(load_variant(0, NULL, NULL, "P 1 25\n", &e), &e, "fewer fields");
    int lines = 0;
    FILE *f0 = fopen("data/slab_fit_bouthors.txt", "r");
    for (int ch; (ch = fgetc(f0)) != EOF;)
        lines += ch == '\n';
    fclose(f0);
    expect_error(load_variant(lines, NULL, NULL, NULL, &e), &e, "missing B2 for group 16+"); /* the last line */
    expect_error(load_variant(0, NULL, NULL, "P 1 3200 Theta=0 1\n", &e), &e, "missing");
    char longline[700];
    memset(longline, 'x', sizeof longline - 2);
    longline[sizeof longline - 2] = '\n';
    longline[sizeof longline - 1] = 0;
    expect_error(load_variant(0, NULL, NULL, longline, &e), &e, "longer than");
    cu_slab_model *m = malloc(sizeof *m);
    cu_slab_transport tr = {0.85, 1};
    expect_error(cu_slab_model_load(m, T_DIR "/nope.txt", tr, &e), &e, "cannot open");
    FILE *f = fopen(T_DIR "/binary.txt", "wb");
    for (int i = 0; i < 300; i++)
        fputc((i * 7919) & 0xff, f);
    fclose(f);
    assert_int_not_equal(cu_slab_model_load(m, T_DIR "/binary.txt", tr, &e), 0);
    free(m);
}

/* Writes the committed collector table changed as write_variant does, then loads it. */
static int load_collector_variant(const char *replace_from, const char *replace_to, const char *extra, cu_error *e)
{
    write_variant("data/slab_collector.txt", T_DIR "/collector.txt", 0, replace_from, replace_to, extra);
    cu_collector c;
    int rc = cu_collector_load(&c, T_DIR "/collector.txt", e);
    if (!rc)
        cu_collector_free(&c);
    return rc;
}

static void test_collector_loader_rejects_bad_input(void **st)
{
    (void)st;
    cu_error e;
    if (load_collector_variant(NULL, NULL, NULL, &e))
        fail_msg("%s", e.msg);
    /* row 4 of the committed table is "25 0 0 0 45 0 0 0 0", row 5 the same at phiV = 90 */
    static const struct { const char *row4, *message; } bad[] = {
        {"25 0 0 0 45 0 1e39 0 0", "collector.txt:4: field 'cx_m': '1e39' does not fit in a float"},
        {"25 0 0 0 45 -1e300 0 0 0", "collector.txt:4: field 'C_ms': '-1e300' does not fit in a float"},
        {"25 0 0 0 45 0 0 0 nan", "collector.txt:4: field 'sigma_m': expected a finite number"},
        {"25 0 0 0 45 0 0 0", "collector.txt:4: field 'sigma_m': expected a finite number"},
        {"25 0 0 0 45 0 0 0 0 0", "collector.txt:4: more than 9 fields"},
        {"25 0 30 0 45 0 0 0 0", "collector.txt:4: field 'd_m': 30 is out of range [0, t_m = 25]"},
        {"25 0 0 0 45 -0.5 0 0 0", "collector.txt:4: field 'C_ms': -0.5 is out of range [0, inf)"},
        {"25 0 0 0 45 0 0 0 -1", "collector.txt:4: field 'sigma_m': -1 is out of range [0, inf)"},
        {"25 0 0 0 200 0 0 0 0", "collector.txt:4: field 'phiV': 200 is out of range [0, 180]"},
        {"25 0 0 0 90 0 0 0 0", "collector.txt:5: duplicate cell"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        expect_error(load_collector_variant("25 0 0 0 45 0 0 0 0", bad[i].row4, NULL, &e), &e, bad[i].message);
    expect_error(load_collector_variant(NULL, NULL, "25 0 0 0 45 0 0 0 0\n", &e), &e, "rows for a grid of");
    cu_collector c;
    expect_error(cu_collector_load(&c, T_DIR "/nope.txt", &e), &e, "cannot open the collector table");
}

/* The twin's interpolation: at the nodes it is the fitted function, between them it stays between neighbours'
 * values and never goes negative or non-finite over the whole domain and beyond it. */
static void test_model_evaluation_is_finite_and_bounded(void **st)
{
    (void)st;
    cu_slab_model *m = malloc(sizeof *m);
    cu_error e;
    cu_slab_transport tr;
    assert_int_equal(cu_slab_committed_transport("data", &tr, &e), 0);
    assert_int_equal(cu_slab_model_load(m, "data/slab_fit_bouthors.txt", tr, &e), 0);
    double worst = 0;
    for (double t = 1; t < 1e5; t *= 1.7)
        for (double rel = 0; rel <= 1.0; rel += 0.125)
            for (double thv = 0; thv <= 180; thv += 7.5)
                for (double thl = 0; thl <= 90; thl += 15)
                    for (double ph = 0; ph <= 180; ph += 30) {
                        double tv = thv * CU_PI / 180, tl = thl * CU_PI / 180;
                        double ct = cos(tl) * cos(tv) + sin(tl) * sin(tv) * cos(ph * CU_PI / 180);
                        double th = acos(fmax(-1.0, fmin(1.0, ct))) * 180 / CU_PI; /* a consistent geometry */
                        /* the renderer raises d to t / 10 for light going down (Kol 3.4.5); above it, d = 0 is
                         * the structural zero the fit was not given, and its value there is never used */
                        double d = thv < 80 ? fmax(rel, 0.1) * t : rel * t;
                        double c = cu_slab_model_eval(m, 1, t, d, thv, thl, th);
                        if (!isfinite(c) || c < 0)
                            fail_msg("C(t=%g, d=%g, thV=%g, thL=%g, Theta=%g) = %g", t, d, thv, thl, th, c);
                        if (c > worst && getenv("CUMULO_TEST_DEBUG")) printf("  C %.3g at t %g d %g thV %g thL %g Theta %g\n", c, t, d, thv, thl, th);
                        worst = fmax(worst, c);
                    }
    printf("slab model: largest C over the domain %.3g sr^-1\n", worst);
    /* the simulated C of orders 2..16+ never exceed 0.80 sr^-1 in any cell of data/slab_C_tables.tar.gz (t = 100 m,
     * d = 30 m, light going straight down); the fit with its caps stays within 1.5 times that */
    assert_true(worst < 1.2);
    free(m);
}

/* A slab returns no more than it receives: the model's orders 2..16+ integrated over both hemispheres plus the
 * closed-form single scattering and the direct beam stay <= 1 for every thickness and sun angle (the energy scaling
 * kappa in slabmodel.c guarantees it up to quadrature error; without it, 1000 m at the zenith gave 1.077). */
static void test_slab_energy_bounded(void **st)
{
    (void)st;
    cu_slab_model *m = malloc(sizeof *m);
    cu_error e;
    cu_slab_transport tr;
    assert_int_equal(cu_slab_committed_transport("data", &tr, &e), 0);
    assert_int_equal(cu_slab_model_load(m, "data/slab_fit_bouthors.txt", tr, &e), 0);
    double worst = 0;
    for (double t = 10; t < 5000; t *= 1.5)
        for (double thl = 0; thl <= 70; thl += 10) {
            double mu0 = cos(thl * CU_PI / 180), ms = 0;
            const int NV = 48, NP = 24;
            for (int i = 0; i < NV; i++)
                for (int j = 0; j < NP; j++) {
                    double thv = (i + 0.5) * 180.0 / NV, ph = (j + 0.5) * 180.0 / NP;
                    double tv = thv * CU_PI / 180, tl = thl * CU_PI / 180;
                    double ct = cos(tl) * cos(tv) + sin(tl) * sin(tv) * cos(ph * CU_PI / 180);
                    double th = acos(fmax(-1.0, fmin(1.0, ct))) * 180 / CU_PI;
                    double dw = sin(tv) * (CU_PI / NV) * (2 * CU_PI / NP);
                    ms += cu_slab_model_eval(m, 1, t, thv > 90 ? 0 : t, thv, thl, th) * fabs(cos(tv)) * dw / mu0;
                }
            double total = ms + exp(-t * CU_SLAB_KE_REF * tr.tau_scale / mu0);
            worst = fmax(worst, total);
        }
    printf("slab model: largest multiply scattered + direct flux over t = 10..5000 m, thL = 0..70: %.4f\n", worst);
    assert_true(worst <= 1.01); /* 1 plus the quadrature error of this 48 x 24 grid against conserve_energy's */
    free(m);
}

static const char *const SPHERE =
    "[output]\nsize = 64 64\nexposure = 1\n[camera]\nposition = 0 0 -20000\nlook_at = 0 0 0\nfov = 4\n"
    "[sun]\nelevation = 35\nazimuth = 30\nirradiance = 1 1 1\n[sky]\nmodel = constant\ncolor = 0 0 0\n"
    "[cloud]\ndensity = 400\nboundary = 20\n[quality]\nnoise = off\n"
    "[ellipsoid]\ncenter = 0 0 0\nradii = 500 500 500\n";

/* The sunlight a scene's clouds intercept, on the CPU with the engine's density twin (independent of the renderer's
 * energy closure, src/gpu/pass_energy.c): the integral over the sun's cross-section of 1 - e^-(1-f) tau, what the chopped
 * medium scatters (delta-M), and of 1 - e^-tau, all of it, in m^2 per unit irradiance. Also the cloud's centre and
 * bounding radius and the sun direction. */
typedef struct budget {
    double dm, full, R;
    vec3 centre, sun;
} budget;

static budget intercepted(const char *scene, const char *const *sets)
{
    budget b = {0};
    cu_scene *s;
    cu_error e;
    int rc = scene[0] == '[' ? cu_scene_parse(&s, "test", scene, strlen(scene), &e) : cu_scene_load(&s, scene, &e);
    assert_int_equal(rc, 0);
    for (int i = 0; sets && sets[i]; i++)
        assert_int_equal(cu_scene_set(s, sets[i], &e), 0);
    cu_phase_table t;
    assert_int_equal(cu_phase_table_build(&t, s, "data", &e), 0);
    cu_noise n;
    assert_int_equal(cu_noise_create(&n, 20130612u), 0); /* the renderer's NOISE_SEED */
    cu_cloud cl;
    cu_cloud_build(&cl, s, &n);
    cl.ke = cu_phase_table_extinction(&t, s);
    double f = t.f[1];
    b.sun = cu_sun_direction(s->sun_elevation, s->sun_azimuth);
    b.R = cl.bound_radius;
    b.centre = cl.origin;
    vec3 right, up;
    cu_sun_basis(b.sun, &right, &up);
    const int G = 128, M = 800;
    double px = 2 * b.R / G, ds = 2 * b.R / M;
    for (int i = 0; i < G; i++)
        for (int j = 0; j < G; j++) {
            double tau = 0;
            for (int k = 0; k < M; k++) {
                vec3 p = v3_add(v3_add(v3_scale(right, -b.R + (i + 0.5) * px), v3_scale(up, -b.R + (j + 0.5) * px)),
                                v3_scale(b.sun, -b.R + (k + 0.5) * ds));
                tau += cu_cloud_extinction(&cl, p) * ds;
            }
            b.dm += (1 - exp(-(1 - f) * tau)) * px * px;
            b.full += (1 - exp(-tau)) * px * px;
        }
    cu_noise_destroy(&n);
    cu_phase_table_free(&t);
    cu_scene_free(s);
    return b;
}

/* Radiant intensity toward direction d (from the cloud): a far camera's pixels, radiance times footprint. */
static double intensity(tr_ctx *c, int size, const char *scene, const char *const *sets, const budget *b, vec3 d)
{
    double D = 200 * b->R;
    char pos[160], look[160], fov[64];
    snprintf(pos, sizeof pos, "camera.position=%.4f %.4f %.4f", b->centre.x + D * d.x, b->centre.y + D * d.y,
             b->centre.z + D * d.z);
    snprintf(look, sizeof look, "camera.look_at=%.4f %.4f %.4f", b->centre.x, b->centre.y, b->centre.z);
    snprintf(fov, sizeof fov, "camera.fov=%.8f", 2 * atan(b->R / D) * 180 / CU_PI);
    const char *all[16] = {pos, look, fov, "sky.model=constant", "sky.color=0 0 0", "ms.sky_light=off",
                           "sun.irradiance=1 1 1"};
    int k = 7;
    for (int i = 0; sets && sets[i] && k < 15; i++)
        all[k++] = sets[i];
    all[k] = NULL;
    if (tr_render(c, scene, all))
        fail_msg("%s", c->err);
    float *px = malloc(sizeof(float) * (size_t)(size * size * 3));
    tr_read_rgbf(c, px);
    double I = 0, a = 2 * b->R / size;
    for (int q = 0; q < size * size; q++)
        I += px[3 * q + 1] * a * a;
    free(px);
    return I;
}

/* Energy, sphere: a sphere of cloud (radius 500 m, optical diameter 69) in black space. It is symmetric about the
 * sun's axis, so the power it scatters is 2 pi times the integral of its intensity over cos(Theta), Theta the
 * scattering angle: 24 views, midpoints in cos(Theta) over Theta = 4..180 deg (at 4 deg the sun disk is out of the
 * view; the forward peak's energy inside is exact by construction, cloud.frag, and the smooth terms' share of
 * 0..4 deg is about 0.05 %). The power must stay within what the cloud intercepts, whatever the blur and with the
 * collector search; without the energy closure it does not (the control). Measured (2026-11-22): 0.839, 0.980 and
 * 0.962 of the delta-M intercepted power for blur 200 m, 800 m and the collector; 2.12 without the closure at
 * 800 m; the path tracer gives 0.989 over the same angles (0.961 of pi R^2). */
static double sphere_power(tr_ctx *c, const char *const *sets, const budget *b)
{
    vec3 right, up;
    cu_sun_basis(b->sun, &right, &up);
    const int N = 24;
    double mu0 = cos(4 * CU_PI / 180), power = 0;
    for (int i = 0; i < N; i++) {
        double mu = mu0 - (i + 0.5) * (mu0 + 1) / N, s = sqrt(1 - mu * mu);
        vec3 d = v3_add(v3_scale(b->sun, -mu), v3_scale(right, s)); /* light leaving at Theta = acos(mu) */
        power += intensity(c, 64, SPHERE, sets, b, d) * 2 * CU_PI * (mu0 + 1) / N;
    }
    return power;
}

static void test_sphere_power_within_intercepted(void **st)
{
    (void)st;
    tr_ctx c;
    if (tr_open(&c, &cu_display_egl, 64, 64, 1))
        fail_msg("%s", c.err);
    budget b = intercepted(SPHERE, NULL);
    printf("sphere: intercepted %.4g m^2 (delta-M), %.4g (all), pi R^2 = %.4g\n", b.dm, b.full, CU_PI * 500 * 500);
    const char *cases[][3] = {{"ms.blur=200", NULL}, {"ms.blur=800", NULL}, {"ms.mode=collector", NULL}};
    for (int k = 0; k < 3; k++) {
        double p = sphere_power(&c, cases[k], &b);
        printf("sphere, %s: scattered %.4f of the intercepted (delta-M)\n", cases[k][0], p / b.dm);
        assert_true(p <= b.dm);
        assert_true(p > 0.8 * b.dm); /* and most of it is there: the test notices a dark cloud */
    }
    const char *off[] = {"ms.blur=800", "ms.closure=off", NULL};
    double p = sphere_power(&c, off, &b);
    printf("sphere, ms.blur=800 without the closure: %.4f of the intercepted (delta-M)\n", p / b.dm);
    assert_true(p > 1.3 * b.dm);
    tr_close(&c);
}

/* Energy, a noisy cumulus (scenes/cumulus.scene, sky and sky light off): intensities over a Fibonacci sphere of 96
 * directions (4 pi / 96 sr each, 48 x 48 pixels), leaving out those within 10 deg of the sunbeam (the forward peak,
 * exact by construction, and the sun disk). Measured (2026-11-22): 0.944 of the delta-M intercepted power with the
 * closure (96 directions; 600 directions at 48 pixels gave 0.94 and 64 at 64 pixels 0.97 with an earlier version of
 * the closure: the rule's error is about 3 %), 1.57 without it (32 directions). */
static double fibonacci_power(tr_ctx *c, const char *scene, const char *const *sets, const budget *b, int n)
{
    double power = 0;
    for (int i = 0; i < n; i++) {
        double z = 1 - (i + 0.5) * 2.0 / n, r = sqrt(1 - z * z), ph = i * 2.399963229728653;
        vec3 d = v3(r * cos(ph), z, r * sin(ph));
        if (v3_dot(d, b->sun) < -cos(10 * CU_PI / 180))
            continue;
        power += intensity(c, 48, scene, sets, b, d) * 4 * CU_PI / n;
    }
    return power;
}

static void test_cumulus_power_within_intercepted(void **st)
{
    (void)st;
    tr_ctx c;
    if (tr_open(&c, &cu_display_egl, 48, 48, 1))
        fail_msg("%s", c.err);
    budget b = intercepted("scenes/cumulus.scene", NULL);
    double p = fibonacci_power(&c, "scenes/cumulus.scene", NULL, &b, 96);
    printf("cumulus: intercepted %.4g m^2 (delta-M); scattered %.4f of it\n", b.dm, p / b.dm);
    assert_true(p <= b.dm);
    assert_true(p > 0.7 * b.dm);
    const char *off[] = {"ms.closure=off", NULL};
    double q = fibonacci_power(&c, "scenes/cumulus.scene", off, &b, 32);
    printf("cumulus without the closure: %.4f of it\n", q / b.dm);
    assert_true(q > 1.2 * b.dm);
    tr_close(&c);
}

/* Small sun steps give small image changes: no popping when the sun maps and slab maps are redone, nor when the
 * energy closure's gains are measured again (src/gpu/pass_energy.c: once the sun has moved 1 deg, here between 41.00 and
 * 41.05). The step 0.05 deg moves the sun's shadow by 1 m at 1 km; the change per step is compared with the image's
 * range. */
static void test_sun_steps_are_continuous(void **st)
{
    (void)st;
    tr_ctx c;
    if (tr_open(&c, &cu_display_egl, 160, 120, 1))
        fail_msg("%s", c.err);
    size_t n = 160 * 120 * 3;
    float *a = malloc(sizeof(float) * n), *b = malloc(sizeof(float) * n);
    double worst = 0, range = 0;
    const double elev[] = {40.0, 40.05, 40.1, 40.15, 40.2, 40.95, 41.0, 41.05, 41.1};
    /* the scene once; then only the sun moves, as with a knob. Whole maps every frame: with the maps made over several
     * frames the 0.75 degree step (not checked) would arrive frames later, at a checked step, as the maps catch up
     * (test_sun_bands checks the continuity of those) */
    const char *whole[] = {"quality.sun_map_frames=1", NULL};
    if (tr_render(&c, "scenes/cumulus.scene", whole))
        fail_msg("%s", c.err);
    double el0, az;
    cu_renderer_get_sun(c.r, &el0, &az);
    for (int k = 0; k < 9; k++) {
        cu_error e;
        assert_int_equal(cu_renderer_set_sun(c.r, elev[k], az, &e), 0);
        if (tr_render_again(&c))
            fail_msg("%s", c.err);
        tr_read_rgbf(&c, k ? b : a);
        if (k && k != 5) {
            double step = 0;
            for (size_t i = 0; i < n; i++) {
                step = fmax(step, fabs(a[i] - b[i]));
                range = fmax(range, a[i]);
            }
            printf("sun %.2f -> %.2f deg: largest pixel change %.3g\n", elev[k - 1], elev[k], step);
            worst = fmax(worst, step);
        }
        if (k)
            memcpy(a, b, sizeof(float) * n);
    }
    printf("sun steps of 0.05 deg: largest pixel change %.3g (image maximum %.3g, %.2f%%)\n", worst, range,
           100 * worst / range);
    assert_true(worst < 0.02 * range);
    free(a);
    free(b);
    tr_close(&c);
}

int main(void)
{
    if (system("mkdir -p " T_DIR) != 0)
        return 1;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_table_loader_rejects_bad_input),
        cmocka_unit_test(test_collector_loader_rejects_bad_input),
        cmocka_unit_test(test_model_evaluation_is_finite_and_bounded),
        cmocka_unit_test(test_slab_energy_bounded),
        cmocka_unit_test(test_sphere_power_within_intercepted),
        cmocka_unit_test(test_cumulus_power_within_intercepted),
        cmocka_unit_test(test_sun_steps_are_continuous),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
