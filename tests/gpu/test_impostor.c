/* tests/gpu/test_impostor.c: impostors (quality.impostor_pixels; src/gpu/frame_impostor.c, pass_impostor.c) against
 * the full render of the same frames: a field of clouds seen from the ground, most of them small, when the images
 * are made; the camera turning slowly (the images kept while the direction turns less than impostor_degrees); a still
 * view makes no image after the first frame; a cloud approached through the switch size does not pop (the step at
 * the switch is no larger than the full render's own steps); the temporal grid and a linear target take them too. */
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

#define W 200
#define H 120
#define PX ((size_t)W * H * 4)

static cu_scene *scene_with(const char *path, const char *const *sets)
{
    cu_scene *s;
    cu_error e;
    if (cu_scene_load(&s, path, &e))
        fail_msg("%s", e.msg);
    for (int i = 0; sets && sets[i]; i++)
        if (cu_scene_set(s, sets[i], &e))
            fail_msg("%s: %s", sets[i], e.msg);
    return s;
}

/* A frame from the scene's camera turned yaw_deg to the right and moved `forward` metres along its view. */
static void frame(tr_ctx *c, const cu_scene *base, double yaw_deg, double forward, uint8_t *rgba)
{
    double p[3], l[3], d[3], len = 0;
    memcpy(p, base->cam_pos, sizeof p);
    memcpy(l, base->cam_look, sizeof l);
    for (int i = 0; i < 3; i++) {
        d[i] = l[i] - p[i];
        len += d[i] * d[i];
    }
    len = sqrt(len);
    double a = yaw_deg * CU_PI / 180.0, dx = d[0] * cos(a) - d[2] * sin(a), dz = d[0] * sin(a) + d[2] * cos(a);
    d[0] = dx;
    d[2] = dz;
    for (int i = 0; i < 3; i++)
        p[i] += d[i] / len * forward;
    cu_scene *s = scene_with("scenes/cumulus.scene", NULL);
    memcpy(s->cam_pos, p, sizeof p);
    for (int i = 0; i < 3; i++)
        s->cam_look[i] = p[i] + d[i];
    s->cam_fov = base->cam_fov;
    float view[16], proj[16];
    cu_error e;
    if (cu_scene_camera_matrices(s, (double)W / H, 1.0, 1.0e5, view, proj, &e))
        fail_msg("%s", e.msg);
    unsigned fbo;
    int w, h;
    c->be->frame(c->disp, &fbo, &w, &h);
    cu_frame f = {.fbo = fbo, .width = w, .height = h, .linear = c->linear, .view = view, .projection = proj};
    if (cu_render(c->r, &f, &e))
        fail_msg("%s", e.msg);
    if (rgba)
        tr_read_rgba8(c, rgba);
    cu_scene_free(s);
}

typedef struct run {
    uint8_t *img;  /* n frames */
    long made;     /* impostor images made over the run */
    long drawn;    /* clouds drawn from impostors in the last frame */
    int first_full;/* the first frame in which no cloud was drawn from an impostor (-1: none) */
} run;

/* Renders the path (yaw, forward per frame) of `path` with the scene and sets given. */
static run render_path(const char *path, const char *const *sets, double (*pose)[2], int n)
{
    tr_ctx c;
    if (tr_open(&c, &cu_display_egl, W, H, 0))
        fail_msg("%s", c.err);
    cu_scene *s = scene_with(path, sets);
    cu_error e;
    if (cu_renderer_set_scene(c.r, s, &e))
        fail_msg("%s", e.msg);
    run out = {malloc(PX * (size_t)n), 0, 0, -1};
    assert_non_null(out.img);
    for (int k = 0; k < n; k++) {
        frame(&c, s, pose[k][0], pose[k][1], out.img + PX * (size_t)k);
        out.drawn = 0;
        for (int i = 0; i < c.r->clouds.n; i++)
            out.drawn += c.r->clouds.slot[i].imp.in_use;
        if (out.drawn == 0 && out.first_full < 0)
            out.first_full = k;
    }
    out.made = c.r->impostors_made;
    cu_scene_free(s);
    tr_close(&c);
    return out;
}

static double worst_psnr(const run *a, const run *b, int n, int *max_diff, const char *name)
{
    double worst = 99;
    *max_diff = 0;
    for (int k = 0; k < n; k++) {
        tr_diff d = tr_compare_rgba8(a->img + PX * (size_t)k, b->img + PX * (size_t)k, W, H, 4);
        if (d.psnr < worst) {
            worst = d.psnr;
            if (d.psnr < (getenv("CUMULO_TEST_SAVE") ? 99 : 35))
                tr_save_failure(name, a->img + PX * (size_t)k, b->img + PX * (size_t)k, W, H);
        }
        if (d.max_diff > *max_diff)
            *max_diff = d.max_diff;
    }
    return worst;
}

/* field_noon from the ground: most clouds are smaller than 64 pixels here. The camera turns 0.3 degrees a frame (the
 * images stay exact: the eye does not move) and flies 150 m a frame toward the clouds (the direction to the nearer
 * ones turns by up to a degree a frame: their images are made again, four a frame, nearest first). */
