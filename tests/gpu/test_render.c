/* tests/gpu/test_render.c: the renderer through both headless back ends (EGL surfaceless GLES 3.2 and OSMesa GL 4.5
 * core): Beer-Lambert opacity along chords, the union of overlapping ellipsoids integrated once, an empty scene is
 * exactly the sky, no NaN/Inf anywhere, camera continuity into the cloud, reference images, back ends agree. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "ellipsoid.h"
#include "image.h"
#include "scene.h"
#include "render_util.h"

static const cu_display_backend *const backends[] = {&cu_display_egl, &cu_display_osmesa};
static const char *const backend_names[] = {"egl", "osmesa"};

/* A homogeneous cloud (no noise, h = 0) in front of a constant white sky with no sun and the sky-light term off:
 * each pixel is then exactly the transmittance T = exp(-k_e L) along its chord L. (With sky light on, a uniform sky
 * makes the cloud vanish: test_furnace.) */
#define BEER_SCENE                                                                                        \
    "[output]\nsize = 160 120\n[camera]\nposition = 40 230 -900\nlook_at = 10 260 0\nfov = 40\n"      \
    "[sun]\nelevation = 30\nirradiance = 0 0 0\n[sky]\nmodel = constant\ncolor = 1 1 1\n"              \
    "[cloud]\ndensity = 20\nboundary = 0\nphase = hg\ng = 0.85\n[quality]\nnoise = off\nsegments = 3\n"    \
    "[ms]\nsky_light = off\n"                     \
    "[ellipsoid]\ncenter = 0 250 0\nradii = 200 120 160\n"

/* Length of the union of the chords of a ray through a set of ellipsoids. */
static double union_chord(const cu_scene *s, vec3 o, vec3 d)
{
    double a[CU_MAX_ELLIPSOIDS], b[CU_MAX_ELLIPSOIDS];
    int n = 0;
    for (int i = 0; i < s->n_ellipsoids; i++) {
        double t0, t1;
        if (cu_ray_ellipsoid(o, d, v3_from(s->ell[i].center), v3_from(s->ell[i].radii), &t0, &t1) && t1 > 0) {
            a[n] = t0 > 0 ? t0 : 0;
            b[n] = t1;
            n++;
        }
    }
    for (int i = 1; i < n; i++) /* sort by entry */
        for (int j = i; j > 0 && a[j - 1] > a[j]; j--) {
            double ta = a[j], tb = b[j];
            a[j] = a[j - 1]; b[j] = b[j - 1];
            a[j - 1] = ta; b[j - 1] = tb;
        }
    double L = 0, end = -1e300;
    for (int i = 0; i < n; i++) {
        double lo = a[i] > end ? a[i] : end;
        if (b[i] > lo)
            L += b[i] - lo;
        if (b[i] > end)
            end = b[i];
    }
    return L;
}

static void check_beer(const char *scene_text, int be_index, double *max_err_out, int *edge_out)
{
    tr_ctx c;
    if (tr_open(&c, backends[be_index], 160, 120, 1) || tr_render(&c, scene_text, NULL))
        fail_msg("%s: %s", backend_names[be_index], c.err);
    float *px = malloc(sizeof(float) * 3 * 160 * 120);
    tr_read_rgbf(&c, px);
    cu_scene *s;
    cu_error e;
    assert_int_equal(cu_scene_parse(&s, "beer", scene_text, strlen(scene_text), &e), 0);
    double ke = cu_scene_core_extinction(s);
    double max_err = 0;
    int edge = 0, covered = 0;
    for (int y = 0; y < 120; y++)
        for (int x = 0; x < 160; x++) {
            vec3 d = tr_pixel_dir(s, 160, 120, x, y);
            double L = union_chord(s, v3_from(s->cam_pos), d);
            double T = exp(-ke * L);
            double got = px[(y * 160 + x) * 3 + 1];
            double err = fabs(got - T);
            /* Chords shorter than 10 m are within a fraction of a pixel of the silhouette, where L changes faster
             * than any pixel-centre convention can pin down; they are counted, not judged. */
            if (L > 10) {
                covered++;
                if (err > max_err) {
                    max_err = err;
                    if (getenv("CUMULO_TEST_DEBUG"))
                        printf("  worst so far: pixel %d,%d L %.2f expected %.5f got %.5f\n", x, y, L, T, got);
                }
            } else if (err > 0.01) {
                edge++;
            }
        }
    assert_true(covered > 2000);
    *max_err_out = max_err;
    *edge_out = edge;
    free(px);
    cu_scene_free(s);
    tr_close(&c);
}

