/* tests/gpu/test_sun_bands.c: quality.sun_map_frames (src/gpu/frame_maps.c, frame_shadow.c): a creeping sun's maps
 * made again a band of rows a frame into spares and swapped in whole. Against whole maps made at once (a fresh scene
 * at that sun, the energy closure off so that nothing else remembers the path): the picture a moving sun settles to
 * is the whole render bit for bit, within 2K frames; while the sun turns, every frame draws exactly one band of the
 * cloud's maps and of the ground's shadow, the cloud is lit by a sun at most (2K - 1) steps behind, and the picture
 * is as far from the exact one as the exact picture of the maps' sun; a creeping sun does not pop; a jump of the sun
 * remakes the maps in that frame; with K = 1 every frame is the whole render of its own sun; a camera flying on has
 * the ground's shadow made in bands and settles to the whole render too. */
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
#define STEP 0.6 /* degrees of azimuth a frame: a knob turned fast (18 degrees a second at 30 fps) */
#define EL 30.0
#define AZ 135.0

/* From above and aside, so that the cloud's shadow on the ground is in view as well as the cloud; the cloud still
 * forming (its density 0.6 of its mature one: the maps are made at the mature density, the cloud drawn at its own). */
#define VIEW "camera.position=700 900 -1300", "camera.look_at=0 80 -250", "cloud.lifetime=1000", "cloud.life_phase=0.1"
static const char *const sets_k4[] = {"ms.closure=off", "quality.sun_map_frames=4", VIEW, NULL};

static double rel_diff(const float *a, const float *b)
{
    return tr_rel_diff(a, b, NPX);
}

/* The whole render of a fresh scene at sun (el, az), with `frames` (quality.sun_map_frames) as given. */
static void whole_render(tr_ctx *c, double el, double az, const char *frames, float *out)
{
    char e1[64], e2[64];
    snprintf(e1, sizeof e1, "sun.elevation=%.9g", el);
    snprintf(e2, sizeof e2, "sun.azimuth=%.9g", az);
    const char *sets[] = {"ms.closure=off", frames, e1, e2, VIEW, NULL};
    if (tr_render(c, "scenes/cumulus.scene", sets))
        fail_msg("%s", c->err);
    tr_read_rgbf(c, out);
}

static void set_sun(tr_ctx *c, double el, double az)
{
    cu_error e;
    if (cu_renderer_set_sun(c->r, el, az, &e) || tr_render_again(c))
        fail_msg("%s %s", e.msg, c->err);
}

static double degrees_between(vec3 a, vec3 b)
{
    return acos(fmin(1.0, v3_dot(a, b))) * 180.0 / CU_PI;
}

/* The sun's direction k frames into the turn (y up, as the renderer's). */
static vec3 sun_at(int k)
{
    double el = EL * CU_PI / 180.0, az = (AZ + STEP * k) * CU_PI / 180.0;
    return v3(cos(el) * sin(az), sin(el), -cos(el) * cos(az));
}

/* The sun turning STEP a frame: one band of the cloud's maps and of the ground's shadow each frame, the cloud lit by a
 * sun at most 2K - 1 steps behind and never further from the exact picture than the bound; when the sun stops the
 * picture settles, within 2K frames, to the whole render of the final sun, bit for bit. */
