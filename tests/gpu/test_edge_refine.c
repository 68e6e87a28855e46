/* tests/gpu/test_edge_refine.c: quality.edge_refine (src/gpu/pass_refine.c), the pixels a half-resolution cloud image
 * blurs marched again at full resolution. Against the full-resolution render of the same settings (medium: low is
 * medium at half resolution), through both composites (linear output: upsample.frag; tone-mapped: the sky pass's
 * one-pass composite):
 * - a threshold near 0 marks every pixel a cloud reaches: the picture is the full-resolution one (a lone cloud: to
 *   rounding; a field with many clouds: the marks survive each cloud's clear of depth and stencil);
 * - a threshold of 1 marks nothing: the picture is low's, bit for bit (the unmarked pixels' sentinel never leaks);
 * - in between the error against full resolution falls as the threshold falls, and 0.3 already removes most of low's
 *   on the silver lining's thin bright rim, the view where half resolution fails (docs/methods.md);
 * - the camera inside a cloud (the full-screen cloud pass, whose stencil test is the refinement's own). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "render_util.h"

#define W 160
#define H 120

/* Renders scene with the preset and the extra settings (NULL-terminated, at most 4) into linear rgb or RGBA8. */
static void render(const char *scene, const char *preset, const char *const *extra, int linear, float *rgb,
                   uint8_t *rgba)
{
    const char *sets[8] = {preset};
    int n = 1;
    for (int i = 0; extra && extra[i] && n < 7; i++)
        sets[n++] = extra[i];
    sets[n] = NULL;
    tr_ctx c;
    if (tr_open(&c, &cu_display_egl, W, H, linear) || tr_render(&c, scene, sets))
        fail_msg("%s: %s", scene, c.err);
    if (linear)
        tr_read_rgbf(&c, rgb);
    else
        tr_read_rgba8(&c, rgba);
    tr_close(&c);
}

typedef struct diff {
    double rel_rmse;  /* over the pixels where either image differs from the sky by 1 % (the cloud's) */
    double worst;     /* the largest |a - b| / (|b| + 1e-3) of any channel */
    int off;          /* pixels with a channel off by more than 1 % of its value */
    int cloud;        /* the pixels of rel_rmse */
    double mean_abs;  /* mean |a - b| over every channel of every pixel */
} diff;

/* a against the full-resolution b, linear; sky: a pixel's value where no cloud is (the corner's, far from any) */
static diff compare(const float *a, const float *b)
{
    diff d = {0, 0, 0, 0, 0};
    double se = 0, sr = 0;
    const float *sky = b; /* pixel (0, 0) of the top row: sky in every view used here */
    for (int i = 0; i < W * H; i++) {
        int is_cloud = 0, is_off = 0;
        for (int k = 0; k < 3; k++) {
            float x = a[3 * i + k], y = b[3 * i + k];
            assert_true(isfinite(x));
            double e = fabs((double)x - y), r = e / (fabs(y) + 1e-3);
            d.mean_abs += e / (3.0 * W * H);
            d.worst = r > d.worst ? r : d.worst;
            is_off |= r > 0.01;
            is_cloud |= fabs(y - sky[k]) > 0.01 * sky[k] || fabs(x - sky[k]) > 0.01 * sky[k];
        }
        d.off += is_off;
        /* the sun's disk (radiance = irradiance / 6.8e-5 sr, 10^4 and more of the sky's) is not cloud */
        int disk = b[3 * i + 1] > 1000.0f * sky[1];
        if (is_cloud && !disk) {
            d.cloud++;
            for (int k = 0; k < 3; k++) {
                se += ((double)a[3 * i + k] - b[3 * i + k]) * ((double)a[3 * i + k] - b[3 * i + k]);
                sr += (double)b[3 * i + k] * b[3 * i + k];
            }
        }
    }
    d.rel_rmse = sr > 0 ? sqrt(se / sr) : 0;
    return d;
}

static const char *const TINY[] = {"quality.edge_refine=0.000001", NULL};
static const char *const NONE[] = {"quality.edge_refine=1", NULL};

/* Near 0 every pixel a cloud reaches is marked: low with it is medium, through the linear composite to fp32
 * rounding and through the one-pass composite to 1/255 (its RGBA16F image, as test_composite's bound); low alone
 * differs on hundreds of pixels, so the comparison can fail. The refinement draws each cloud as one full-screen
 * triangle, whose rays come from the unprojected pixel rather than the hull's interpolated point: fp32 rounding of
 * the direction, 1.1e-4 of a pixel's value at most (measured), bound 1e-3. */
