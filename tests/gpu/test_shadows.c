/* tests/gpu/test_shadows.c: clouds shade each other and the ground (src/gpu/pass_shadow.c): a cloud with another
 * between it and the sun is darker than alone, one on its far side from the sun changes nothing, and the ground
 * under a cloud loses the two-stream share of its direct sunlight where the geometry says its shadow falls. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "host_util.h"

static float px[N * 4];
static unsigned char mask[N]; /* cloud B's pixels, from its render alone */

/* Sets the scene text on the host's renderer. */
static void set_scene(const char *text)
{
    cu_scene *s;
    cu_error e;
    if (cu_scene_parse(&s, "shadow.scene", text, strlen(text), &e) || cu_renderer_set_scene(host_ctx.r, s, &e))
        fail_msg("%s", e.msg);
    cu_scene_free(s);
}

/* The clouds alone, premultiplied linear radiance over transparent black; returns the summed green radiance of
 * the pixels whose coverage exceeds 0.5 (with make_mask: and records them as B's; else only B's are summed), and
 * their count in *n. */
static double clouds_green(int *n, int make_mask)
{
    host_draw(fbo32, BLACK0, BLACK0, 0.0, NULL);
    host_render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1, .clouds_only = 1});
    host_read(fbo32, 1, px);
    double sum = 0;
    *n = 0;
    for (int i = 0; i < N; i++) {
        assert_true(isfinite(px[4 * i + 1]) && px[4 * i + 1] >= 0);
        if (make_mask)
            mask[i] = px[4 * i + 3] > 0.5;
        if (mask[i] && px[4 * i + 3] > 0.5) {
            sum += px[4 * i + 1];
            (*n)++;
        }
    }
    return sum;
}

/* Cloud B (radius 200 m) at 1 km seen from the west, the sun in the south at 60 degrees; cloud A (radius 400 m, so
 * its disc seen from the sun covers B's) is put 900 m from B toward the sun (between B and the sun: its shadow
 * covers B) or 1200 m north of it, away from the sun (B may shade A, nothing shades B). A is in view above B
 * (7 degrees up), but apart from B on screen: only B's pixels (those it covers alone) are compared. The sky light
 * is off: it is not shadowed, and here it is 60 % of B's light. The sun maps are 16 texels and one program marches,
 * whatever the clouds' count (a field's maps and level of detail follow their size on screen: with lod_pixels at its
 * default B, 26 pixels wide, is marched with half the segments, 3.3 % darker here). */
#define SHADOW_HEAD                                                                                               \
    "[camera]\nposition = -3000 1000 0\nlook_at = 0 1000 0\nfov = 20\n[sun]\nelevation = 60\nazimuth = 180\n"      \
    "[quality]\nnoise = off\nsun_map_size = 16\nlod_pixels = 0\n[ms]\nsky_light = off\n[cloud]\nboundary = 20\n[ellipsoid]\n"        \
    "center = 0 1000 0\nradii = 200 200 200\n"

static void test_cloud_under_cloud_is_darker(void **st)
{
    (void)st;
    int n_alone, n_under, n_far;
    set_scene(SHADOW_HEAD);
    double alone = clouds_green(&n_alone, 1);
    /* the sun's direction: azimuth 180 (south, +z), elevation 60: (0, sin 60, cos 60) */
    set_scene(SHADOW_HEAD "[cloud]\n[ellipsoid]\ncenter = 0 1779.4 450\nradii = 400 400 400\n");
    double under = clouds_green(&n_under, 0);
    set_scene(SHADOW_HEAD "[cloud]\n[ellipsoid]\ncenter = 0 1000 -1200\nradii = 400 400 400\n");
    double far = clouds_green(&n_far, 0);
    printf("B's green radiance over %d pixels: alone %.4g, A toward the sun %.4g (%.3f), A away %.4g (%.6f)\n",
           n_alone, alone, under, under / alone, far, far / alone);
    assert_true(n_alone > 300);
    /* the shade: A's optical depth along the sun through its centre is 800 m x 0.09 /m = 72, so the direct sunlight
     * on B is gone and its multiple scattering falls to the two-stream share, 1 / (1 + 0.75 x 0.14 x tau) = 0.12 at
     * A's centre and more toward A's rim; B must lose at least half its light. Without the shadow: 1.000. */
    assert_int_equal(n_under, n_alone);
    assert_true(under < 0.5 * alone);
    /* A on B's far side: B is the caster there, nothing shades B: the same pixels to float rounding */
    assert_int_equal(n_far, n_alone);
    assert_true(fabs(far / alone - 1.0) < 1e-5);
}

/* The ground under a cloud: the camera at 50 m looks down 45 degrees at the point G where the sun's ray through the
 * cloud's centre meets the ground; the cloud (at 1 km, 14 degrees or more above the view) is out of view. */
static void test_ground_shadow(void **st)
{
    (void)st;
    const char *head = "[camera]\nposition = -1154.7 50 -50\nlook_at = -1154.7 0 0\nfov = 10\n"
                       "[sun]\nelevation = 40\nazimuth = 90\n[quality]\nnoise = off\n[cloud]\nboundary = 20\n";
    /* sun from the east (+x) at 40 degrees: the cloud's centre (0, 1000 - ..., 0) casts onto x = -1000 / tan 40 */
    static float clear[N * 4], shade[N * 4], aside[N * 4];
    char text[1024];
    snprintf(text, sizeof text, "%s", head);
    set_scene(text);
    host_draw(fbo32, BLACK0, BLACK0, 0.0, NULL);
    host_render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1});
    host_read(fbo32, 1, clear);
    snprintf(text, sizeof text, "%s[ellipsoid]\ncenter = 0 968.9 0\nradii = 300 300 300\n", head);
    set_scene(text);
    host_draw(fbo32, BLACK0, BLACK0, 0.0, NULL);
    host_render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1});
    host_read(fbo32, 1, shade);
    snprintf(text, sizeof text, "%s[ellipsoid]\ncenter = 0 968.9 5000\nradii = 300 300 300\n", head);
    set_scene(text);
    host_draw(fbo32, BLACK0, BLACK0, 0.0, NULL);
    host_render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1});
    host_read(fbo32, 1, aside);
    int c = (H / 2) * W + W / 2;
    double r = shade[4 * c + 1] / clear[4 * c + 1], ra = aside[4 * c + 1] / clear[4 * c + 1];
    printf("ground at the shadow's centre: %.4g against %.4g in the clear (%.3f); cloud 5 km aside: %.6f\n",
           shade[4 * c + 1], clear[4 * c + 1], r, ra);
    for (int i = 0; i < N; i++)
        assert_true(isfinite(shade[4 * i + 1]) && shade[4 * i + 1] > 0);
    /* optical depth about 600 m x 0.09 /m = 54 through the centre: the direct share of the ground's light drops to
     * the two-stream 1 / (1 + 0.75 x 0.14 x 54) = 0.15; the sun is most of the ground's light at 40 degrees */
    assert_true(r < 0.6);
    assert_true(r > 0.05); /* the sky still lights it */
    assert_true(fabs(ra - 1.0) < 1e-6); /* a cloud whose shadow falls elsewhere changes nothing here */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cloud_under_cloud_is_darker),
        cmocka_unit_test(test_ground_shadow),
    };
    return cmocka_run_group_tests(tests, host_setup, host_teardown);
}
