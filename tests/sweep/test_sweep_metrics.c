/* tests/sweep/test_sweep_metrics.c: the sweep's cloud metrics (tools/sweep/metrics.c) on images made here, whose
 * answers are known: the reference itself (error 0, every fifth 1, its own contrast), the reference doubled (every
 * fifth 2), the brightest fifth's pixels tripled (the darkest three fifths do not move), a flattened picture (the
 * cloud's mean everywhere: above 1 in the dark fifths, below in the bright ones, while its mean light is right), and
 * the mask leaving the sky out. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sweep.h"

#define W 40
#define H 30
#define NPX (W * H)

/* sweep.c's comparator: metrics.c sorts with it (the rest of sweep.c needs a GL context). */
int sw_cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static sweep sw;
static view v;
static float ref[NPX * 3], sky[NPX * 3], img[NPX * 3];

/* A cloud whose brightness rises linearly from left to right (2 .. 20), the same down each column: its box-filtered
 * luminance is as monotone in x as it is, so the fifths are sets of whole columns. ellipse = 0: the cloud fills the
 * view over a black sky; 1: it fills an ellipse, a grey sky of 1 around it. */
static void setup_view(int ellipse)
{
    memset(&sw, 0, sizeof sw);
    memset(&v, 0, sizeof v);
    sw.ew = W;
    sw.eh = H;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double dx = (x - 19.5) / 16.0, dy = (y - 14.5) / 11.0;
            float s = ellipse ? 1.0f : 0.0f, c = (float)(2.0 + 18.0 * x / (W - 1));
            if (ellipse && dx * dx + dy * dy >= 1)
                c = s;
            for (int k = 0; k < 3; k++) {
                sky[3 * (y * W + x) + k] = s;
                ref[3 * (y * W + x) + k] = c;
            }
        }
    v.ref.width = W;
    v.ref.height = H;
    v.ref.channels = 3;
    v.ref.pxf = ref;
    v.exposure = 0.1;
    for (int k = 0; k < 3; k++) {
        v.white[k] = 1;
        v.clip[k] = 1e30;
    }
    assert_int_equal(sw_view_mask(&sw, &v, sky), 0);
}

static void teardown_view(void)
{
    free(v.mask);
    v.mask = NULL;
}

static result measure(void)
{
    result r;
    memset(&r, 0, sizeof r);
    sw_cloud_metrics(&sw, &v, img, &r);
    return r;
}

static void test_the_reference_itself(void **st)
{
    (void)st;
    setup_view(0);
    memcpy(img, ref, sizeof img);
    result r = measure();
    assert_true(r.cloud_rel_rmse == 0);
    assert_true(fabs(r.contrast - v.ref_contrast) < 1e-12 && v.ref_contrast > 3);
    for (int k = 0; k < SW_FIFTHS; k++)
        assert_true(fabs(r.fifths[k] - 1) < 1e-12);
    for (int k = 1; k < SW_FIFTHS - 1; k++)
        assert_true(v.fifth_edge[k] > v.fifth_edge[k - 1]);
    teardown_view();
}

static void test_twice_the_light(void **st)
{
    (void)st;
    setup_view(0);
    for (int i = 0; i < NPX * 3; i++)
        img[i] = 2 * ref[i];
    result r = measure();
    for (int k = 0; k < SW_FIFTHS; k++)
        assert_true(fabs(r.fifths[k] - 2) < 1e-9);
    teardown_view();
}

/* The brightest fifth's columns tripled: the three darkest fifths do not move, the brightest nearly triples (the
 * filter mixes one column of the fourth fifth into its edge, and that fifth moves a little). */
static void test_one_fifth_changed(void **st)
{
    (void)st;
    setup_view(0);
    for (int p = 0; p < NPX; p++)
        for (int k = 0; k < 3; k++)
            img[3 * p + k] = ref[3 * p + k] * (ref[3 * p] > v.fifth_edge[SW_FIFTHS - 2] ? 3.0f : 1.0f);
    result r = measure();
    for (int k = 0; k < SW_FIFTHS - 2; k++)
        assert_true(fabs(r.fifths[k] - 1) < 1e-9);
    assert_true(r.fifths[SW_FIFTHS - 1] > 2.5 && r.fifths[SW_FIFTHS - 1] <= 3.0 + 1e-9);
    assert_true(r.fifths[SW_FIFTHS - 2] >= 1.0 && r.fifths[SW_FIFTHS - 2] < 1.5);
    teardown_view();
}

/* Every cloud pixel at the cloud's mean: the light is right on the whole, and misplaced. */
static void test_flattened_picture(void **st)
{
    (void)st;
    setup_view(0);
    double sum = 0;
    int n = 0;
    for (int p = 0; p < NPX; p++) {
        sum += ref[3 * p];
        n++;
    }
    for (int p = 0; p < NPX; p++)
        for (int k = 0; k < 3; k++)
            img[3 * p + k] = (float)(sum / n);
    result r = measure();
    assert_true(r.fifths[0] > 1.5 && r.fifths[SW_FIFTHS - 1] < 0.8);
    for (int k = 1; k < SW_FIFTHS; k++)
        assert_true(r.fifths[k] < r.fifths[k - 1]);
    assert_true(r.contrast < 1.001 && v.ref_contrast > 3);
    teardown_view();
}

static void test_the_mask_is_the_cloud(void **st)
{
    (void)st;
    setup_view(1);
    int n = 0;
    for (int p = 0; p < NPX; p++) {
        int cloud = ref[3 * p] > 1.5f;
        assert_int_equal(v.mask[p], cloud);
        n += cloud;
    }
    assert_int_equal(v.mask_n, n);
    teardown_view();
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_the_reference_itself), cmocka_unit_test(test_twice_the_light),
        cmocka_unit_test(test_one_fifth_changed),   cmocka_unit_test(test_flattened_picture),
        cmocka_unit_test(test_the_mask_is_the_cloud),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
