/* tests/gpu/test_profile.c: the renderer timing its passes (cu_renderer_set_profiling; src/gpu/profile.c,
 * pass_clock.c). On llvmpipe it picks the wall clock and says why (a CPU rasteriser's timestamps mark submission);
 * GPU timestamps, forced there, time every pass of EGL's GLES and OSMesa's desktop GL with no GL error, the passes
 * within the wall clock around the frame, also while a host's GL_TIME_ELAPSED query is open around cu_render (a
 * second TIME_ELAPSED query would be a GL error); a frame of more boundaries than queries puts the rest in the last
 * pass; profiling off makes no queries and reports nothing. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <GLES3/gl3.h>
#include <GLES2/gl2ext.h>
#include <EGL/egl.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include "pass_clock.h"
#include "render_util.h"
#include "renderer.h"

#define W 160
#define H 120

static char logged[256];

static void keep_profiling_line(void *user, cu_log_level level, const char *msg)
{
    (void)user;
    (void)level;
    if (strncmp(msg, "profiling:", 10) == 0)
        snprintf(logged, sizeof logged, "%s", msg);
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

/* Opens the back end with the first frame drawn unprofiled, then profiling on; timestamps: the clock made by hand
 * (the renderer would choose the wall clock on llvmpipe). */
static void open_profiled(tr_ctx *c, const cu_display_backend *be, int timestamps)
{
    if (tr_open(c, be, W, H, 0))
        fail_msg("%s", c->err);
    c->r->ctx.log = keep_profiling_line;
    logged[0] = 0;
    if (tr_render(c, "scenes/cumulus.scene", NULL))
        fail_msg("%s", c->err);
    if (timestamps) {
        cu_pass_clock_init(&c->r->prof, &c->r->gl, c->r->desc.get_proc_address, c->r->desc.get_proc_user,
                           c->r->is_gles, 1);
        assert_int_equal(c->r->prof.mode, CU_PASS_CLOCK_TIMESTAMPS);
    }
    cu_renderer_set_profiling(c->r, 1);
}

/* Frames timed pass by pass: every time finite and >= 0, the clouds' > 0, all of them within the wall clock around
 * the frame (glFinish before and after). */
static void check_frames(tr_ctx *c, int host_query)
{
    GLuint q = 0;
    if (host_query)
        glGenQueries(1, &q);
    for (int i = 0; i < 4; i++) {
        glFinish();
        double t0 = now_ms();
        if (host_query)
            glBeginQuery(GL_TIME_ELAPSED_EXT, q);
        if (tr_render_again(c))
            fail_msg("%s", c->err);
        if (host_query)
            glEndQuery(GL_TIME_ELAPSED_EXT);
        glFinish();
        double wall = now_ms() - t0, ms[CU_PASS_COUNT], sum = 0;
        assert_int_equal(cu_renderer_pass_times(c->r, ms), 0);
        for (int k = 0; k < CU_PASS_COUNT; k++) {
            assert_true(ms[k] >= 0 && ms[k] < 1e6);
            sum += ms[k];
        }
        assert_true(ms[CU_PASS_CLOUDS] > 0);
        if (sum > wall + 0.5)
            fail_msg("passes %.3f ms against %.3f ms of wall clock around the frame", sum, wall);
        assert_int_equal(glGetError(), GL_NO_ERROR);
    }
    if (host_query)
        glDeleteQueries(1, &q);
}

static void test_llvmpipe_gets_the_wall_clock(void **st)
{
    (void)st;
    tr_ctx c;
    open_profiled(&c, &cu_display_egl, 0);
    assert_string_equal(cu_renderer_profiling_clock(c.r), "not chosen yet");
    check_frames(&c, 0);
    assert_int_equal(c.r->prof.mode, CU_PASS_CLOCK_WALL);
    assert_string_equal(cu_renderer_profiling_clock(c.r), "wall clock, glFinish between passes");
    assert_non_null(strstr(logged, "a CPU rasteriser"));
    tr_close(&c);
}

static void test_timestamps_on_gles(void **st)
{
    (void)st;
    tr_ctx c;
    open_profiled(&c, &cu_display_egl, 1);
    check_frames(&c, 0);
    assert_string_equal(cu_renderer_profiling_clock(c.r), "GPU timestamps");
    tr_close(&c);
}

static void test_timestamps_on_desktop_gl(void **st)
{
    (void)st;
    tr_ctx c;
    open_profiled(&c, &cu_display_osmesa, 1);
    check_frames(&c, 0);
    tr_close(&c);
}

/* The host's GL_TIME_ELAPSED query is open around cu_render: timestamps do not nest, so both work. */
static void test_timestamps_inside_a_host_query(void **st)
{
    (void)st;
    tr_ctx c;
    open_profiled(&c, &cu_display_egl, 1);
    check_frames(&c, 1);
    tr_close(&c);
}

/* 30 boundaries with 24 queries: the time after the 23rd goes to the last pass named, nothing is lost. */
static void test_more_boundaries_than_queries(void **st)
{
    (void)st;
    tr_ctx c;
    open_profiled(&c, &cu_display_egl, 1);
    cu_pass_clock *k = &c.r->prof;
    double ms[CU_PASS_COUNT] = {0};
    cu_pass_clock_start(k, &c.r->gl);
    for (int i = 0; i < 30; i++)
        cu_pass_clock_boundary(k, &c.r->gl, i < 29 ? CU_PASS_SKY : CU_PASS_TONEMAP);
    assert_int_equal(k->n, CU_PASS_CLOCK_MARKS);
    assert_int_equal(k->pass[CU_PASS_CLOCK_MARKS - 1], CU_PASS_TONEMAP);
    assert_int_equal(cu_pass_clock_finish(k, &c.r->gl, ms, CU_PASS_COUNT), 0);
    assert_true(ms[CU_PASS_SKY] >= 0 && ms[CU_PASS_TONEMAP] >= 0 && ms[CU_PASS_CLOUDS] == 0);
    assert_int_equal(glGetError(), GL_NO_ERROR);
    tr_close(&c);
}

static void test_off_measures_nothing(void **st)
{
    (void)st;
    tr_ctx c;
    if (tr_open(&c, &cu_display_egl, W, H, 0))
        fail_msg("%s", c.err);
    if (tr_render(&c, "scenes/cumulus.scene", NULL) || tr_render_again(&c))
        fail_msg("%s", c.err);
    double ms[CU_PASS_COUNT];
    assert_int_equal(cu_renderer_pass_times(c.r, ms), 1);
    assert_int_equal(c.r->prof.mode, CU_PASS_CLOCK_UNSET);
    tr_close(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_llvmpipe_gets_the_wall_clock), cmocka_unit_test(test_timestamps_on_gles),
        cmocka_unit_test(test_timestamps_on_desktop_gl),    cmocka_unit_test(test_timestamps_inside_a_host_query),
        cmocka_unit_test(test_more_boundaries_than_queries), cmocka_unit_test(test_off_measures_nothing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
