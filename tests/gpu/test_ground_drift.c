/* tests/gpu/test_ground_drift.c: the clouds' shadows as time runs, on the ground (src/gpu/frame_ground.c) and on each
 * other (frame_shadow.c). Clouds on one wind: the ground's map is made in a frame drifting with them, so each frame
 * is the whole render of a fresh scene at that time, bit for bit, without the map being made again; a cloud's
 * changing density (its life cycle) has only its shadow's texels made again, each frame still the whole render; with
 * the sun creeping too the map is made in bands, and the picture settles to the whole render when both stop (also
 * when a cloud's shadow straddles two bands drawn at different densities); clouds on two winds get a drifting map
 * each; with more winds than maps the last map holds the rest and is made whole every frame. A cloud shaded by
 * clouds on another wind has its map made again each time they have moved an eighth of its texel, and then it is the
 * whole render. */
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

/* Clouds on winds of their own, each shading the ground in view: the first two, or all three (more winds than the
 * renderer's CU_GROUND_MAPS maps; none re-centres a map's square within the test). With placed >= 0 they have no
 * wind and stand where theirs has carried them by time `placed`, their noise moved back: the same picture without
 * drifting maps. */
/* Winds that carry each cloud whole texels of the ground's map (40 km / 512 = 78.125 m) in FRAMES seconds, so that
 * the placed clouds' maps lie on the same grid of texels as the drifting ones. */
#define TEXEL_PER_RUN (40000.0 / 512 / FRAMES)
static const struct { double c[3], r[3], wind[2]; } WIND_CLOUDS[3] = {
    {{0, 250, 0}, {200, 120, 160}, {2 * TEXEL_PER_RUN, 0}},
    {{-500, 300, -300}, {180, 110, 150}, {0, -2 * TEXEL_PER_RUN}},
    {{400, 280, -700}, {150, 100, 130}, {-TEXEL_PER_RUN, -TEXEL_PER_RUN}},
};
static char winds_text[2048];

static const char *winds_scene(int clouds, double placed)
{
    int n = snprintf(winds_text, sizeof winds_text, "[camera]\nposition = 700 900 -1300\nlook_at = 0 80 -250\n"
                     "fov = 50\n[sun]\nelevation = 30\nazimuth = 135\n[ms]\nclosure = off\n");
    for (int i = 0; i < clouds; i++) {
        double t = placed >= 0 ? placed : 0, w = placed >= 0 ? 0 : 1;
        const double *c = WIND_CLOUDS[i].c, *r = WIND_CLOUDS[i].r, *v = WIND_CLOUDS[i].wind;
        n += snprintf(winds_text + n, sizeof winds_text - (size_t)n,
                      "[cloud]\n%swind = %.9g %.9g\nnoise_offset = %.9g 0 %.9g\n[ellipsoid]\ncenter = %.9g %g %.9g\n"
                      "radii = %g %g %g\n", i ? "" : "boil = 0\n", w * v[0], w * v[1], -v[0] * t, v[1] * t,
                      c[0] + v[0] * t, c[1], c[2] - v[1] * t, r[0], r[1], r[2]);
    }
    return winds_text;
}

static double rel_diff(const float *a, const float *b)
{
    return tr_rel_diff(a, b, NPX);
}

/* A fresh scene at time t: cumulus.scene with the settings given (NULL-terminated), or the scene `text` when `sets`
 * is NULL. */