static void test_beer_lambert_chords(void **st)
{
    (void)st;
    for (int b = 0; b < 2; b++) {
        double err;
        int edge;
        check_beer(BEER_SCENE, b, &err, &edge);
        printf("%s: Beer-Lambert max |T - exp(-k_e L)| = %.2e over chords > 10 m; %d edge pixels off by > 0.01\n",
               backend_names[b], err, edge);
        assert_true(err < 5e-5); /* fp32 trapezoids over a constant: exact but for rounding (measured 8.6e-6) */
        assert_true(edge < 40);
    }
}

static void test_overlap_integrated_once(void **st)
{
    (void)st;
    /* Two overlapping ellipsoids: the overlap must be integrated once (Kol's per-ellipsoid march counts it twice). */
    const char *t = BEER_SCENE "[ellipsoid]\ncenter = 120 290 30\nradii = 150 110 140\n";
    for (int b = 0; b < 2; b++) {
        double err;
        int edge;
        check_beer(t, b, &err, &edge);
        printf("%s: union of two overlapping ellipsoids: max error %.2e\n", backend_names[b], err);
        assert_true(err < 5e-5);
    }
}

static int has_non_finite(const float *p, long n)
{
    for (long i = 0; i < n; i++)
        if (!isfinite(p[i]))
            return 1;
    return 0;
}

static void test_empty_scene_is_sky(void **st)
{
    (void)st;
    static const char *const zero[] = {"cloud.density=0", NULL};
    static const char *const away[] = {"ellipsoid.1.center=0 250 -5000", "ellipsoid.2.center=100 250 -5000",
                                       "ellipsoid.3.center=-100 250 -5000", "ellipsoid.4.center=0 350 -5000",
                                       "ellipsoid.5.center=0 150 -5000", "ellipsoid.6.center=50 250 -5000",
                                       "ellipsoid.7.center=-50 250 -5000", "ellipsoid.8.center=0 200 -5000", NULL};
    for (int b = 0; b < 2; b++) {
        tr_ctx c;
        if (tr_open(&c, backends[b], 128, 96, 1))
            fail_msg("%s", c.err);
        size_t n = 128 * 96 * 3;
        float *a = malloc(sizeof(float) * n), *bb = malloc(sizeof(float) * n);
        if (tr_render(&c, "scenes/cumulus.scene", zero))
            fail_msg("%s", c.err);
        tr_read_rgbf(&c, a);
        if (tr_render(&c, "scenes/cumulus.scene", away))
            fail_msg("%s", c.err);
        tr_read_rgbf(&c, bb);
        assert_memory_equal(a, bb, sizeof(float) * n);
        assert_false(has_non_finite(a, (long)n));
        /* constant sky: every pixel is the sky colour, bit for bit */
        if (tr_render(&c, BEER_SCENE, zero))
            fail_msg("%s", c.err);
        tr_read_rgbf(&c, a);
        for (size_t i = 0; i < n; i++)
            if (a[i] != 1.0f)
                fail_msg("%s: pixel value %g at %zu, sky is 1", backend_names[b], a[i], i);
        free(a);
        free(bb);
        tr_close(&c);
    }
}

/* A frame with no cloud in view draws its sky straight into the output, tone-mapped in the same pass (frame.c); with
 * a cloud in view the sky goes through the HDR target and the tone map. The sky above the cloud must not tell them
 * apart: within 1/255 (the half-float target's rounding), on both back ends. */
