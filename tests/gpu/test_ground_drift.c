/* tests/gpu/test_ground_drift.c: the clouds' shadow on the ground as time runs (src/gpu/frame_shadow.c). Clouds on
 * one wind: the ground's map is made in a frame drifting with them, so each frame is the whole render of a fresh
 * scene at that time, bit for bit, without the map being made again; a cloud's changing density (its life cycle) has
 * the map made a band a frame, and the picture settles to the whole render when time stops; clouds on different
 * winds have the map made whole every frame, each frame again the whole render. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "render_util.h"
#include "renderer.h"
#include "scene.h"

#define W 96
#define H 72
#define NPX ((size_t)W * H * 3)
#define FRAMES 8

/* From above and aside, so that the cloud's shadow on the ground is in view as well as the cloud. No boil: the
 * cloud's own maps stay as they are, and what changes is where the cloud and its shadow are. */
#define VIEW "ms.closure=off", "quality.sun_map_frames=4", "cloud.boil=0", "camera.position=700 900 -1300", \
             "camera.look_at=0 80 -250"

/* Two clouds, one drifting east and one north, both shading the ground in view. */
static const char two_winds[] = "[camera]\nposition = 700 900 -1300\nlook_at = 0 80 -250\nfov = 50\n"
                                "[sun]\nelevation = 30\nazimuth = 135\n[ms]\nclosure = off\n"
                                "[cloud]\nboil = 0\nwind = 20 0\n[ellipsoid]\ncenter = 0 250 0\nradii = 200 120 160\n"
                                "[cloud]\nwind = 0 25\n[ellipsoid]\ncenter = -500 300 -300\nradii = 180 110 150\n";

static double rel_diff(const float *a, const float *b)
{
    return tr_rel_diff(a, b, NPX);
}

/* A fresh scene at time t: cumulus.scene with the settings given (NULL-terminated, at most 8), or the two-wind
 * scene when `sets` is NULL. */
static void fresh_render(tr_ctx *c, const char *const *sets, double t, float *out)
{
    cu_scene *s;
    cu_error e;
    char tk[64];
    snprintf(tk, sizeof tk, "scene.time=%.9g", t);
    int bad = sets ? cu_scene_load(&s, "scenes/cumulus.scene", &e)
                   : cu_scene_parse(&s, "two_winds.scene", two_winds, strlen(two_winds), &e);
    for (int i = 0; !bad && sets && sets[i]; i++)
        bad = cu_scene_set(s, sets[i], &e);
    if (bad || cu_scene_set(s, tk, &e))
        fail_msg("%s", e.msg);
    if (tr_render_scene(c, s))
        fail_msg("%s", c->err);
    cu_scene_free(s);
    tr_read_rgbf(c, out);
}

static void at_time(tr_ctx *c, double t)
{
    cu_error e;
    if (cu_renderer_set_time(c->r, t, &e) || tr_render_again(c))
        fail_msg("%s %s", e.msg, c->err);
}

/* Renders FRAMES + 1 frames of the scene, time running dt a frame, each against a fresh scene at that time; counts
 * the ground map's whole remakes after the first frame and the frames with a band under way. */
static void run(const char *const *sets, double dt, int *whole, int *banded, double *worst, double *moved)
{
    tr_ctx c;
    if (tr_open(&c, &cu_display_egl, W, H, 1))
        fail_msg("%s", c.err);
    float *got = malloc(sizeof(float) * NPX * (FRAMES + 2)), *exact = got + NPX;
    for (int k = 0; k <= FRAMES; k++)
        fresh_render(&c, sets, dt * k, exact + NPX * (size_t)k);
    fresh_render(&c, sets, 0.0, got);
    assert_true(c.r->ground_sig != 0); /* the ground's map is in use */
    *whole = *banded = 0;
    *worst = 0;
    for (int k = 1; k <= FRAMES; k++) {
        uint64_t sig = c.r->ground_sig;
        int band = c.r->ground_band;
        at_time(&c, dt * k);
        /* a new map not from the last band of a spare: made whole in this frame */
        *whole += c.r->ground_sig != sig && !(band == 3 && c.r->ground_band == 0);
        *banded += c.r->ground_band > 0;
        tr_read_rgbf(&c, got);
        *worst = fmax(*worst, rel_diff(got, exact + NPX * (size_t)k));
    }
    *moved = rel_diff(exact, exact + NPX * (size_t)FRAMES);
    free(got);
    tr_close(&c);
}

/* The shadow where its cloud is: the drifting scene at time t against the still cloud seen from a camera moved the
 * other way by as much. The ground's map then lies on another grid of texels (shifted 20 t m, 2.05 texels at 8 s),
 * so the two agree to its bilinear filtering, not to the bit; a map read where it was made is off by its shadow. */