static void test_tiny_threshold_is_full_resolution(void **st)
{
    (void)st;
    const char *scenes[] = {"scenes/sweep_silver_lining_hg.scene", "scenes/cumulus.scene"};
    float *full = malloc(sizeof(float) * 3 * W * H), *got = malloc(sizeof(float) * 3 * W * H);
    uint8_t *full8 = malloc((size_t)W * H * 4), *got8 = malloc((size_t)W * H * 4);
    assert_true(full && got && full8 && got8);
    for (int s = 0; s < 2; s++) {
        render(scenes[s], "quality.preset=medium", NULL, 1, full, NULL);
        render(scenes[s], "quality.preset=low", NULL, 1, got, NULL);
        diff low = compare(got, full);
        render(scenes[s], "quality.preset=low", TINY, 1, got, NULL);
        diff tiny = compare(got, full);
        printf("%s: linear: low %d pixels off by > 1 %% (worst %.3g), edge_refine 1e-6 %d (worst %.3g)\n", scenes[s],
               low.off, low.worst, tiny.off, tiny.worst);
        assert_true(low.off > 100);
        assert_int_equal(tiny.off, 0);
        assert_true(tiny.worst < 1e-3);
        render(scenes[s], "quality.preset=medium", NULL, 0, NULL, full8);
        render(scenes[s], "quality.preset=low", NULL, 0, NULL, got8);
        tr_diff low8 = tr_compare_rgba8(got8, full8, W, H, 1);
        render(scenes[s], "quality.preset=low", TINY, 0, NULL, got8);
        tr_diff tiny8 = tr_compare_rgba8(got8, full8, W, H, 1);
        printf("%s: tone-mapped: low max %d/255 (%.4f of pixels over 1), edge_refine 1e-6 max %d/255\n", scenes[s],
               low8.max_diff, low8.frac_over, tiny8.max_diff);
        assert_true(low8.frac_over > 0.001);
        assert_true(tiny8.max_diff <= 1);
        if (tiny8.max_diff > 1)
            tr_save_failure("edge_refine_tiny", got8, full8, W, H);
    }
    free(full);
    free(got);
    free(full8);
    free(got8);
}

/* scene with `setting` (NULL: none): medium's frame, and low's and low's with edge_refine 1e-6 against it (linear). */
static void low_and_refined(const char *scene, const char *setting, diff *low, diff *refined)
{
    const char *const plain[] = {setting, NULL}, *const tiny[] = {setting ? setting : TINY[0], setting ? TINY[0] : NULL,
                                                                   NULL};
    float *full = malloc(sizeof(float) * 3 * W * H), *got = malloc(sizeof(float) * 3 * W * H);
    assert_true(full && got);
    render(scene, "quality.preset=medium", plain, 1, full, NULL);
    render(scene, "quality.preset=low", plain, 1, got, NULL);
    *low = compare(got, full);
    render(scene, "quality.preset=low", tiny, 1, got, NULL);
    *refined = compare(got, full);
    free(full);
    free(got);
}

/* Many clouds drawn one after another into the refinement target, each clearing the depth and stencil it used:
 * the marks must outlive those clears. Impostors off (the default, set so that another default cannot change what
 * this tests: their images are made at the cloud pass's resolution, so they differ between low and medium by
 * design). At most a few pixels may differ: a cloud smaller than a low-resolution texel that the half-resolution pass
 * missed entirely leaves no neighbour to differ (measured: 1 pixel of 19200). */
static void test_field_keeps_marks(void **st)
{
    (void)st;
    diff low, ref;
    low_and_refined("scenes/field_noon.scene", "quality.impostor_pixels=0", &low, &ref);
    printf("field: low %d pixels off by > 1 %%, edge_refine 1e-6 %d; cloud rel. RMSE %.4f -> %.5f\n", low.off,
           ref.off, low.rel_rmse, ref.rel_rmse);
    assert_true(low.off > 1000);
    assert_true(ref.off <= 5);
    assert_true(ref.rel_rmse < 0.01 * low.rel_rmse);
}

/* Clouds drawn from impostors (quality.impostor_pixels) among them: each impostor is drawn into the refinement
 * target over every pixel it may touch, not the rectangle of the cloud drawn before it (which once cut it off). The
 * impostors' images are made at the cloud pass's resolution, so low's differ from medium's by design: near 0 the
 * frame must still come far nearer medium's than low's does (measured at 160x120: mean |difference| 0.031
 * against low's 0.169; with the impostors cut off, 0.180). */