static void test_sky_alone_in_one_pass(void **st)
{
    (void)st;
    static const char *const none[] = {"cloud.density=0", NULL};
    const int w = 128, h = 96, rows = 12; /* the cloud starts lower (cumulus.scene's camera looks up at it) */
    for (int b = 0; b < 2; b++) {
        tr_ctx c;
        if (tr_open(&c, backends[b], w, h, 0))
            fail_msg("%s", c.err);
        uint8_t *with = malloc((size_t)w * h * 4), *alone = malloc((size_t)w * h * 4);
        if (tr_render(&c, "scenes/cumulus.scene", NULL))
            fail_msg("%s", c.err);
        tr_read_rgba8(&c, with);
        if (tr_render(&c, "scenes/cumulus.scene", none))
            fail_msg("%s", c.err);
        tr_read_rgba8(&c, alone);
        int worst = 0, differ = 0;
        for (int i = 0; i < w * h * 4; i++) {
            int d = abs((int)with[i] - (int)alone[i]);
            differ += d > 0;
            if (i < rows * w * 4 && d > worst)
                worst = d;
        }
        printf("%s: sky above the cloud, one pass against two: max difference %d/255 over %d rows; %d values differ "
               "in the whole frame\n", backend_names[b], worst, rows, differ);
        assert_true(worst <= 1);
        assert_true(differ > 100); /* the frames are not the same: one has the cloud */
        free(with);
        free(alone);
        tr_close(&c);
    }
}

static void test_furnace(void **st)
{
    (void)st;
    /* Non-absorbing droplets in a uniform environment and no sun: whatever the cloud, every pixel must come out as
     * the environment (what is scattered in replaces what is scattered out). */
    static const char *const furnace[] = {"sky.model=constant", "sky.color=0.3 0.5 0.9", "sun.irradiance=0 0 0", NULL};
    const float sky[3] = {0.3f, 0.5f, 0.9f};
    for (int b = 0; b < 2; b++) {
        tr_ctx c;
        if (tr_open(&c, backends[b], 96, 72, 1))
            fail_msg("%s", c.err);
        float *px = malloc(sizeof(float) * 96 * 72 * 3);
        double worst = 0;
        for (size_t sc = 0; sc < 2; sc++) {
            if (tr_render(&c, sc ? "scenes/inside.scene" : "scenes/cumulus.scene", furnace))
                fail_msg("%s", c.err);
            tr_read_rgbf(&c, px);
            for (long i = 0; i < 96 * 72 * 3; i++)
                worst = fmax(worst, fabs(px[i] - sky[i % 3]) / sky[i % 3]);
        }
        printf("%s furnace: max relative deviation %.2e\n", backend_names[b], worst);
        assert_true(worst < 1e-4);
        free(px);
        tr_close(&c);
    }
}

/* A homogeneous ellipsoid (no noise, h = 0), optically thick (tau 20-40 along its chords), lit by the sun alone: the
 * sunlit source falls exponentially along each segment, which the energy-conserving segments (default) integrate
 * exactly and Kol's trapezoids of k_e S e^-tau (eq. 3.20) overestimate by (dtau/2) coth(dtau/2). */
#define THICK_SCENE                                                                                     \
    "[output]\nsize = 128 96\n[camera]\nposition = 40 230 -900\nlook_at = 10 260 0\nfov = 40\n"         \
    "[sun]\nelevation = 30\nazimuth = 200\n[sky]\nmodel = constant\ncolor = 0 0 0\n"                     \
    "[cloud]\ndensity = 400\nboundary = 0\nphase = hg\ng = 0.85\n[quality]\nnoise = off\n"                \
    "[ms]\nsky_light = off\nmode = none\n[ellipsoid]\ncenter = 0 250 0\nradii = 200 120 160\n"

