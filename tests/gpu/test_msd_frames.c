/* tests/gpu/test_msd_frames.c: ms.mode = diffusion's grids solved again over frames (ms.frame_work; src/gpu/
 * pass_msd.c): after the sun turns past the grid's half degree, each frame runs only its work of the re-solve (a
 * sweep a frame at the least), the cloud keeps the light it has until the solve is done (the frames in between are
 * the same picture), the picture does not settle before (cu_renderer_settled: a still camera's frames go on until it
 * is done), and it settles to the picture of the same re-solve run in one frame, bit for bit. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "render_util.h"
#include "renderer.h"

#define W 48
#define H 36
#define NPX ((size_t)W * H * 3)
#define EL 30.0
#define AZ 135.0

/* The cumulus with its grid solved, then the sun turned 0.6 degrees: frames until the picture settles (at most
 * `most`), the last one in out; *sweeps the re-solve's sweeps. Every frame but the last is checked on the way. */
static int turn_and_settle(const char *work, int most, float *out, int *sweeps)
{
    tr_ctx c;
    if (tr_open(&c, &cu_display_egl, W, H, 1))
        fail_msg("%s", c.err);
    const char *sets[] = {"ms.mode=diffusion", "quality.sun_map_frames=1", "sun.elevation=30", "sun.azimuth=135",
                          work, NULL};
    if (tr_render(&c, "scenes/cumulus.scene", sets))
        fail_msg("%s", c.err);
    const cu_cloud_msd *m = &c.r->clouds.slot[0].msd;
    assert_int_equal(m->solved, 1); /* the first solve is whole, in the first frame */
    assert_int_equal(m->grid.solving, 0);
    assert_int_equal(cu_renderer_settled(c.r), 1);
    cu_error e;
    if (cu_renderer_set_sun(c.r, EL, AZ + 0.6, &e))
        fail_msg("%s", e.msg);
    float *prev = malloc(sizeof(float) * NPX);
    assert_non_null(prev);
    int frames = 0, last_sweeps = 0;
    for (; frames < most; frames++) {
        if (tr_render_again(&c))
            fail_msg("%s", c.err);
        tr_read_rgbf(&c, out);
        if (cu_renderer_settled(c.r))
            break;
        assert_int_equal(m->grid.solving, 1); /* only the grid keeps it from settling */
        if (frames > 0) {
            assert_int_equal(m->grid.sweeps, last_sweeps + 1); /* ms.frame_work = 1: a sweep a frame */
            assert_memory_equal(out, prev, sizeof(float) * NPX); /* the cloud keeps its light meanwhile */
        }
        last_sweeps = m->grid.sweeps;
        memcpy(prev, out, sizeof(float) * NPX);
    }
    assert_int_equal(m->grid.solving, 0);
    *sweeps = m->grid.sweeps;
    free(prev);
    tr_close(&c);
    return frames + 1;
}

static void test_resolve_over_frames(void **st)
{
    (void)st;
    float *spread = malloc(sizeof(float) * NPX), *whole = malloc(sizeof(float) * NPX);
    assert_non_null(spread);
    assert_non_null(whole);
    int sweeps_spread, sweeps_whole;
    int frames = turn_and_settle("ms.frame_work=1", 2000, spread, &sweeps_spread);
    int frames_whole = turn_and_settle("ms.frame_work=1000000", 5, whole, &sweeps_whole);
    print_message("the sun turned 0.6 degrees: the re-solve took %d frames at a sweep a frame (%d sweeps), %d at no "
                  "limit (%d sweeps)\n", frames, sweeps_spread, frames_whole, sweeps_whole);
    assert_int_equal(frames_whole, 1);
    assert_int_equal(sweeps_spread, sweeps_whole);
    assert_int_equal(frames, sweeps_spread); /* settled in the frame of its last sweep */
    assert_true(frames > 5);
    assert_memory_equal(spread, whole, sizeof(float) * NPX);
    free(spread);
    free(whole);
}

static void frame_from(tr_ctx *c, const char *pos, const char *look)
{
    if (tr_render_from(c, "scenes/cumulus.scene", pos, look))
        fail_msg("%s", c->err);
}

/* A cloud that comes into view in a running sky (the camera turned to it) gets its grid of half the cells a side
 * sampled and solved at once, and its own grid sampled and solved, from that answer, over the next frames; the picture settles to
 * within 1 % of a first frame that solved the grid whole (the two solves start from different places and stop at the
 * same tolerance), and the coarse grid's frame is already within 10 % of it. */
static void test_new_cloud_coarse_first(void **st)
{
    (void)st;
    static const char *pos = "0 300 -1500", *at = "0 300 0";
    const char *sets[] = {"ms.mode=diffusion", "quality.sun_map_frames=1", "camera.position=0 300 -1500",
                          "camera.look_at=0 300 -3000", NULL};
    const char *sets_at[] = {"ms.mode=diffusion", "quality.sun_map_frames=1", "camera.position=0 300 -1500",
                             "camera.look_at=0 300 0", NULL};
    float *img = malloc(sizeof(float) * NPX), *first = malloc(sizeof(float) * NPX), *whole = malloc(sizeof(float) * NPX);
    assert_true(img && first && whole);
    tr_ctx c;
    if (tr_open(&c, &cu_display_egl, W, H, 1))
        fail_msg("%s", c.err);
    if (tr_render(&c, "scenes/cumulus.scene", sets_at))
        fail_msg("%s", c.err);
    tr_read_rgbf(&c, whole);
    if (tr_render(&c, "scenes/cumulus.scene", sets)) /* a new scene, the cloud behind the camera */
        fail_msg("%s", c.err);
    const cu_cloud_msd *m = &c.r->clouds.slot[0].msd;
    assert_int_equal(m->solved, 0);
    frame_from(&c, pos, at);
    tr_read_rgbf(&c, first);
    assert_int_equal(m->solved, 1);
    assert_int_equal(m->pending, 1); /* 300 thousand cell updates: short of sampling and solving the whole grid */
    assert_non_null(m->coarse.ke);
    assert_int_equal(m->coarse.n[0], (m->grid.n[0] + 1) / 2);
    assert_true(m->tex_size.x > m->grid.h[0] * m->grid.n[0] - 1e-3); /* the coarse grid's box holds the fine one's */
    assert_int_equal(cu_renderer_settled(c.r), 0);
    int frames = 1;
    for (; !cu_renderer_settled(c.r) && frames < 200; frames++)
        frame_from(&c, pos, at);
    tr_read_rgbf(&c, img);
    assert_int_equal(m->grid.solving, 0);
    assert_null(m->coarse.ke); /* freed when the fine solve started from it */
    assert_true(m->tex_size.x < m->grid.h[0] * m->grid.n[0] + 1e-3); /* the fine grid's own texture */
    double d_first = tr_rel_diff(first, whole, NPX), d_final = tr_rel_diff(img, whole, NPX);
    print_message("a cloud coming into view: its own grid's light after %d frames; the coarse grid's frame %.4f off "
                  "the whole first solve's, the settled picture %.4f\n", frames, d_first, d_final);
    assert_true(frames > 1);
    assert_true(d_first > 0.0 && d_first < 0.10);
    assert_true(d_final < 0.01);
    tr_close(&c);
    free(img);
    free(first);
    free(whole);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_resolve_over_frames),
        cmocka_unit_test(test_new_cloud_coarse_first),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