static void test_moving_sun_settles_to_the_whole_render(void **st)
{
    (void)st;
    tr_ctx c;
    if (tr_open(&c, &cu_display_egl, W, H, 1))
        fail_msg("%s", c.err);
    float *got = malloc(sizeof(float) * NPX);
    const int K = 4, moves = 10;
    double worst = 0;
    /* The exact pictures need a fresh scene each; the moving renderer keeps one: two passes over the same path. */
    float *exact = malloc(sizeof(float) * NPX * (moves + 1));
    for (int k = 0; k <= moves; k++)
        whole_render(&c, EL, AZ + STEP * k, "quality.sun_map_frames=1", exact + NPX * (size_t)k);
    if (tr_render(&c, "scenes/cumulus.scene", sets_k4))
        fail_msg("%s", c.err);
    const cu_cloud_slot *sl = &c.r->clouds.slot[0];
    int band = sl->next_band, ground_band = c.r->ground[0].band;
    assert_int_equal(band, 0); /* the first frame makes its maps whole */
    for (int k = 1; k <= moves; k++) {
        set_sun(&c, EL, AZ + STEP * k);
        /* exactly one band a frame, the cloud's and the ground's */
        assert_int_equal(sl->next_band, (band + 1) % K);
        assert_int_equal(c.r->ground[0].band, (ground_band + 1) % K);
        band = sl->next_band;
        ground_band = c.r->ground[0].band;
        double lag = degrees_between(sl->maps_sun, c.r->sky.sun_dir);
        assert_true(lag <= (2 * K - 1) * STEP + 1e-6);
        tr_read_rgbf(&c, got);
        /* as far from this frame's exact picture as the exact picture of the sun the maps were made for, give or
         * take what the sky (which follows the sun now) adds */
        int behind = (int)lround(lag / degrees_between(sun_at(0), sun_at(1)));
        double d = rel_diff(got, exact + NPX * (size_t)k);
        double old = behind ? rel_diff(exact + NPX * (size_t)(k - behind), exact + NPX * (size_t)k) : 0;
        printf("sun %.1f deg on: maps %.2f deg (%d frames) behind, largest difference %.4f of the image's brightest "
               "(the exact picture %d frames before: %.4f)\n", STEP * k, lag, behind, d, behind, old);
        assert_true(d <= 1.1 * old + 0.002);
        worst = fmax(worst, d);
    }
    printf("largest difference while the sun turns: %.4f\n", worst);
    int settled_after = -1;
    for (int f = 1; f <= 2 * K && settled_after < 0; f++) {
        if (tr_render_again(&c))
            fail_msg("%s", c.err);
        if (cu_renderer_settled(c.r))
            settled_after = f;
    }
    printf("the sun stopped: settled after %d frames\n", settled_after);
    assert_true(settled_after > 0 && settled_after <= 2 * K);
    tr_read_rgbf(&c, got);
    assert_true(degrees_between(sl->maps_sun, c.r->sky.sun_dir) < 1e-6);
    double d = rel_diff(got, exact + NPX * (size_t)moves);
    printf("settled against the whole render: largest difference %.3g\n", d);
    assert_true(d == 0.0);
    free(exact);
    free(got);
    tr_close(&c);
}

/* A jump of the sun (over a degree in a frame) remakes the maps whole in that frame: the whole render at once. */
static void test_jump_remakes_at_once(void **st)
{
    (void)st;
    tr_ctx c;
    if (tr_open(&c, &cu_display_egl, W, H, 1))
        fail_msg("%s", c.err);
    float *got = malloc(sizeof(float) * NPX), *ref = malloc(sizeof(float) * NPX);
    whole_render(&c, EL + 20, AZ - 30, "quality.sun_map_frames=4", ref);
    if (tr_render(&c, "scenes/cumulus.scene", sets_k4))
        fail_msg("%s", c.err);
    set_sun(&c, EL, AZ + STEP); /* a band under way when the jump comes */
    assert_int_equal(c.r->clouds.slot[0].next_band, 1);
    set_sun(&c, EL + 20, AZ - 30);
    assert_int_equal(c.r->clouds.slot[0].next_band, 0);
    tr_read_rgbf(&c, got);
    double d = rel_diff(got, ref);
    printf("a 20 degree jump, the frame after: largest difference %.3g\n", d);
    assert_true(d == 0.0);
    free(got);
    free(ref);
    tr_close(&c);
}

/* K = 1: every frame of the turning sun is the whole render of its own sun. */
static void test_one_frame_maps_follow_every_frame(void **st)
{
    (void)st;
    tr_ctx c;
    if (tr_open(&c, &cu_display_egl, W, H, 1))
        fail_msg("%s", c.err);
    float *got = malloc(sizeof(float) * (NPX * 4)), *ref = got + NPX * 3;
    static const char *const sets_k1[] = {"ms.closure=off", "quality.sun_map_frames=1", VIEW, NULL};
    if (tr_render(&c, "scenes/cumulus.scene", sets_k1))
        fail_msg("%s", c.err);
    for (int k = 1; k <= 3; k++) {
        set_sun(&c, EL, AZ + STEP * k);
        tr_read_rgbf(&c, got + NPX * (size_t)(k - 1));
    }
    for (int k = 1; k <= 3; k++) {
        whole_render(&c, EL, AZ + STEP * k, "quality.sun_map_frames=1", ref);
        double d = rel_diff(got + NPX * (size_t)(k - 1), ref);
        printf("K = 1, sun %.1f deg on: largest difference %.3g\n", STEP * k, d);
        assert_true(d == 0.0);
    }
    free(got);
    tr_close(&c);
}

/* A sun creeping 0.05 degrees a frame (a slow knob, the time of day) with maps made a band a frame and the energy
 * closure on: no frame pops when a map's last band swaps in (each step's change within 2 % of the image's range, the
 * bound test_ms holds whole maps to). */