static void test_field_against_full_render(void **st)
{
    (void)st;
    enum { N = 10 };
    double pose[N][2];
    for (int k = 0; k < N; k++)
        pose[k][0] = 0.3 * k, pose[k][1] = 150.0 * k;
    const char *full[] = {"quality.impostor_pixels=0", NULL}, *imp[] = {"quality.impostor_pixels=64", NULL};
    run a = render_path("scenes/field_noon.scene", full, pose, N), b = render_path("scenes/field_noon.scene", imp,
                                                                                   pose, N);
    int maxd;
    double psnr = worst_psnr(&b, &a, N, &maxd, "impostor_field");
    printf("field_noon, %ld clouds from impostors: worst %.1f dB (max difference %d/255) over %d frames turning 0.3 "
           "deg and flying 150 m a frame; %ld images made\n", b.drawn, psnr, maxd, N, b.made);
    assert_true(b.drawn >= 5);
    assert_true(a.made == 0);
    /* every image made in the first frame, then about one in three frames each: fewer than all of them every frame */
    assert_true(b.made < (long)b.drawn * N / 2);
    assert_true(psnr >= 40.0);
    free(a.img);
    free(b.img);
}

/* A still view makes its images once: the frames after the first re-march nothing, and equal the first; with Kol's
 * method (the sun of the cloud's maps) and with the uniform march (no maps: the sun itself). */
static void test_still_view_makes_images_once(void **st)
{
    (void)st;
    double pose[4][2] = {{0, 0}, {0, 0}, {0, 0}, {0, 0}};
    const char *methods[2][3] = {{"quality.impostor_pixels=64", NULL, NULL},
                                 {"quality.impostor_pixels=64", "quality.method=uniform", NULL}};
    for (int m = 0; m < 2; m++) {
        run b = render_path("scenes/field_noon.scene", methods[m], pose, 4);
        run one = render_path("scenes/field_noon.scene", methods[m], pose, 1);
        assert_int_equal(b.made, one.made);
        assert_true(one.made >= 5);
        for (int k = 1; k < 4; k++)
            assert_memory_equal(b.img + PX * (size_t)k, b.img, PX);
        free(b.img);
        free(one.img);
    }
}

/* The cumulus approached from 7.2 km to the scene's 1.2 km: it grows to about 60 pixels, through 40, where it stops
 * being drawn from its image. The step at the switch is no larger than the largest step of the full render's own frames. */
static void test_no_pop_at_the_switch(void **st)
{
    (void)st;
    enum { N = 13 };
    double pose[N][2];
    for (int k = 0; k < N; k++)
        pose[k][0] = 0, pose[k][1] = -6000.0 + 500.0 * k; /* backwards from the scene's camera, then nearer */
    const char *full[] = {"quality.impostor_pixels=0", NULL}, *imp[] = {"quality.impostor_pixels=40", NULL};
    run a = render_path("scenes/cumulus.scene", full, pose, N), b = render_path("scenes/cumulus.scene", imp, pose, N);
    int maxd;
    double psnr = worst_psnr(&b, &a, N, &maxd, "impostor_switch");
    double worst_step = 0, worst_ref_step = 0;
    for (int k = 1; k < N; k++) {
        tr_diff sb = tr_compare_rgba8(b.img + PX * (size_t)k, b.img + PX * (size_t)(k - 1), W, H, 4);
        tr_diff sa = tr_compare_rgba8(a.img + PX * (size_t)k, a.img + PX * (size_t)(k - 1), W, H, 4);
        double eb = pow(10.0, -sb.psnr / 10.0), ea = pow(10.0, -sa.psnr / 10.0); /* mean squared steps */
        worst_step = fmax(worst_step, eb);
        worst_ref_step = fmax(worst_ref_step, ea);
    }
    printf("approach: drawn from its image until frame %d; worst %.1f dB against the full render (max %d/255); "
           "largest step %.2f dB, the full render's %.2f dB; %ld images made\n", b.first_full, psnr, maxd,
           -10 * log10(worst_step), -10 * log10(worst_ref_step), b.made);
    assert_true(b.first_full > 2 && b.first_full < N - 1); /* the switch is inside the path */
    assert_true(b.made >= 2); /* made again as it grew */
    assert_true(psnr >= 40.0);
    assert_true(worst_step <= 1.1 * worst_ref_step);
    free(a.img);
    free(b.img);
}

/* With the temporal grid and into a linear float target: the same frames, finite, near the full render. */
static void test_with_grid_and_linear(void **st)
{
    (void)st;
    enum { N = 6 };
    double pose[N][2];
    for (int k = 0; k < N; k++)
        pose[k][0] = 0.2 * k, pose[k][1] = 0;
    const char *full[] = {"quality.temporal_grid=2", NULL},
               *imp[] = {"quality.temporal_grid=2", "quality.impostor_pixels=64", NULL};
    run a = render_path("scenes/field_noon.scene", full, pose, N), b = render_path("scenes/field_noon.scene", imp,
                                                                                   pose, N);
    int maxd;
    double psnr = worst_psnr(&b, &a, N, &maxd, "impostor_grid");
    printf("with a 2 x 2 grid: worst %.1f dB (max %d/255)\n", psnr, maxd);
    assert_true(b.drawn >= 5);
    assert_true(psnr >= 38.0);
    free(a.img);
    free(b.img);

    tr_ctx c;
    if (tr_open(&c, &cu_display_egl, W, H, 1))
        fail_msg("%s", c.err);
    cu_scene *s = scene_with("scenes/field_noon.scene", imp + 1);
    cu_error e;
    if (cu_renderer_set_scene(c.r, s, &e))
        fail_msg("%s", e.msg);
    float *px = malloc(sizeof(float) * 3 * W * H);
    assert_non_null(px);
    frame(&c, s, 0, 0, NULL);
    tr_read_rgbf(&c, px);
    for (long i = 0; i < 3L * W * H; i++)
        assert_true(isfinite(px[i]) && px[i] >= 0);
    assert_true(c.r->impostors_made >= 5);
    free(px);
    cu_scene_free(s);
    tr_close(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_field_against_full_render), cmocka_unit_test(test_still_view_makes_images_once),
        cmocka_unit_test(test_no_pop_at_the_switch),      cmocka_unit_test(test_with_grid_and_linear),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