static void test_field_impostors(void **st)
{
    (void)st;
    diff low, ref;
    low_and_refined("scenes/field_noon.scene", "quality.impostor_pixels=48", &low, &ref);
    printf("field with impostors: mean |difference| from medium: low %.4g, edge_refine 1e-6 %.4g\n", low.mean_abs,
           ref.mean_abs);
    assert_true(low.mean_abs > 0);
    assert_true(ref.mean_abs < 0.25 * low.mean_abs);
}

/* A threshold of 1 marks nothing (neither measure can exceed it): the frame is low's, bit for bit, through both
 * composites. */
static void test_no_marks_is_low(void **st)
{
    (void)st;
    const char *scene = "scenes/sweep_silver_lining_hg.scene";
    float *low = malloc(sizeof(float) * 3 * W * H), *got = malloc(sizeof(float) * 3 * W * H);
    uint8_t *low8 = malloc((size_t)W * H * 4), *got8 = malloc((size_t)W * H * 4);
    assert_true(low && got && low8 && got8);
    render(scene, "quality.preset=low", NULL, 1, low, NULL);
    render(scene, "quality.preset=low", NONE, 1, got, NULL);
    assert_memory_equal(low, got, sizeof(float) * 3 * W * H);
    render(scene, "quality.preset=low", NULL, 0, NULL, low8);
    render(scene, "quality.preset=low", NONE, 0, NULL, got8);
    assert_memory_equal(low8, got8, (size_t)W * H * 4);
    free(low);
    free(got);
    free(low8);
    free(got8);
}

/* The trade: the error against full resolution on the silver lining (low's worst view) falls with the threshold.
 * Measured at 160x120 on llvmpipe (cloud rel. RMSE against medium; the sun's disk left out): low 0.51, 0.6 -> 0.066,
 * 0.3 -> 0.0061, 0.1 -> 0.0023. The bounds: 0.6 removes half of low's error, 0.3 nine tenths, 0.1 at least as
 * much as 0.3 (a margin of 2 %). */
static void test_error_falls_with_threshold(void **st)
{
    (void)st;
    const char *scene = "scenes/sweep_silver_lining_hg.scene";
    float *full = malloc(sizeof(float) * 3 * W * H), *got = malloc(sizeof(float) * 3 * W * H);
    assert_true(full && got);
    render(scene, "quality.preset=medium", NULL, 1, full, NULL);
    const char *t[] = {NULL, "quality.edge_refine=0.6", "quality.edge_refine=0.3", "quality.edge_refine=0.1"};
    double e[4];
    for (int i = 0; i < 4; i++) {
        const char *extra[] = {t[i], NULL};
        render(scene, "quality.preset=low", t[i] ? extra : NULL, 1, got, NULL);
        diff d = compare(got, full);
        e[i] = d.rel_rmse;
        printf("silver lining: %s: cloud rel. RMSE against full resolution %.4f over %d pixels\n",
               t[i] ? t[i] : "low", e[i], d.cloud);
        assert_true(d.cloud > 500);
    }
    assert_true(e[0] > 0.05);
    assert_true(e[1] < 0.5 * e[0]);
    assert_true(e[2] < 0.1 * e[0]);
    assert_true(e[3] <= 1.02 * e[2]);
    free(full);
    free(got);
}

/* Inside a cloud the cloud pass is one full-screen triangle, tested against the marks by its own stencil state: near
 * 0 the picture comes within a tenth of low's mean difference from medium, and within 0.5 % anywhere (measured:
 * low's mean |difference| 1.0e-4, refined 1.1e-6; the rest are pixels whose four texels are equal). */
static void test_inside(void **st)
{
    (void)st;
    diff low, tiny;
    low_and_refined("scenes/inside.scene", NULL, &low, &tiny);
    printf("inside: mean |difference| from medium: low %.3g, edge_refine 1e-6 %.3g (worst relative %.3g)\n",
           low.mean_abs, tiny.mean_abs, tiny.worst);
    assert_true(low.mean_abs > 0);
    assert_true(tiny.mean_abs < 0.1 * low.mean_abs);
    assert_true(tiny.worst < 0.005);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_tiny_threshold_is_full_resolution),
        cmocka_unit_test(test_field_keeps_marks),
        cmocka_unit_test(test_field_impostors),
        cmocka_unit_test(test_no_marks_is_low),
        cmocka_unit_test(test_error_falls_with_threshold),
        cmocka_unit_test(test_inside),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