static void test_segment_integration(void **st)
{
    (void)st;
    /* Three segments against the converged image: 64 even segments (a geometric 48 is no reference: at ratio 1.6
     * its last segments span most of the chord). Measured RMSE 0.12 (energy-conserving) against 0.71 (Kol's
     * trapezoids), mean radiance 0.076. On the noisy default cumulus the two are alike (0.055 and 0.033): there the
     * error is the noise's sampling, not the segments' integration. */
    static const char *const ref[] = {"quality.segments=64", "quality.segment_ratio=1", NULL};
    static const char *const exp3[] = {"quality.segments=3", NULL};
    static const char *const kol3[] = {"quality.segments=3", "quality.integration=kol", NULL};
    const char *const *sets[3] = {ref, exp3, kol3};
    tr_ctx c;
    if (tr_open(&c, &cu_display_egl, 128, 96, 1))
        fail_msg("%s", c.err);
    long n = 128 * 96 * 3;
    float *img[3];
    for (int k = 0; k < 3; k++) {
        img[k] = malloc(sizeof(float) * (size_t)n);
        if (tr_render(&c, THICK_SCENE, sets[k]))
            fail_msg("%s", c.err);
        tr_read_rgbf(&c, img[k]);
    }
    double e[2] = {0, 0};
    for (int k = 1; k < 3; k++) {
        for (long i = 0; i < n; i++)
            e[k - 1] += ((double)img[k][i] - img[0][i]) * ((double)img[k][i] - img[0][i]);
        e[k - 1] = sqrt(e[k - 1] / n);
    }
    printf("3 segments vs 64 even ones, a thick homogeneous cloud: RMSE %.4f energy-conserving, %.4f Kol trapezoids\n",
           e[0], e[1]);
    assert_true(e[0] < 0.5 * e[1]);
    for (int k = 0; k < 3; k++)
        free(img[k]);
    tr_close(&c);
}

static const char *const test_scenes[] = {"scenes/cumulus.scene", "scenes/silver_lining.scene", "scenes/inside.scene",
                                          "scenes/low_sun.scene"};

static void test_no_nan_in_any_scene(void **st)
{
    (void)st;
    static const char *const variants[][3] = {
        {NULL}, {"ms.mode=octaves", NULL}, {"ms.mode=none", NULL}, {"cloud.profile=kol", NULL},
        {"quality.integration=kol", "light.shadow=front", NULL},
        {"cloud.phase=hg", "cloud.g=0.99", NULL}, {"cloud.boundary=0", NULL}, {"quality.segment_ratio=1", NULL},
        {"ms.mode=collector", "light.shadow=osm", NULL}, {"light.shadow=fom", NULL}};
    for (int b = 0; b < 2; b++) {
        tr_ctx c;
        if (tr_open(&c, backends[b], 96, 72, 1))
            fail_msg("%s", c.err);
        float *px = malloc(sizeof(float) * 96 * 72 * 3);
        for (size_t s = 0; s < sizeof test_scenes / sizeof test_scenes[0]; s++)
            for (size_t v = 0; v < sizeof variants / sizeof variants[0]; v++) {
                if (tr_render(&c, test_scenes[s], variants[v]))
                    fail_msg("%s %s: %s", backend_names[b], test_scenes[s], c.err);
                tr_read_rgbf(&c, px);
                if (has_non_finite(px, 96 * 72 * 3))
                    fail_msg("%s: NaN/Inf in %s with %s", backend_names[b], test_scenes[s],
                             variants[v][0] ? variants[v][0] : "defaults");
                for (long i = 0; i < 96 * 72 * 3; i++)
                    assert_true(px[i] >= 0.0f);
            }
        free(px);
        tr_close(&c);
    }
}

static double band_mean(const double *sum, const int *cnt, double a, double b)
{
    double s = 0;
    int n = 0;
    for (int i = (int)(a * 2.0); i < (int)(b * 2.0) && i <= 360; i++) {
        s += sum[i];
        n += cnt[i];
    }
    return n ? s / n : 0;
}

static double mean_abs_diff(const float *a, const float *b, long n)
{
    double s = 0;
    for (long i = 0; i < n; i++)
        s += fabs((double)a[i] - b[i]);
    return s / n;
}

