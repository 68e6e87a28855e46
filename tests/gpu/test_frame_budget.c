/* tests/gpu/test_frame_budget.c: the frame budget in the renderer (quality.target_fps; src/gpu/frame_budget.c,
 * frame_timer.c): a budget no frame can meet walks the whole ladder to the coarsest rung, one logged change a rung,
 * with GPU timer queries and with the wall clock, and stays there when the scene is set again; a budget every frame
 * meets changes nothing, not a pixel; after the walk a still view converges to the picture of those settings set by
 * hand; a timer query's frame is no longer than the wall clock around it; a host that has a timer query of its own
 * open gets its frame drawn, unmeasured; and cu_renderer_settled counts the frames a temporal grid still needs. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <EGL/egl.h>
#include <GLES3/gl3.h>
#include <GLES2/gl2ext.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "frame_timer.h"
#include "render_util.h"
#include "renderer.h"

#define W 160
#define H 120
#define PX ((size_t)W * H * 4)

static int changes; /* "frame budget: frames take ..." lines logged */

static void count_changes(void *user, cu_log_level level, const char *msg)
{
    (void)user;
    (void)level;
    if (strncmp(msg, "frame budget: frames take", 25) == 0)
        changes++;
}

static void open_with(tr_ctx *c, const char *const *sets, int wall_clock)
{
    if (tr_open(c, &cu_display_egl, W, H, 0))
        fail_msg("%s", c->err);
    c->r->ctx.log = count_changes;
    c->r->fb.no_queries = wall_clock;
    changes = 0;
    if (tr_render(c, "scenes/cumulus.scene", sets))
        fail_msg("%s", c->err);
}

static void frames(tr_ctx *c, int n)
{
    for (int i = 0; i < n; i++)
        if (tr_render_again(c))
            fail_msg("%s", c->err);
}

/* 1000 fps is out of reach: every rung is too slow, so the budget walks down the ladder, a rung a window. */
static void walk_down(int wall_clock)
{
    tr_ctx c;
    const char *sets[] = {"quality.target_fps=1000", "quality.max_downsample=2", "quality.max_temporal_grid=4", NULL};
    open_with(&c, sets, wall_clock);
    int d, g;
    double ms;
    assert_int_equal(cu_renderer_budget(c.r, &d, &g, &ms), 0);
    assert_int_equal(d, 1);
    assert_int_equal(g, 1);
    assert_int_equal(c.r->fb.budget.n, 5); /* (1,1) (2,1) (2,2) (2,3) (2,4) */
    assert_int_equal(c.r->fb.timer.mode, wall_clock ? CU_TIMER_WALL : CU_TIMER_QUERY);
    /* a window and its settling frames a rung, and the queries' frames in flight */
    frames(&c, (CU_BUDGET_WINDOW + CU_BUDGET_SETTLE) * 4 + CU_FRAME_TIMER_QUERIES + 2);
    assert_int_equal(cu_renderer_budget(c.r, &d, &g, &ms), 0);
    assert_int_equal(d, 2);
    assert_int_equal(g, 4);
    assert_true(ms > 1.0 && isfinite(ms));
    assert_int_equal(changes, 4);
    frames(&c, 20); /* nowhere further to go */
    assert_int_equal(changes, 4);
    /* the same scene again (an image generator rebuilding its layers): the budget stays where it stood */
    if (tr_render(&c, "scenes/cumulus.scene", sets))
        fail_msg("%s", c.err);
    assert_int_equal(cu_renderer_budget(c.r, &d, &g, &ms), 0);
    assert_int_equal(d, 2);
    assert_int_equal(g, 4);
    frames(&c, 16);
    assert_int_equal(changes, 4);

    /* a still view converges to the picture of these settings set by hand (16 frames for a 4 x 4 grid) */
    uint8_t *got = malloc(PX), *ref = malloc(PX);
    assert_non_null(got);
    assert_non_null(ref);
    tr_read_rgba8(&c, got);
    tr_close(&c);
    const char *hand[] = {"quality.cloud_downsample=2", NULL};
    if (tr_open(&c, &cu_display_egl, W, H, 0) || tr_render(&c, "scenes/cumulus.scene", hand))
        fail_msg("%s", c.err);
    tr_read_rgba8(&c, ref);
    tr_diff df = tr_compare_rgba8(got, ref, W, H, 1);
    if (df.max_diff > 1)
        tr_save_failure("frame_budget", got, ref, W, H);
    assert_true(df.max_diff <= 1);
    tr_close(&c);
    free(got);
    free(ref);
}

static void test_walks_down_with_queries(void **st)
{
    (void)st;
    walk_down(0);
}

static void test_walks_down_with_the_wall_clock(void **st)
{
    (void)st;
    walk_down(1);
}