static double shadow_follows(tr_ctx *c, const char *const *sets, double t)
{
    float *a = malloc(sizeof(float) * NPX * 2), *b = a + NPX;
    char p[96], l[96];
    snprintf(p, sizeof p, "camera.position=%.9g 900 -1300", 700 - 20 * t);
    snprintf(l, sizeof l, "camera.look_at=%.9g 80 -250", 0 - 20 * t);
    const char *const moved_cam[] = {VIEW, p, l, NULL};
    fresh_render(c, sets, t, a);
    fresh_render(c, moved_cam, 0.0, b);
    double d = rel_diff(a, b);
    free(a);
    return d;
}

/* A cloud drifting 20 m/s east: its shadow drifts with it (where the still cloud seen from a camera moving the
 * other way has it), every frame the whole render at its time, and the ground's map is never made again. */
static void test_one_wind_moves_the_map_not_remakes_it(void **st)
{
    (void)st;
    static const char *const sets[] = {VIEW, "cloud.wind=20 0", NULL};
    int whole, banded;
    double worst, moved;
    run(sets, 1.0, &whole, &banded, &worst, &moved);
    printf("one wind, 1 s a frame: %d whole remakes, %d frames with a band, largest difference from the whole render "
           "%.3g (the picture moved by %.3g)\n", whole, banded, worst, moved);
    assert_int_equal(whole, 0);
    assert_int_equal(banded, 0);
    assert_true(moved > 0.02);
    assert_true(worst == 0.0);
    tr_ctx c;
    if (tr_open(&c, &cu_display_egl, W, H, 1))
        fail_msg("%s", c.err);
    double follows = shadow_follows(&c, sets, FRAMES);
    printf("after %d s: against the still cloud seen from a camera moved back %.3g (measured 1e-5; 0.1 with the map "
           "read where it was made)\n", FRAMES, follows);
    assert_true(follows < 1e-3);
    tr_close(&c);
}

/* A forming cloud drifting on the wind: its density grows, the ground's map is made again a band a frame (never
 * whole), and when time stops the picture settles to the whole render at that time, bit for bit. */
static void test_growing_cloud_bands_and_settles(void **st)
{
    (void)st;
    static const char *const sets[] = {VIEW, "cloud.wind=20 0", "cloud.lifetime=1000", "cloud.life_phase=0.05",
                                       NULL};
    tr_ctx c;
    if (tr_open(&c, &cu_display_egl, W, H, 1))
        fail_msg("%s", c.err);
    float *got = malloc(sizeof(float) * NPX * 2), *ref = got + NPX;
    const double dt = 4.0;
    fresh_render(&c, sets, dt * FRAMES, ref);
    fresh_render(&c, sets, 0.0, got);
    int banded = 0, whole = 0;
    for (int k = 1; k <= FRAMES; k++) {
        uint64_t sig = c.r->ground_sig;
        int band = c.r->ground_band;
        at_time(&c, dt * k);
        whole += c.r->ground_sig != sig && !(band == 3 && c.r->ground_band == 0);
        banded += c.r->ground_band > 0;
    }
    int settled_after = -1;
    for (int f = 1; f <= 8 && settled_after < 0; f++) {
        if (tr_render_again(&c))
            fail_msg("%s", c.err);
        if (cu_renderer_settled(c.r))
            settled_after = f;
    }
    tr_read_rgbf(&c, got);
    double d = rel_diff(got, ref);
    printf("a forming cloud, 4 s a frame: %d whole remakes, %d frames with a band; settled after %d frames, against "
           "the whole render %.3g\n", whole, banded, settled_after, d);
    assert_int_equal(whole, 0);
    assert_true(banded >= 3);
    assert_true(settled_after > 0 && settled_after <= 8);
    assert_true(d == 0.0);
    free(got);
    tr_close(&c);
}

/* Clouds on different winds cannot share a drifting frame: the map is made whole every frame they moved, each
 * frame the whole render at its time. */
static void test_two_winds_remake_whole(void **st)
{
    (void)st;
    int whole, banded;
    double worst, moved;
    run(NULL, 1.0, &whole, &banded, &worst, &moved);
    printf("two winds, 1 s a frame: %d whole remakes, %d frames with a band, largest difference from the whole "
           "render %.3g (the picture moved by %.3g)\n", whole, banded, worst, moved);
    assert_int_equal(whole, FRAMES);
    assert_int_equal(banded, 0);
    assert_true(moved > 0.02);
    assert_true(worst == 0.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_one_wind_moves_the_map_not_remakes_it),
        cmocka_unit_test(test_growing_cloud_bands_and_settles),
        cmocka_unit_test(test_two_winds_remake_whole),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