static void test_camera_into_cloud_is_continuous(void **st)
{
    (void)st;
    /* Walk the camera in 2 m steps, looking into the cloud of the inside scene, from 60 m outside its surface to 60 m
     * inside.
     * On the way it crosses the hull (where the cloud pass switches from hull rasterisation to a full-screen
     * triangle) and the cloud surface itself. No step may change the image much more than the steps around it. */
    cu_scene *s;
    cu_error e;
    assert_int_equal(cu_scene_load(&s, "scenes/inside.scene", &e), 0);
    tr_ctx c;
    if (tr_open(&c, &cu_display_egl, 96, 72, 1))
        fail_msg("%s", c.err);
    const int N = 61;
    long n = 96 * 72 * 3;
    float *prev = malloc(sizeof(float) * n), *cur = malloc(sizeof(float) * n);
    double diffs[64];
    for (int k = 0; k < N; k++) {
        double z = -260 + 2.0 * k; /* the ellipsoid's surface is at z = -200 */
        s->cam_pos[2] = z;
        s->cam_look[2] = z + 300;
        if (tr_render_scene(&c, s))
            fail_msg("%s", c.err);
        tr_read_rgbf(&c, cur);
        assert_false(has_non_finite(cur, n));
        if (k > 0)
            diffs[k - 1] = mean_abs_diff(prev, cur, n);
        float *t = prev; prev = cur; cur = t;
    }
    /* A discontinuity is one step much larger than both its neighbours; a smooth change inside the cloud (the
     * multiply scattered radiance at the camera's depth, which the slab model varies with depth) is steps that
     * grow together. */
    double worst = 0, at = 0, med_sorted[64];
    memcpy(med_sorted, diffs, sizeof(double) * (N - 1));
    for (int i = 1; i < N - 1; i++)
        for (int j = i; j > 0 && med_sorted[j - 1] > med_sorted[j]; j--) {
            double t = med_sorted[j]; med_sorted[j] = med_sorted[j - 1]; med_sorted[j - 1] = t;
        }
    for (int k = 0; k < N - 1; k++) {
        double around = fmax(k > 0 ? diffs[k - 1] : 0, k < N - 2 ? diffs[k + 1] : 0);
        double ratio = diffs[k] / (around + 1e-3);
        if (ratio > worst) {
            worst = ratio;
            at = -260 + 2.0 * (k + 1);
        }
    }
    printf("camera walk into the cloud: median step change %.4f, largest %.4f (radiance units); largest step / "
           "larger neighbour %.2f (at z = %.0f m)\n", med_sorted[(N - 1) / 2], med_sorted[N - 2], worst, at);
    assert_true(worst <= 4.0);
    free(prev);
    free(cur);
    tr_close(&c);
    cu_scene_free(s);
}

/* Reference images: tone-mapped 8-bit renders at 160x120 committed under tests/ref/ (regenerate with
 * `make refs` after an intended change, and look at them). Tolerances: llvmpipe's results move with the CPU's
 * vector width, so we compare statistics, never hashes: PSNR >= 38 dB, at most 0.5% of pixels off by more than
 * 6/255 in any channel, no channel off by more than 48/255. */
#define REF_W 160
#define REF_H 120

static void test_reference_images(void **st)
{
    (void)st;
    int regenerate = getenv("CUMULO_WRITE_REFS") != NULL;
    uint8_t *got[2];
    for (size_t s = 0; s < sizeof test_scenes / sizeof test_scenes[0]; s++) {
        const char *base = strrchr(test_scenes[s], '/') + 1;
        char name[128], refpath[256];
        snprintf(name, sizeof name, "%.*s", (int)(strlen(base) - 6), base);
        snprintf(refpath, sizeof refpath, "tests/ref/%s.png", name);
        for (int b = 0; b < 2; b++) {
            tr_ctx c;
            if (tr_open(&c, backends[b], REF_W, REF_H, 0) || tr_render(&c, test_scenes[s], NULL))
                fail_msg("%s %s: %s", backend_names[b], name, c.err);
            got[b] = malloc(4 * REF_W * REF_H);
            tr_read_rgba8(&c, got[b]);
            tr_close(&c);
        }
        cu_error err;
        if (regenerate) {
            if (cu_write_png(refpath, got[0], REF_W, REF_H, &err))
                fail_msg("%s", err.msg);
            printf("wrote %s\n", refpath);
        }
        cu_image ref;
        if (cu_png_read(refpath, &ref, &err))
            fail_msg("%s (run `make refs` to create references)", err.msg);
        assert_int_equal(ref.width, REF_W);
        assert_int_equal(ref.height, REF_H);
        for (int b = 0; b < 2; b++) {
            tr_diff d = tr_compare_rgba8(got[b], ref.px8, REF_W, REF_H, 6);
            printf("%-14s %-7s vs reference: PSNR %.1f dB, %.3f%% pixels > 6/255, max %d/255\n", name,
                   backend_names[b], d.psnr, 100 * d.frac_over, d.max_diff);
            if (d.psnr < 38 || d.frac_over > 0.005 || d.max_diff > 48) {
                char tag[160];
                snprintf(tag, sizeof tag, "%s-%s", name, backend_names[b]);
                tr_save_failure(tag, got[b], ref.px8, REF_W, REF_H);
                fail_msg("%s on %s differs from %s (images in build/test-output/)", name, backend_names[b], refpath);
            }
        }
        tr_diff d = tr_compare_rgba8(got[0], got[1], REF_W, REF_H, 6);
        printf("%-14s egl vs osmesa: PSNR %.1f dB, max %d/255\n", name, d.psnr, d.max_diff);
        if (d.psnr < 40 || d.max_diff > 32) {
            tr_save_failure(name, got[1], got[0], REF_W, REF_H);
            fail_msg("%s: EGL and OSMesa disagree", name);
        }
        cu_image_free(&ref);
        free(got[0]);
        free(got[1]);
    }
}

