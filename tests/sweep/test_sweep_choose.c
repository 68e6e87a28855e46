/* tests/sweep/test_sweep_choose.c: how the sweep picks presets (tools/sweep/choose.c) from measurements made up here:
 * by the error on the cloud's pixels (result.error), not the whole image's, and never a point flatter than high
 * (sw_flatter: contrast further off, or SSIM lower), in the pick and in the greedy descent alike. Two variants of
 * ms.mode stand in for the sweep's table: "octaves", faster and with the smaller error, and "collector". And
 * ms.mode = diffusion, whose CPU solves the sweep's static frames do not time, is a preset only when the timed
 * frames turn the sun (--sun-step 0.5 or more: then they hold the solves). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <stdio.h>
#include <string.h>
#include "sweep.h"

static int k_ms, j_oct, j_col, measured_octaves, measures;
static result agg[3]; /* 0 high, 1 ms.mode = octaves, 2 ms.mode = collector */
static int vidx[SW_NKNOBS * SW_MAX_VALUES];

/* measure.c's, without GL: a combination measures as the one-knob variant of its ms.mode (the only knob changed). */
int sw_measure_config(sweep *sw, const config *c, const char *kind, const char *label, result *out)
{
    (void)sw, (void)kind, (void)label;
    measures++;
    if (c->v[k_ms] == j_oct)
        measured_octaves = 1;
    *out = c->v[k_ms] == j_oct ? agg[1] : c->v[k_ms] == j_col ? agg[2] : agg[0];
    return 0;
}

static result made(double time, double error, double rel_rmse, double ssim, double contrast_err)
{
    result r;
    memset(&r, 0, sizeof r);
    r.time_ratio = time, r.error = error, r.rel_rmse = rel_rmse, r.ssim = ssim, r.contrast_err = contrast_err;
    r.ok = 1;
    return r;
}

static int setup(void **st)
{
    (void)st;
    cu_error e;
    memset(&e, 0, sizeof e);
    if (sw_knobs_init("scenes/cumulus.scene", &e))
        return fprintf(stderr, "%s\n", e.msg), -1;
    k_ms = j_oct = j_col = -1;
    for (int k = 0; k < SW_NKNOBS; k++)
        if (sw_knob_is(k, "ms.mode"))
            k_ms = k;
    for (int j = 0; k_ms >= 0 && j < sw_knobs[k_ms].nvals; j++) {
        if (strcmp(sw_knobs[k_ms].vals[j], "octaves") == 0)
            j_oct = j;
        if (strcmp(sw_knobs[k_ms].vals[j], "collector") == 0)
            j_col = j;
    }
    for (int i = 0; i < SW_NKNOBS * SW_MAX_VALUES; i++)
        vidx[i] = -1;
    if (k_ms < 0 || j_oct < 0 || j_col < 0)
        return -1;
    vidx[k_ms * SW_MAX_VALUES + sw_knobs[k_ms].high] = 0;
    vidx[k_ms * SW_MAX_VALUES + j_oct] = 1;
    vidx[k_ms * SW_MAX_VALUES + j_col] = 2;
    return 0;
}

/* medium's pick (budget 0.5; low's budget 1 ends the descent before it starts), the sun turned sun_step degrees a
 * timed frame */
static int medium_mode_at(double sun_step)
{
    sweep sw;
    memset(&sw, 0, sizeof sw);
    sw.budget_med = 0.5, sw.budget_low = 1.0;
    sw.sun_step = sun_step;
    point med, low, trail[SW_MAX_GREEDY];
    int ntrail = 0;
    assert_int_equal(sw_choose_presets(&sw, agg, vidx, &agg[0], &med, &low, trail, &ntrail), 0);
    assert_int_equal(ntrail, 0);
    return med.c.v[k_ms];
}

static int medium_mode(void)
{
    return medium_mode_at(0);
}

static void test_the_cloud_error_chooses(void **st)
{
    (void)st;
    /* octaves: the smaller error on the cloud's pixels, the larger over the whole image (the sky's share) */
    agg[0] = made(1.0, 0.30, 0.20, 0.75, 0.30);
    agg[1] = made(0.40, 0.20, 0.50, 0.76, 0.29);
    agg[2] = made(0.45, 0.25, 0.10, 0.80, 0.20);
    assert_int_equal(medium_mode(), j_oct);
}

static void test_a_flatter_point_is_never_picked(void **st)
{
    (void)st;
    agg[0] = made(1.0, 0.30, 0.20, 0.75, 0.30);
    agg[2] = made(0.45, 0.25, 0.10, 0.80, 0.20);
    agg[1] = made(0.40, 0.20, 0.15, 0.73, 0.29); /* SSIM 0.02 below high's */
    assert_int_equal(medium_mode(), j_col);
    agg[1] = made(0.40, 0.20, 0.15, 0.76, 0.33); /* the contrast 0.03 further off */
    assert_int_equal(medium_mode(), j_col);
    agg[1] = made(0.40, 0.20, 0.15, 0.745, 0.315); /* within both margins: not flatter */
    assert_int_equal(medium_mode(), j_oct);
}