/* 1 fps: every frame fits; nothing moves and the picture is the one without a budget, bit for bit. */
static void test_generous_budget_changes_nothing(void **st)
{
    (void)st;
    tr_ctx c;
    const char *sets[] = {"quality.target_fps=1", NULL};
    open_with(&c, sets, 0);
    frames(&c, 20);
    int d, g;
    double ms;
    assert_int_equal(cu_renderer_budget(c.r, &d, &g, &ms), 0);
    assert_int_equal(d, 1);
    assert_int_equal(g, 1);
    assert_int_equal(changes, 0);
    assert_true(ms > 0 && ms < 1000);
    uint8_t *got = malloc(PX), *ref = malloc(PX);
    assert_non_null(got);
    assert_non_null(ref);
    tr_read_rgba8(&c, got);
    tr_close(&c);
    open_with(&c, NULL, 0);
    assert_int_equal(cu_renderer_budget(c.r, &d, &g, &ms), 1); /* no budget: the scene's own settings */
    assert_int_equal(d, 1);
    assert_int_equal(g, 1);
    tr_read_rgba8(&c, ref);
    assert_memory_equal(got, ref, PX);
    tr_close(&c);
    free(got);
    free(ref);
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

/* The timer's frame lies within the wall clock around it (the GPU cannot work on a frame longer than from its first
 * command to glFinish's return); it is read back once, after the GPU says it is ready. */
static void test_query_within_wall_clock(void **st)
{
    (void)st;
    tr_ctx c;
    open_with(&c, NULL, 0);
    cu_frame_timer t;
    cu_frame_timer_init(&t, &c.r->gl, NULL, NULL, c.r->is_gles, 1); /* NULL: the process's, then EGL's */
    assert_int_equal(t.mode, CU_TIMER_QUERY);
    for (int i = 0; i < 6; i++) {
        glFinish();
        double t0 = now_ms();
        cu_frame_timer_begin(&t, &c.r->gl);
        if (tr_render_again(&c))
            fail_msg("%s", c.err);
        cu_frame_timer_end(&t, &c.r->gl);
        glFinish();
        double wall = now_ms() - t0, ms = -1;
        assert_int_equal(cu_frame_timer_poll(&t, &c.r->gl, &ms), 1); /* finished: the result is there */
        assert_int_equal(cu_frame_timer_poll(&t, &c.r->gl, &ms), 0); /* and given once */
        assert_true(ms > 0 && ms <= wall + 0.5);
    }
    assert_int_equal(glGetError(), GL_NO_ERROR);
    cu_frame_timer_free(&t, &c.r->gl);
    tr_close(&c);
}

/* The host times its own work with a timer query around cu_render: queries of one target do not nest, so cumulo's
 * frame goes unmeasured, and the host's query and the frame are fine. */
static void test_host_query_open(void **st)
{
    (void)st;
    tr_ctx c;
    const char *sets[] = {"quality.target_fps=1000", NULL};
    open_with(&c, sets, 0);
    frames(&c, CU_FRAME_TIMER_QUERIES + 1); /* the frames in flight so far are read back */
    long seen = c.r->fb.budget.frame;
    PFNGLGETQUERYOBJECTUI64VEXTPROC get_ui64 =
        (PFNGLGETQUERYOBJECTUI64VEXTPROC)eglGetProcAddress("glGetQueryObjectui64vEXT");
    assert_non_null(get_ui64);
    GLuint q;
    glGenQueries(1, &q);
    for (int i = 0; i < 12; i++) {
        glBeginQuery(GL_TIME_ELAPSED_EXT, q);
        if (tr_render_again(&c))
            fail_msg("%s", c.err);
        glEndQuery(GL_TIME_ELAPSED_EXT);
        GLuint64 ns = 0;
        get_ui64(q, GL_QUERY_RESULT, &ns);
        assert_true(ns > 0);
        assert_int_equal(glGetError(), GL_NO_ERROR);
    }
    frames(&c, CU_FRAME_TIMER_QUERIES + 1);
    /* only the frames without the host's query were measured (the ones in flight before, and the last few) */
    assert_true(c.r->fb.budget.frame - seen <= CU_FRAME_TIMER_QUERIES + 1 + CU_FRAME_TIMER_QUERIES);
    glDeleteQueries(1, &q);
    tr_close(&c);
}

/* cu_renderer_settled: a frame drawn whole has settled; after a small turn of the camera a 2 x 2 grid needs three more
 * frames of the same view (the four pixels of each block), and a further change starts the count again. */
static void test_settled(void **st)
{
    (void)st;
    tr_ctx c;
    const char *sets[] = {"quality.temporal_grid=2", NULL};
    open_with(&c, sets, 0);
    assert_int_equal(cu_renderer_settled(c.r), 1); /* the first frame: whole */
    cu_scene *s;
    cu_error e;
    if (cu_scene_load(&s, "scenes/cumulus.scene", &e))
        fail_msg("%s", e.msg);
    s->cam_look[0] += 0.002 * (s->cam_look[2] - s->cam_pos[2]); /* a turn of about a tenth of a degree */
    float view[16], proj[16];
    if (cu_scene_camera_matrices(s, (double)W / H, 1.0, 1.0e5, view, proj, &e))
        fail_msg("%s", e.msg);
    unsigned fbo;
    int w, h;
    c.be->frame(c.disp, &fbo, &w, &h);
    cu_frame f = {.fbo = fbo, .width = w, .height = h, .view = view, .projection = proj};
    int got[6];
    for (int i = 0; i < 6; i++) {
        if (i == 4)
            view[12] += 1.0f; /* the camera moves a metre: counting again */
        if (cu_render(c.r, &f, &e))
            fail_msg("%s", e.msg);
        got[i] = cu_renderer_settled(c.r);
    }
    assert_int_equal(got[0], 0);
    assert_int_equal(got[1], 0);
    assert_int_equal(got[2], 0);
    assert_int_equal(got[3], 1);
    assert_int_equal(got[4], 0);
    assert_int_equal(got[5], 0);
    cu_scene_free(s);
    tr_close(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_walks_down_with_queries),   cmocka_unit_test(test_walks_down_with_the_wall_clock),
        cmocka_unit_test(test_generous_budget_changes_nothing), cmocka_unit_test(test_query_within_wall_clock),
        cmocka_unit_test(test_host_query_open),           cmocka_unit_test(test_settled),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