static void fresh_render(tr_ctx *c, const char *const *sets, const char *text, double t, float *out)
{
    cu_scene *s;
    cu_error e;
    char tk[64];
    snprintf(tk, sizeof tk, "scene.time=%.9g", t);
    int bad = sets ? cu_scene_load(&s, "scenes/cumulus.scene", &e)
                   : cu_scene_parse(&s, "winds.scene", text, strlen(text), &e);
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

/* Renders FRAMES + 1 frames of the scene, time running dt a frame, each against a fresh scene at that time; counts,
 * for each ground map, its whole remakes after the first frame and the frames with a band under way. */
typedef struct run_counts {
    int whole[CU_GROUND_MAPS], banded[CU_GROUND_MAPS], maps, mixed;
    double worst, moved;
} run_counts;

static void run(const char *const *sets, const char *text, double dt, run_counts *rc)
{
    tr_ctx c;
    if (tr_open(&c, &cu_display_egl, W, H, 1))
        fail_msg("%s", c.err);
    float *got = malloc(sizeof(float) * NPX * (FRAMES + 2)), *exact = got + NPX;
    for (int k = 0; k <= FRAMES; k++)
        fresh_render(&c, sets, text, dt * k, exact + NPX * (size_t)k);
    fresh_render(&c, sets, text, 0.0, got);
    memset(rc, 0, sizeof *rc);
    rc->maps = c.r->ground_maps;
    for (int g = 0; g < rc->maps; g++)
        assert_true(c.r->ground[g].sig != 0); /* each map is in use */
    for (int k = 1; k <= FRAMES; k++) {
        uint64_t sig[CU_GROUND_MAPS];
        int band[CU_GROUND_MAPS];
        for (int g = 0; g < rc->maps; g++)
            sig[g] = c.r->ground[g].sig, band[g] = c.r->ground[g].band;
        at_time(&c, dt * k);
        for (int g = 0; g < rc->maps; g++) {
            const cu_ground_map *m = &c.r->ground[g];
            /* a new map not from the last band of a spare: made whole in this frame */
            rc->whole[g] += m->sig != sig[g] && !(band[g] == 3 && m->band == 0);
            rc->banded[g] += m->band > 0;
        }
        tr_read_rgbf(&c, got);
        rc->worst = fmax(rc->worst, rel_diff(got, exact + NPX * (size_t)k));
    }
    rc->mixed = c.r->ground[rc->maps - 1].mixed;
    rc->moved = rel_diff(exact, exact + NPX * (size_t)FRAMES);
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
    fresh_render(c, sets, NULL, t, a);
    fresh_render(c, moved_cam, NULL, 0.0, b);
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
    run_counts k;
    run(sets, NULL, 1.0, &k);
    printf("one wind, 1 s a frame: %d whole remakes, %d frames with a band, largest difference from the whole render "
           "%.3g (the picture moved by %.3g)\n", k.whole[0], k.banded[0], k.worst, k.moved);
    assert_int_equal(k.maps, 1);
    assert_int_equal(k.whole[0], 0);
    assert_int_equal(k.banded[0], 0);
    assert_true(k.moved > 0.02);
    assert_true(k.worst == 0.0);
    tr_ctx c;
    if (tr_open(&c, &cu_display_egl, W, H, 1))
        fail_msg("%s", c.err);
    double follows = shadow_follows(&c, sets, FRAMES);
    printf("after %d s: against the still cloud seen from a camera moved back %.3g (measured 1e-5; 0.1 with the map "
           "read where it was made)\n", FRAMES, follows);
    assert_true(follows < 1e-3);
    tr_close(&c);
}

/* A forming cloud drifting on the wind: its density grows, and the ground's map has only the texels of its shadow
 * made again (never whole, no band), so that every frame is the whole render of a fresh scene at that time, bit for
 * bit. Then the sun creeps too: the map is made again in bands, of the densities of the frames each band was drawn
 * in; when time and the sun stop the picture settles to the whole render, bit for bit (the cloud's texels made again
 * once more where its bands held different densities). */
static void test_growing_cloud_patches_and_settles(void **st)
{
    (void)st;
    static const char *const sets[] = {VIEW, "cloud.wind=20 0", "cloud.lifetime=1000", "cloud.life_phase=0.05",
                                       NULL};
    tr_ctx c;
    if (tr_open(&c, &cu_display_egl, W, H, 1))
        fail_msg("%s", c.err);
    float *got = malloc(sizeof(float) * NPX * (FRAMES + 2)), *refs = got + NPX, *ref = refs;
    const double dt = 4.0;
    double worst = 0;
    int whole = 0, banded = 0;
    long patches = 0;
    for (int k = 1; k <= FRAMES; k++) /* first: each render replaces the renderer's scene */
        fresh_render(&c, sets, NULL, dt * k, refs + NPX * (size_t)k);
    fresh_render(&c, sets, NULL, 0.0, got);
    for (int k = 1; k <= FRAMES; k++) {
        uint64_t sig = c.r->ground[0].sig;
        long p = c.r->ground[0].patches;
        at_time(&c, dt * k);
        patches += c.r->ground[0].patches - p;
        whole += c.r->ground[0].sig != sig && c.r->ground[0].patches == p;
        banded += c.r->ground[0].band > 0;
        tr_read_rgbf(&c, got);
        worst = fmax(worst, rel_diff(got, refs + NPX * (size_t)k));
    }
    printf("a forming cloud, 4 s a frame: %d whole remakes, %ld patches, %d frames with a band; against the whole "
           "render of each frame %.3g\n", whole, patches, banded, worst);
    assert_int_equal(whole, 0);
    assert_int_equal(banded, 0);
    assert_true(patches >= 3);
    assert_true(worst == 0.0);

    /* the sun creeping 0.2 degrees a frame as well: bands, each of its frame's densities */
    double el, az;
    cu_renderer_get_sun(c.r, &el, &az);
    cu_error e;
    banded = 0;
    double t = dt * FRAMES;
    for (int k = 1; k <= FRAMES; k++) {
        t += dt;
        if (cu_renderer_set_sun(c.r, el + 0.2 * k, az, &e))
            fail_msg("%s", e.msg);
        at_time(&c, t);
        banded += c.r->ground[0].band > 0;
    }
    int settled_after = -1;
    for (int f = 1; f <= 12 && settled_after < 0; f++) {
        if (tr_render_again(&c))
            fail_msg("%s", c.err);
        if (cu_renderer_settled(c.r))
            settled_after = f;
    }
    char sun_el[64], sun_az[64];
    snprintf(sun_el, sizeof sun_el, "sun.elevation=%.17g", el + 0.2 * FRAMES);
    snprintf(sun_az, sizeof sun_az, "sun.azimuth=%.17g", az);
    const char *const sets2[] = {VIEW, "cloud.wind=20 0", "cloud.lifetime=1000", "cloud.life_phase=0.05", sun_el,
                                 sun_az, NULL};
    tr_read_rgbf(&c, got);
    fresh_render(&c, sets2, NULL, t, ref);
    double d = rel_diff(got, ref);
    printf("and the sun creeping 0.2 degrees a frame: %d frames with a band; settled after %d frames, against the "
           "whole render %.3g\n", banded, settled_after, d);
    assert_true(banded >= 3);
    assert_true(settled_after > 0 && settled_after <= 12);
    assert_true(d == 0.0);
    free(got);
    tr_close(&c);
}

/* A wide, flat cloud growing straight above the ground map's centre (the camera 300 m up, looking down at its
 * shadow), the shadow across the boundary of the map's second and third bands: the sun steps once, so the map is
 * made again in bands, and the cloud grows between them, so its shadow is drawn at two densities. Time then stops:
 * the map must know the cloud is mixed and make its texels again (a patch), or the picture keeps the two halves of
 * its shadow (0.23 off, with the cloud taken as of the last band's density). */
static void test_bands_of_different_densities(void **st)
{
    (void)st;
    char text[1024];
    tr_ctx c;
    if (tr_open(&c, &cu_display_egl, W, H, 1))
        fail_msg("%s", c.err);
    float *got = malloc(sizeof(float) * NPX * 3), *ref = got + NPX, *none = ref + NPX;
    const double dt = 8.0;
    for (int pass = 0; pass < 2; pass++) {
        snprintf(text, sizeof text, "[camera]\nposition = 0 300 450\nlook_at = 0 0 0\nfov = 50\n[sun]\n"
                 "elevation = %.17g\nazimuth = 180\n[ms]\nclosure = off\n[quality]\nsun_map_frames = 4\n"
                 "[cloud]\nboil = 0\nlifetime = 200\nlife_phase = 0.02\n[ellipsoid]\ncenter = 0 900 0\n"
                 "radii = 1500 80 120\n", pass ? 85.2 : 85.0);
        fresh_render(&c, NULL, text, pass ? dt * 4 : 0.0, pass ? ref : none);
        if (pass)
            break;
        long patches = c.r->ground[0].patches;
        int banded = 0;
        for (int k = 1; k <= 4; k++) {
            cu_error e;
            if (k == 1 && cu_renderer_set_sun(c.r, 85.2, 180, &e))
                fail_msg("%s", e.msg);
            at_time(&c, dt * k);
            banded += c.r->ground[0].band > 0;
        }
        for (int f = 0; f < 4; f++)
            if (tr_render_again(&c))
                fail_msg("%s", c.err);
        tr_read_rgbf(&c, got);
        printf("bands of different densities: %d frames with a band, %ld patches after\n", banded,
               c.r->ground[0].patches - patches);
        assert_true(banded >= 3);
        assert_true(c.r->ground[0].patches > patches);
    }
    double d = rel_diff(got, ref), shown = rel_diff(none, ref);
    printf("against the whole render %.3g (the shadow itself: %.3g)\n", d, shown);
    assert_true(shown > 0.01);
    assert_true(d == 0.0);
    free(got);
    tr_close(&c);
}

/* Shadows between clouds on two winds (frame_shadow.c): three casters on one wind drifting 0.3 of an eighth of a
 * texel of the shaded cloud's map a frame above a still cloud. Its map is made again when they have moved an eighth
 * of a texel since: every third or fourth frame (not whenever one of them crosses a grid of eighths of its own: 3x as
 * often), and each such frame is the whole render at its time, bit for bit; between, it lags by a fraction of that. */
static void test_cloud_shadow_follows_other_wind(void **st)
{
    (void)st;
    enum { N = 16 };
    const double v = 10.0; /* m/s, the caster's wind */
    char text[1024];
    snprintf(text, sizeof text, "[camera]\nposition = 0 300 1500\nlook_at = 0 400 0\nfov = 50\n[sun]\n"
             "elevation = 89\nazimuth = 180\n[ms]\nclosure = off\n[cloud]\nboil = 0\n[ellipsoid]\n"
             "center = 0 300 0\nradii = 300 150 250\n[cloud]\nwind = %g 0\n[ellipsoid]\n"
             "center = -150 1000 -100\nradii = 90 60 80\n[cloud]\nwind = %g 0\n[ellipsoid]\n"
             "center = 61.7 1050 80\nradii = 80 60 90\n[cloud]\nwind = %g 0\n[ellipsoid]\n"
             "center = 203.1 1000 -50\nradii = 90 60 80\n", v, v, v);
    tr_ctx c;
    if (tr_open(&c, &cu_display_egl, W, H, 1))
        fail_msg("%s", c.err);
    float *got = malloc(sizeof(float) * NPX * (N + 3)), *refs = got + NPX, *later = refs + NPX * (N + 1);
    fresh_render(&c, NULL, text, 0.0, got);
    const cu_cloud_slot *sl = &c.r->clouds.slot[0];
    /* the map's radius (sunmap.c: cu_sun_radius) and side (frame_shadow.c) */
    double Ri = sl->cloud.bound_radius * 1.01 + 1.0;
    double step = Ri / (4.0 * (sl->map_size / 2 > 16 ? sl->map_size / 2 : 16));
    double dt = 0.3 * step / v;
    for (int k = 1; k <= N; k++) /* first: each render replaces the renderer's scene */
        fresh_render(&c, NULL, text, dt * k, refs + NPX * (size_t)k);
    fresh_render(&c, NULL, text, 0.0, got);
    fresh_render(&c, NULL, text, step / v, later);
    double one_step = rel_diff(got, later), worst_between = 0, worst_remade = 0;
    fresh_render(&c, NULL, text, 0.0, got);
    sl = &c.r->clouds.slot[0];
    int remakes = 0;
    for (int k = 1; k <= N; k++) {
        double made = sl->shadow_time;
        at_time(&c, dt * k);
        tr_read_rgbf(&c, got);
        double d = rel_diff(got, refs + NPX * (size_t)k);
        if (sl->shadow_time != made) {
            remakes++;
            worst_remade = fmax(worst_remade, d);
        } else {
            worst_between = fmax(worst_between, d);
        }
    }
    printf("casters on another wind, 0.3 of a step a frame: %d remakes in %d frames (an eighth of a texel: %.2f m); "
           "remade frames against the whole render %.3g; others %.3g, against %.3g for a whole step\n", remakes, N,
           step, worst_remade, worst_between, one_step);
    assert_true(sl->has_shadow);
    assert_true(remakes >= 3 && remakes <= 5);
    assert_true(worst_remade == 0.0);
    assert_true(one_step > 0.0 && worst_between < one_step);
    free(got);
    tr_close(&c);
}

/* The clouds on winds of their own at time t against the same clouds standing where their winds carried them, no
 * wind: the drifting maps read where their clouds are (the maps lie on other grids of texels, as above). */
static double winds_follow(int clouds, double t)
{
    tr_ctx c;
    if (tr_open(&c, &cu_display_egl, W, H, 1))
        fail_msg("%s", c.err);
    float *a = malloc(sizeof(float) * NPX * 2), *b = a + NPX;
    fresh_render(&c, NULL, winds_scene(clouds, -1), t, a);
    fresh_render(&c, NULL, winds_scene(clouds, t), 0.0, b);
    double d = rel_diff(a, b);
    free(a);
    tr_close(&c);
    return d;
}

/* Two clouds on two winds: a map each, each drifting with its cloud, neither made again; each frame the whole
 * render at its time to float rounding (the clouds' offsets from a map's centre are worked out from other positions:
 * 2e-6 measured), and the shadows where the clouds are. */
static void test_two_winds_two_maps(void **st)
{
    (void)st;
    run_counts k;
    run(NULL, winds_scene(2, -1), 1.0, &k);
    double follows = winds_follow(2, FRAMES);
    printf("two winds, 1 s a frame: %d maps, whole remakes %d and %d, bands %d and %d, largest difference from the "
           "whole render %.3g (the picture moved by %.3g); against the clouds placed %.3g\n", k.maps, k.whole[0],
           k.whole[1], k.banded[0], k.banded[1], k.worst, k.moved, follows);
    assert_int_equal(k.maps, 2);
    assert_false(k.mixed);
    assert_true(k.whole[0] == 0 && k.whole[1] == 0 && k.banded[0] == 0 && k.banded[1] == 0);
    assert_true(k.moved > 0.02);
    assert_true(k.worst <= 1e-5);
    assert_true(follows < 1e-3);
}

/* Three winds, two maps: the third cloud shares the last map, which cannot drift and is made whole every frame; the
 * first map still drifts. Each frame the whole render, the shadows where the clouds are. */
static void test_more_winds_than_maps(void **st)
{
    (void)st;
    run_counts k;
    run(NULL, winds_scene(3, -1), 1.0, &k);
    double follows = winds_follow(3, FRAMES);
    printf("three winds, 1 s a frame: %d maps (the last mixed: %d), whole remakes %d and %d, largest difference from "
           "the whole render %.3g; against the clouds placed %.3g\n", k.maps, k.mixed, k.whole[0], k.whole[1],
           k.worst, k.moved > 0 ? follows : -1.0);
    assert_int_equal(k.maps, CU_GROUND_MAPS);
    assert_true(k.mixed);
    assert_int_equal(k.whole[0], 0);
    assert_int_equal(k.whole[1], FRAMES);
    assert_true(k.worst <= 1e-5);
    assert_true(follows < 1e-3);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_one_wind_moves_the_map_not_remakes_it),
        cmocka_unit_test(test_growing_cloud_patches_and_settles),
        cmocka_unit_test(test_bands_of_different_densities),
        cmocka_unit_test(test_cloud_shadow_follows_other_wind),
        cmocka_unit_test(test_two_winds_two_maps),
        cmocka_unit_test(test_more_winds_than_maps),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