static void test_the_descent_skips_a_flatter_change(void **st)
{
    (void)st;
    agg[0] = made(1.0, 0.30, 0.20, 0.75, 0.30);
    agg[1] = made(0.40, 0.20, 0.15, 0.70, 0.29); /* flatter */
    agg[2] = made(0.45, 0.25, 0.10, 0.80, 0.20);
    sweep sw;
    memset(&sw, 0, sizeof sw);
    sw.budget_med = 0.5, sw.budget_low = 0.3;
    point med, low, trail[SW_MAX_GREEDY];
    int ntrail = 0;
    measured_octaves = measures = 0;
    assert_int_equal(sw_choose_presets(&sw, agg, vidx, &agg[0], &med, &low, trail, &ntrail), 0);
    assert_int_equal(measured_octaves, 0);
    assert_int_equal(measures, 1); /* the collector, then nothing left that saves time and is not flatter */
    assert_int_equal(ntrail, 1);
    assert_int_equal(trail[0].c.v[k_ms], j_col);
    assert_int_equal(med.c.v[k_ms], j_col);
    /* nothing within low's 0.3: the fastest point, but not the flatter octaves */
    assert_int_equal(low.c.v[k_ms], j_col);
}

/* Measured, reported, never chosen from static frames: diffusion (its solves are not in them) and the sun's maps made
 * dearer than high's (nor are they); the other multiple-scattering models and cheaper maps are eligible. From frames
 * that turn the sun half a degree or more, all of them are. */
static void test_eligible(void **st)
{
    (void)st;
    int j_none = -1, j_dif = -1;
    for (int j = 0; j < sw_knobs[k_ms].nvals; j++) {
        j_none = strcmp(sw_knobs[k_ms].vals[j], "none") == 0 ? j : j_none;
        j_dif = strcmp(sw_knobs[k_ms].vals[j], "diffusion") == 0 ? j : j_dif;
    }
    assert_true(j_none >= 0 && j_dif >= 0);
    assert_false(knob_preset_eligible(k_ms, j_dif, 0));
    assert_true(knob_preset_eligible(k_ms, j_dif, 1));
    for (int t = 0; t < 2; t++) {
        assert_true(knob_preset_eligible(k_ms, j_oct, t) && knob_preset_eligible(k_ms, j_col, t));
        assert_true(knob_preset_eligible(k_ms, j_none, t) && knob_preset_eligible(k_ms, sw_knobs[k_ms].high, t));
    }
    static const char *const maps[] = {"light.sun_samples", "light.sun_intervals", "quality.sun_map_size", "ms.blur"};
    for (size_t m = 0; m < sizeof maps / sizeof maps[0]; m++) {
        int k = -1;
        for (int i = 0; i < SW_NKNOBS; i++)
            k = sw_knob_is(i, maps[m]) ? i : k;
        assert_true(k >= 0);
        for (int j = 0; j < sw_knobs[k].nvals; j++) { /* the values are listed cheapest first */
            assert_int_equal(knob_preset_eligible(k, j, 0), j <= sw_knobs[k].high);
            assert_true(knob_preset_eligible(k, j, 1));
        }
    }
    /* what stays out whatever the sun: content (no noise, another phase), one interval per pixel */
    for (int k = 0; k < SW_NKNOBS; k++)
        for (int j = 0; j < sw_knobs[k].nvals; j++)
            if ((sw_knob_is(k, "quality.noise_octaves") && strcmp(sw_knobs[k].vals[j], "off") == 0) ||
                (sw_knob_is(k, "cloud.phase") && j != sw_knobs[k].high) ||
                (sw_knob_is(k, "quality.max_intervals") && strcmp(sw_knobs[k].vals[j], "1") == 0))
                assert_false(knob_preset_eligible(k, j, 1));
    /* the pick with diffusion measured best and within the budget: from static frames the octaves, the best eligible
     * point; from frames turning the sun 0.3 degrees (no grid solved again in them) still the octaves; from 0.6
     * degrees, diffusion */
    agg[0] = made(1.0, 0.30, 0.20, 0.75, 0.30);
    agg[1] = made(0.40, 0.25, 0.50, 0.76, 0.29);
    vidx[k_ms * SW_MAX_VALUES + j_col] = -1;
    vidx[k_ms * SW_MAX_VALUES + j_dif] = 2;
    agg[2] = made(0.45, 0.10, 0.10, 0.80, 0.20);
    int still = medium_mode(), slow = medium_mode_at(0.3), turning = medium_mode_at(0.6);
    vidx[k_ms * SW_MAX_VALUES + j_dif] = -1;
    vidx[k_ms * SW_MAX_VALUES + j_col] = 2;
    assert_int_equal(still, j_oct);
    assert_int_equal(slow, j_oct);
    assert_int_equal(turning, j_dif);
}

static void test_flatter(void **st)
{
    (void)st;
    result high = made(1, 0.3, 0.2, 0.75, 0.30);
    assert_false(sw_flatter(&high, &high));
    result r = high;
    r.ssim = 0.7399;
    assert_true(sw_flatter(&r, &high));
    r = high;
    r.contrast_err = 0.3201;
    assert_true(sw_flatter(&r, &high));
    r = high;
    r.ssim = 0.99, r.contrast_err = 0.0;
    assert_false(sw_flatter(&r, &high));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_eligible),
        cmocka_unit_test(test_flatter),
        cmocka_unit_test(test_the_cloud_error_chooses),
        cmocka_unit_test(test_a_flatter_point_is_never_picked),
        cmocka_unit_test(test_the_descent_skips_a_flatter_change),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