static void test_glory_and_fogbow(void **st)
{
    (void)st;
    /* A thin cloud seen around the antisolar point with the Mie table: radiance against the scattering angle must
     * rise into the glory at 180 degrees and peak in the fogbow near 140 degrees (Kol Fig. 4.9-4.10). */
    const int W = 320, H = 240;
    tr_ctx c;
    if (tr_open(&c, &cu_display_egl, W, H, 1) || tr_render(&c, "scenes/glory.scene", NULL))
        fail_msg("%s", c.err);
    float *px = malloc(sizeof(float) * 3 * (size_t)W * H);
    tr_read_rgbf(&c, px);
    tr_close(&c);
    cu_scene *s;
    cu_error e;
    assert_int_equal(cu_scene_load(&s, "scenes/glory.scene", &e), 0);
    vec3 sun = cu_sun_direction(s->sun_elevation, s->sun_azimuth);
    double sum[361] = {0};
    int cnt[361] = {0};
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            vec3 d = tr_pixel_dir(s, W, H, x, y);
            /* cos(Theta) = s_L . v with s_L = -sun, v = -d (from the sample toward the eye) */
            double th = acos(fmax(-1.0, fmin(1.0, v3_dot(sun, d)))) * 180.0 / CU_PI;
            int b = (int)(th * 2.0);
            const float *p = px + ((size_t)y * W + x) * 3;
            sum[b] += 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
            cnt[b]++;
        }
    /* mean luminance over [a, b) degrees */
#define BAND(a, b) band_mean(sum, cnt, (a), (b))
    double glory = BAND(179.0, 180.1), below_glory = BAND(172.0, 176.0);
    double best = 0, best_th = 0;
    for (double t = 130.0; t < 152.0; t += 0.5) {
        double v = BAND(t, t + 1.0);
        if (v > best) {
            best = v;
            best_th = t + 0.5;
        }
    }
    double inside = BAND(150.0, 158.0), outside = BAND(122.0, 128.0);
    printf("glory: mean luminance %.3f at 179-180 deg vs %.3f at 172-176 deg\n", glory, below_glory);
    printf("fogbow: peak %.3f at %.1f deg vs %.3f at 150-158 deg and %.3f at 122-128 deg\n", best, best_th, inside,
           outside);
    assert_true(glory > 1.05 * below_glory);
    assert_true(best_th > 134 && best_th < 146);
    assert_true(best > 1.02 * inside && best > 1.02 * outside);
#undef BAND
    free(px);
    cu_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_beer_lambert_chords),   cmocka_unit_test(test_overlap_integrated_once),
        cmocka_unit_test(test_empty_scene_is_sky),    cmocka_unit_test(test_sky_alone_in_one_pass),    cmocka_unit_test(test_no_nan_in_any_scene),
        cmocka_unit_test(test_camera_into_cloud_is_continuous), cmocka_unit_test(test_reference_images),
        cmocka_unit_test(test_glory_and_fogbow),      cmocka_unit_test(test_furnace),
        cmocka_unit_test(test_segment_integration),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