static void test_creeping_sun_does_not_pop(void **st)
{
    (void)st;
    tr_ctx c;
    if (tr_open(&c, &cu_display_egl, W, H, 1))
        fail_msg("%s", c.err);
    float *a = malloc(sizeof(float) * NPX * 2), *b = a + NPX;
    static const char *const sets[] = {"quality.sun_map_frames=4", VIEW, NULL};
    if (tr_render(&c, "scenes/cumulus.scene", sets))
        fail_msg("%s", c.err);
    tr_read_rgbf(&c, a);
    double worst = 0, range = 0;
    int swaps = 0;
    for (int k = 1; k <= 24; k++) {
        vec3 before = c.r->clouds.slot[0].maps_sun;
        set_sun(&c, EL + 0.05 * k, AZ);
        swaps += v3_len(v3_sub(before, c.r->clouds.slot[0].maps_sun)) > 0;
        tr_read_rgbf(&c, b);
        double step = 0;
        for (size_t i = 0; i < NPX; i++) {
            step = fmax(step, fabs(a[i] - b[i]));
            range = fmax(range, b[i]);
        }
        worst = fmax(worst, step);
        memcpy(a, b, sizeof(float) * NPX);
    }
    printf("sun creeping 0.05 deg a frame, maps in 4 bands: %d swaps in 24 frames, largest step %.3g (%.2f%% of the "
           "range)\n", swaps, worst, 100 * worst / range);
    assert_true(swaps >= 5 && swaps <= 6); /* the maps follow every K = 4 frames */
    assert_true(worst < 0.02 * range);
    free(a);
    tr_close(&c);
}

/* Renders the current scene from the camera at (x, y, z) looking at (lx, ly, lz), through host matrices: the renderer
 * keeps its maps (a new scene would start over). */
static void frame_from(tr_ctx *c, const double pos[3], const double look[3])
{
    char p[96], l[96];
    snprintf(p, sizeof p, "%.9g %.9g %.9g", pos[0], pos[1], pos[2]);
    snprintf(l, sizeof l, "%.9g %.9g %.9g", look[0], look[1], look[2]);
    if (tr_render_from(c, "scenes/cumulus.scene", p, l))
        fail_msg("%s", c->err);
}

/* A camera flying on at 100 m above the ground moves the ground's shadow square (8 km, re-centred every 500 m): the
 * new square's map is made a band a frame, and when the camera stops the picture settles to the whole render from
 * there, bit for bit. */
static void test_flying_camera_settles(void **st)
{
    (void)st;
    tr_ctx c;
    if (tr_open(&c, &cu_display_egl, W, H, 1))
        fail_msg("%s", c.err);
    float *got = malloc(sizeof(float) * NPX * 2), *ref = got + NPX;
    static const char *const sets[] = {"ms.closure=off", "quality.sun_map_frames=4", NULL};
    double pos[3] = {-600, 100, -1600}, look[3] = {-600, 0, -200};
    if (tr_render(&c, "scenes/cumulus.scene", sets))
        fail_msg("%s", c.err);
    int banded = 0;
    for (int k = 0; k <= 8; k++) {
        pos[0] = look[0] = -600 + 150.0 * k;
        frame_from(&c, pos, look);
        banded += c.r->ground[0].band > 0;
    }
    int settled_after = -1;
    for (int f = 1; f <= 8 && settled_after < 0; f++) {
        frame_from(&c, pos, look);
        if (cu_renderer_settled(c.r))
            settled_after = f;
    }
    tr_read_rgbf(&c, got);
    char p[96], l[96];
    snprintf(p, sizeof p, "camera.position=%.9g %.9g %.9g", pos[0], pos[1], pos[2]);
    snprintf(l, sizeof l, "camera.look_at=%.9g %.9g %.9g", look[0], look[1], look[2]);
    const char *whole[] = {"ms.closure=off", "quality.sun_map_frames=1", p, l, NULL};
    if (tr_render(&c, "scenes/cumulus.scene", whole))
        fail_msg("%s", c.err);
    tr_read_rgbf(&c, ref);
    double d = rel_diff(got, ref);
    printf("flying 150 m a frame: %d frames with a ground band under way; settled after %d frames; against the whole "
           "render %.3g\n", banded, settled_after, d);
    assert_true(banded >= 3);
    assert_true(settled_after > 0 && settled_after <= 8);
    assert_true(d == 0.0);
    free(got);
    tr_close(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_moving_sun_settles_to_the_whole_render),
        cmocka_unit_test(test_jump_remakes_at_once),
        cmocka_unit_test(test_one_frame_maps_follow_every_frame),
        cmocka_unit_test(test_creeping_sun_does_not_pop),
        cmocka_unit_test(test_flying_camera_settles),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
