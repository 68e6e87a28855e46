/* tests/gpu/test_sky.c: the sky pass against the CPU's Preetham model (sky.c: cu_sky_radiance, in double precision):
 * every pixel of the analytic sky, through both headless back ends, over sun elevations from the horizon to high noon,
 * a clear and a hazy sky, and views toward the sun, the zenith and the horizon. The pass reads the Perez function as
 * the product of two tables (cu_sky_tables); this is what says the tables, their spacing, their storage and the
 * shader's lookup reproduce the model. And the rows: the pass draws rows of sky alone, of ground alone and rows
 * holding the horizon with programs of their own (pass_sky.c); host cameras rolled and pitched every way put each
 * pixel above the horizon on the sky and each below on the ground, in radiance and tone-mapped. And the grid
 * (quality.sky_grid): the sky interpolated from the corners of cells, against the sky at every pixel. And a constant
 * sky drawn flat with the sun's disk over it. */
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
#include "sky.h"
#include "tonemap.h"

static const cu_display_backend *const backends[] = {&cu_display_egl, &cu_display_osmesa};
static const char *const backend_names[] = {"egl", "osmesa"};

#define W 96
#define H 72

/* scenes/cumulus.scene with `sets` applied (NULL-terminated), as the renderer was given it. */
static cu_scene *scene_with(const char *const *sets)
{
    cu_scene *s;
    cu_error e;
    assert_int_equal(cu_scene_load(&s, "scenes/cumulus.scene", &e), 0);
    for (int i = 0; sets[i]; i++)
        assert_int_equal(cu_scene_set(s, sets[i], &e), 0);
    return s;
}

/* One sky: renders it (linear output: radiance itself) and compares each pixel above the horizon and away from the
 * sun's disk with the CPU. Returns the largest relative error of any channel brighter than 2 % of the pixel's
 * brightest; *median gets the median of the pixels' largest errors. */
static double sky_error(tr_ctx *c, const char *const *sets, double *median)
{
    if (tr_render(c, "scenes/cumulus.scene", sets))
        fail_msg("%s", c->err);
    float *px = malloc(sizeof(float) * 3 * W * H);
    double *errs = malloc(sizeof(double) * W * H);
    assert_non_null(px);
    assert_non_null(errs);
    tr_read_rgbf(c, px);
    cu_scene *s = scene_with(sets);
    cu_sky sky;
    cu_sky_compute(&sky, s);
    double worst = 0;
    int n = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            vec3 d = tr_pixel_dir(s, W, H, x, y);
            if (d.y < 1e-3 || v3_dot(d, sky.sun_dir) > cos(1.0 * CU_PI / 180.0))
                continue;
            double want[3], peak = 0, err = 0;
            cu_sky_radiance(&sky, s, d, want);
            for (int k = 0; k < 3; k++)
                peak = want[k] > peak ? want[k] : peak;
            for (int k = 0; k < 3; k++) {
                const float got = px[3 * (y * W + x) + k];
                assert_false(isnan(got) || isinf(got));
                if (want[k] > 0.02 * peak) {
                    double r = fabs(got - want[k]) / want[k];
                    err = r > err ? r : err;
                }
            }
            errs[n++] = err;
            worst = err > worst ? err : worst;
        }
    assert_true(n > W * H / 8); /* the view holds sky to judge */
    for (int i = 1; i < n; i++) /* insertion sort: a few thousand values */
        for (int j = i; j > 0 && errs[j - 1] > errs[j]; j--) {
            double t = errs[j];
            errs[j] = errs[j - 1];
            errs[j - 1] = t;
        }
    *median = errs[n / 2];
    free(px);
    free(errs);
    cu_scene_free(s);
    return worst;
}

static void test_sky_is_preetham(void **st)
{
    (void)st;
    static const char *const elevations[] = {"sun.elevation=0.5", "sun.elevation=4", "sun.elevation=25",
                                             "sun.elevation=70"};
    static const char *const turbidities[] = {"sun.turbidity=2", "sun.turbidity=8"};
    /* toward the sun (its azimuth in cumulus.scene) low and high, straight up, and away from it along the horizon */
    static const char *const views[] = {"camera.look_at=0 160 -900", "camera.look_at=0 900 -900",
                                        "camera.look_at=1 5000 -1", "camera.look_at=0 160 900"};
    for (int b = 0; b < 2; b++) {
        tr_ctx c;
        if (tr_open(&c, backends[b], W, H, 1))
            fail_msg("%s", c.err);
        double worst = 0, worst_median = 0;
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 2; j++)
                for (int v = 0; v < 4; v++) {
                    const char *sets[] = {"cloud.density=0", "sky.model=preetham", elevations[i], turbidities[j],
                                          views[v], "camera.fov=70", "quality.sky_grid=0", NULL};
                    double median, err = sky_error(&c, sets, &median);
                    if (err > worst || getenv("CUMULO_TEST_DEBUG"))
                        printf("%s: %s %s %s: max %.5f median %.5f\n", backend_names[b], elevations[i],
                               turbidities[j], views[v], err, median);
                    worst = err > worst ? err : worst;
                    worst_median = median > worst_median ? median : worst_median;
                }
        printf("%s: the sky against cu_sky_radiance: max relative error %.5f, worst median %.5f\n", backend_names[b],
               worst, worst_median);
        /* Measured: 0.0006 and 0.00003. The same tables in fp16 give 0.029 and 0.0038 (xyY -> RGB amplifies their
         * rounding), read through a lowp sampler (GLES's default in a fragment shader) 0.08 and 0.004. */
        assert_true(worst < 0.002);
        assert_true(worst_median < 0.0002);
        tr_close(&c);
    }
}

/* A host camera at the scene's position looking along dir, rolled by roll degrees about it, fov degrees high, for a w x
 * h frame. */
static void rolled_camera(const cu_scene *s, vec3 dir, double roll, double fov, int w, int h, float view[16],
                          float proj[16], mat4 *inv)
{
    vec3 f = v3_norm(dir), side = v3_cross(f, v3(0, 1, 0));
    if (v3_len(side) < 1e-6) /* straight up or down */
        side = v3(1, 0, 0);
    side = v3_norm(side);
    double a = roll * CU_PI / 180;
    vec3 up = v3_add(v3_scale(v3_cross(side, f), cos(a)), v3_scale(side, sin(a)));
    mat4 rot = m4_look_dir(v3(0, 0, 0), f, up), eye = m4_look_dir(v3_from(s->cam_pos), f, up);
    mat4 p = m4_perspective(fov * CU_PI / 180.0, (double)w / h, 1.0, 1e5);
    m4_to_float(eye, view);
    m4_to_float(p, proj);
    *inv = m4_inverse(m4_mul(p, rot));
}

/* The direction through the centre of pixel (x, y) of a w x h frame, top row first, through inv (clip ->
 * direction). */
static vec3 pixel_dir(mat4 inv, int w, int h, int x, int y)
{
    double c[4] = {(x + 0.5) / w * 2 - 1, 1 - (y + 0.5) / h * 2, 1, 1}, o[4] = {0, 0, 0, 0};
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 4; k++)
            o[i] += inv.m[k * 4 + i] * c[k];
    return v3_norm(v3(o[0] / o[3], o[1] / o[3], o[2] / o[3]));
}

static void test_sky_and_ground_in_rows(void **st)
{
    (void)st;
    /* level, rolled 30, 90 (the horizon up the screen) and 180 degrees (the ground on top), pitched down and up so
     * the horizon crosses a corner, straight down (ground alone) and straight up (sky alone) */
    static const double views[][4] = {{0, -0.1, -1, 0}, {0, -0.1, -1, 30}, {0, 0.2, -1, 90}, {0, 0.1, -1, 180},
                                      {1, -0.6, -1, 20}, {-1, 0.5, 1, -35}, {0, -1, 0, 0}, {0, 1, 0, 0}};
    for (int linear = 0; linear < 2; linear++) {
        tr_ctx c;
        if (tr_open(&c, &cu_display_egl, W, H, linear))
            fail_msg("%s", c.err);
        const char *sets[] = {"cloud.density=0", "sky.model=preetham", "sun.elevation=35", "quality.sky_grid=0", NULL};
        if (tr_render(&c, "scenes/cumulus.scene", sets))
            fail_msg("%s", c.err);
        cu_scene *s = scene_with(sets);
        cu_error e;
        cu_sky sky;
        cu_sky_compute(&sky, s);
        double white[3];
        cu_sky_white_balance(s, white);
        float *px = malloc(sizeof(float) * 3 * W * H);
        uint8_t *rgba = malloc(4 * W * H);
        assert_non_null(px);
        assert_non_null(rgba);
        for (size_t v = 0; v < sizeof views / sizeof views[0]; v++) {
            float view[16], proj[16];
            mat4 inv;
            rolled_camera(s, v3(views[v][0], views[v][1], views[v][2]), views[v][3], 70, W, H, view, proj, &inv);
            unsigned fbo;
            int w, h;
            c.be->frame(c.disp, &fbo, &w, &h);
            cu_frame f = {.fbo = fbo, .width = w, .height = h, .linear = linear, .view = view, .projection = proj};
            if (cu_render(c.r, &f, &e))
                fail_msg("%s", e.msg);
            if (linear)
                tr_read_rgbf(&c, px);
            else
                tr_read_rgba8(&c, rgba);
            int above = 0, below = 0, worst8 = 0;
            double worst = 0;
            for (int y = 0; y < H; y++)
                for (int x = 0; x < W; x++) {
                    vec3 d = pixel_dir(inv, W, H, x, y);
                    if (fabs(d.y) < 1e-3 || v3_dot(d, sky.sun_dir) > cos(1.0 * CU_PI / 180.0))
                        continue;
                    double want[3];
                    if (d.y > 0)
                        cu_sky_radiance(&sky, s, d, want);
                    else
                        for (int k = 0; k < 3; k++)
                            want[k] = sky.ground[k];
                    above += d.y > 0;
                    below += d.y < 0;
                    if (linear) {
                        for (int k = 0; k < 3; k++) {
                            float got = px[3 * (y * W + x) + k];
                            assert_false(isnan(got) || isinf(got));
                            double r = fabs(got - want[k]) / want[k];
                            worst = r > worst ? r : worst;
                        }
                    } else {
                        float wf[3] = {(float)want[0], (float)want[1], (float)want[2]};
                        unsigned char w8[3];
                        cu_tonemap_rgb8(wf, s->exposure, white, w8);
                        for (int k = 0; k < 3; k++) {
                            int dd = abs((int)rgba[4 * (y * W + x) + k] - w8[k]);
                            worst8 = dd > worst8 ? dd : worst8;
                        }
                    }
                }
            printf("view %zu (%s): %d pixels of sky, %d of ground: max relative error %.5f, max %d levels\n", v,
                   linear ? "radiance" : "tone-mapped", above, below, worst, worst8);
            assert_true(above + below > W * H / 2);
            /* the sky's own accuracy is the test above's (0.002); the ground is one colour */
            assert_true(worst < 0.002);
            assert_true(worst8 <= 1);
        }
        free(px);
        free(rgba);
        cu_scene_free(s);
        tr_close(&c);
    }
}

#define GW 400
#define GH 300
/* One frame of the sky (cloud.density 0, so the ground has no shadow maps) through a host camera along dir rolled by
 * roll, held still, into rgba (tone-mapped) or rgb (linear), with sets applied. */
static void host_frame(tr_ctx *c, const char *const *sets, vec3 dir, double roll, mat4 *inv, uint8_t *rgba, float *rgb)
{
    if (tr_render(c, "scenes/cumulus.scene", sets))
        fail_msg("%s", c->err);
    cu_scene *s = scene_with(sets);
    float view[16], proj[16];
    rolled_camera(s, dir, roll, 60, GW, GH, view, proj, inv);
    unsigned fbo;
    int w, h;
    c->be->frame(c->disp, &fbo, &w, &h);
    cu_frame f = {.fbo = fbo, .width = w, .height = h, .linear = c->linear, .view = view, .projection = proj};
    cu_error e;
    /* twice: the second frame is what a still view shows (a frame of sky alone takes the curve at the grid's corners
     * where the plan allows only when the view is the frame before's: pass_sky.c plan) */
    if (cu_render(c->r, &f, &e) || cu_render(c->r, &f, &e))
        fail_msg("%s", e.msg);
    if (rgb)
        tr_read_rgbf(c, rgb);
    else
        tr_read_rgba8(c, rgba);
    cu_scene_free(s);
}

/* quality.sky_grid: the sky worked out at the corners of cells and interpolated, against the same frame with the sky
 * at every pixel (sky_grid 0), in display colours and in radiance, on host cameras toward the sun, beside it, rolled,
 * up and down, at a sun on the horizon and a high one, a clear and a hazy sky and a constant one. The frame is 400 x
 * 300 at 60 degrees: a 16-pixel cell spans 3.2 degrees, coarser than 800 x 480 at the same angle. Where the sun's disk
 * is, the pixels must be the exact ones (pass_sky.c draws them a pixel at a time); elsewhere within the bounds below
 * (measured, with little room). */
static void test_sky_grid(void **st)
{
    (void)st;
    static const int grids[] = {8, 16, 32, 64};
    /* measured (llvmpipe): 1, 1, 3, 4 levels and 0.009, 0.033, 0.079, 0.139 relative in radiance (a dim channel) */
    static const int most8[] = {1, 1, 3, 4};
    static const double most_rel[] = {0.013, 0.05, 0.11, 0.17};
    static const char *const skies[][3] = {{"sun.elevation=3", "sun.turbidity=2", "sky.model=preetham"},
                                           {"sun.elevation=30", "sun.turbidity=8", "sky.model=preetham"},
                                           {"sun.elevation=20", "sun.turbidity=2", "sky.model=constant"}};
    uint8_t *ref8 = malloc(4 * GW * GH), *got8 = malloc(4 * GW * GH);
    float *ref = malloc(sizeof(float) * 3 * GW * GH), *got = malloc(sizeof(float) * 3 * GW * GH);
    assert_true(ref8 && got8 && ref && got);
    for (int linear = 0; linear < 2; linear++) {
        tr_ctx c;
        if (tr_open(&c, &cu_display_egl, GW, GH, linear))
            fail_msg("%s", c.err);
        int worst8[4] = {0, 0, 0, 0}, disk = 0;
        double worst[4] = {0, 0, 0, 0};
        for (int k = 0; k < 3; k++) {
            const char *sets[] = {"cloud.density=0", skies[k][0], skies[k][1], skies[k][2], "quality.sky_grid=0",
                                  NULL};
            cu_scene *s = scene_with(sets);
            cu_sky sky;
            cu_sky_compute(&sky, s);
            cu_scene_free(s);
            vec3 sun = sky.sun_dir, level = v3_norm(v3(sun.x, 0, sun.z)), side = v3_cross(level, v3(0, 1, 0));
            /* at the sun, 25 degrees beside it (near the frame's edge), level toward it rolled 90, rolled 30 with
             * the sun high in the frame, straight up, and down and away from it */
            struct { vec3 dir; double roll; } views[] = {
                {sun, 0}, {v3_add(sun, v3_scale(side, tan(25 * CU_PI / 180))), 0}, {level, 90},
                {v3_add(sun, v3(0, -0.3, 0)), 30}, {v3(0, 1, 0), 0}, {v3_add(v3_scale(level, -1), v3(0, -0.6, 0)), 0}};
            for (size_t v = 0; v < sizeof views / sizeof views[0]; v++) {
                mat4 inv;
                sets[4] = "quality.sky_grid=0";
                host_frame(&c, sets, views[v].dir, views[v].roll, &inv, ref8, linear ? ref : NULL);
                for (int g = 0; g < 4; g++) {
                    char grid[40];
                    snprintf(grid, sizeof grid, "quality.sky_grid=%d", grids[g]);
                    sets[4] = grid;
                    host_frame(&c, sets, views[v].dir, views[v].roll, &inv, got8, linear ? got : NULL);
                    for (int y = 0; y < GH; y++)
                        for (int x = 0; x < GW; x++) {
                            int i = y * GW + x;
                            if (v3_dot(pixel_dir(inv, GW, GH, x, y), sun) > cos(0.3 * CU_PI / 180)) {
                                /* the disk (0.2666 degrees) and a little about it: exact */
                                disk++;
                                for (int ch = 0; ch < 3; ch++)
                                    if (linear ? got[3 * i + ch] != ref[3 * i + ch]
                                               : got8[4 * i + ch] != ref8[4 * i + ch])
                                        fail_msg("sky %d view %zu grid %d: pixel (%d, %d) at the sun differs", k, v,
                                                 grids[g], x, y);
                                continue;
                            }
                            for (int ch = 0; ch < 3; ch++) {
                                if (linear) {
                                    assert_false(isnan(got[3 * i + ch]) || isinf(got[3 * i + ch]));
                                    double r = fabs(got[3 * i + ch] - ref[3 * i + ch]) / fmax(ref[3 * i + ch], 1e-6);
                                    worst[g] = fmax(worst[g], r);
                                } else {
                                    int d = abs((int)got8[4 * i + ch] - ref8[4 * i + ch]);
                                    if (d > 1 && getenv("CUMULO_TEST_DEBUG"))
                                        printf("sky %d view %zu grid %d: (%d, %d) %d levels\n", k, v, grids[g], x, y,
                                               d);
                                    worst8[g] = d > worst8[g] ? d : worst8[g];
                                }
                            }
                        }
                }
            }
        }
        for (int g = 0; g < 4; g++) {
            printf("sky_grid %d, %s: largest difference from the sky at every pixel %s %.4f\n", grids[g],
                   linear ? "radiance" : "tone-mapped", linear ? "relative" : "levels",
                   linear ? worst[g] : worst8[g]);
            if (linear)
                assert_true(worst[g] <= most_rel[g]);
            else
                assert_true(worst8[g] <= most8[g]);
        }
        assert_true(disk > 100); /* the sun was in the frames */
        tr_close(&c);
    }
    free(ref8);
    free(got8);
    free(ref);
    free(got);
}

/* The sky pass's plans (pass_sky.c plan): a frame of sky alone takes the curve at the grid's corners in some runs of
 * rows (the plan's toned bands, sky_grid.h) once the view, the sun and the exposure are those the last frame of sky
 * alone had, and none in a frame where one of them changed (the toned plan is not made for a frame that cannot reuse
 * it); a frame drawn the general way (linear output here, as a frame with clouds) takes none. Frames of the two kinds
 * in turn, with the camera and the sun unmoved, make neither plan again (they are kept apart); a moved sun remakes the
 * radiance plan at once and the toned one in the frame after, a changed exposure the toned one in the frame after.
 * Counted by the pass (toned_runs, plans, toned_plans): what the GPU was asked to draw, not what the CPU plan says it
 * could. The level view away from a sun 30 degrees high: test_sky_plan finds its bands toned. */
static void test_sky_plan_kept(void **st)
{
    (void)st;
    tr_ctx c;
    if (tr_open(&c, &cu_display_egl, GW, GH, 0))
        fail_msg("%s", c.err);
    const char *sets[] = {"cloud.density=0", "sun.elevation=30", "sun.azimuth=180", NULL};
    if (tr_render(&c, "scenes/cumulus.scene", sets))
        fail_msg("%s", c.err);
    cu_scene *s = scene_with(sets);
    cu_sky sky;
    cu_sky_compute(&sky, s);
    vec3 away = v3_norm(v3(-sky.sun_dir.x, 0, -sky.sun_dir.z));
    float view[16], proj[16];
    mat4 inv;
    rolled_camera(s, away, 0, 60, GW, GH, view, proj, &inv);
    unsigned fbo;
    int w, h;
    c.be->frame(c.disp, &fbo, &w, &h);
    const cu_pass_sky *p = &c.r->pass_sky;
    /* by frame: linear output; the sun moved (1) or the exposure changed (2) before it; toned runs expected; plans
     * and toned plans made in it */
    static const struct { int linear, change, toned, plans, toned_plans; } frames[] = {
        {0, 0, 0, 1, 0}, /* a new view */
        {1, 0, 0, 0, 0}, {0, 0, 1, 0, 1}, {1, 0, 0, 0, 0}, {0, 0, 1, 0, 0}, {1, 0, 0, 0, 0},
        {0, 1, 0, 1, 0}, /* the sun moved */
        {0, 0, 1, 0, 1},
        {0, 2, 0, 0, 0}, /* the exposure changed (a host's own, every frame: the renderer's scene, as set_scene
                          * would leave it) */
        {0, 0, 1, 0, 1}};
    long plans = p->plans, toned = p->toned_plans;
    cu_error e;
    for (size_t i = 0; i < sizeof frames / sizeof frames[0]; i++) {
        if (frames[i].change == 1 && cu_renderer_set_sun(c.r, 30.5, 180, &e))
            fail_msg("%s", e.msg);
        if (frames[i].change == 2)
            c.r->scene.exposure *= 1.5;
        cu_frame f = {.fbo = fbo, .width = w, .height = h, .linear = frames[i].linear, .view = view,
                      .projection = proj};
        if (cu_render(c.r, &f, &e))
            fail_msg("%s", e.msg);
        printf("frame %zu (%s): toned runs %d, plans %ld, toned plans %ld\n", i,
               frames[i].linear ? "linear" : "sky alone", p->toned_runs, p->plans, p->toned_plans);
        if (frames[i].toned)
            assert_true(p->toned_runs > 0);
        else
            assert_int_equal(p->toned_runs, 0);
        assert_int_equal(p->plans - plans, frames[i].plans);
        assert_int_equal(p->toned_plans - toned, frames[i].toned_plans);
        plans = p->plans;
        toned = p->toned_plans;
    }
    cu_scene_free(s);
    tr_close(&c);
}

/* A constant sky (sky.model constant): one colour from every direction, the ground's place too, drawn flat (pass_sky.c
 * CU_SKY_FLAT, worked out once) with the sun's disk drawn over it a pixel at a time. Every pixel farther than 0.3
 * degrees from the sun holds sky.color exactly (radiance) or one colour (display); every pixel within 0.2 degrees
 * holds the disk (0.2666 degrees: radiance far above the sky's, white on the display). At the sun, beside it, and
 * down and away, with the grid on and off. */
static void test_constant_sky_and_sun(void **st)
{
    (void)st;
    uint8_t *px8 = malloc(4 * GW * GH);
    float *px = malloc(sizeof(float) * 3 * GW * GH);
    assert_true(px8 && px);
    for (int linear = 0; linear < 2; linear++) {
        tr_ctx c;
        if (tr_open(&c, &cu_display_egl, GW, GH, linear))
            fail_msg("%s", c.err);
        const char *sets[] = {"cloud.density=0", "sun.elevation=20", "sky.model=constant", "sky.color=6 7 9",
                              "quality.sky_grid=0", NULL};
        cu_scene *s = scene_with(sets);
        cu_sky sky;
        cu_sky_compute(&sky, s);
        cu_scene_free(s);
        vec3 sun = sky.sun_dir, level = v3_norm(v3(sun.x, 0, sun.z)), side = v3_cross(level, v3(0, 1, 0));
        vec3 views[] = {sun, v3_add(sun, v3_scale(side, tan(10 * CU_PI / 180))),
                        v3_add(v3_scale(level, -1), v3(0, -0.6, 0))};
        int disk = 0, sky_px = 0;
        for (int g = 0; g < 2; g++) {
            sets[4] = g ? "quality.sky_grid=16" : "quality.sky_grid=0";
            for (size_t v = 0; v < sizeof views / sizeof views[0]; v++) {
                mat4 inv;
                host_frame(&c, sets, views[v], 0, &inv, px8, linear ? px : NULL);
                int base = -1; /* the display colour of the sky, from the first pixel away from the sun */
                for (int y = 0; y < GH; y++)
                    for (int x = 0; x < GW; x++) {
                        int i = y * GW + x;
                        double cosang = v3_dot(pixel_dir(inv, GW, GH, x, y), sun);
                        if (cosang > cos(0.2 * CU_PI / 180)) {
                            disk++;
                            for (int ch = 0; ch < 3; ch++)
                                if (linear ? !(px[3 * i + ch] > 1000.0f) : px8[4 * i + ch] != 255)
                                    fail_msg("view %zu grid %d: pixel (%d, %d) in the sun's disk holds no sun", v,
                                             g, x, y);
                        } else if (cosang < cos(0.3 * CU_PI / 180)) {
                            sky_px++;
                            int rgb = px8[4 * i] << 16 | px8[4 * i + 1] << 8 | px8[4 * i + 2];
                            base = base < 0 ? rgb : base;
                            if (linear ? px[3 * i] != 6.0f || px[3 * i + 1] != 7.0f || px[3 * i + 2] != 9.0f
                                       : rgb != base || rgb == 0xffffff)
                                fail_msg("view %zu grid %d: pixel (%d, %d) is not the constant sky", v, g, x, y);
                        }
                    }
            }
        }
        printf("%s: %d pixels of the sun's disk, %d of the constant sky\n", linear ? "radiance" : "display", disk,
               sky_px);
        assert_true(disk >= 8 && sky_px > GW * GH); /* measured 14 and 719980 (of 6 frames) */
        tr_close(&c);
    }
    free(px8);
    free(px);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_sky_is_preetham),
                                       cmocka_unit_test(test_sky_and_ground_in_rows),
                                       cmocka_unit_test(test_sky_grid),
                                       cmocka_unit_test(test_sky_plan_kept),
                                       cmocka_unit_test(test_constant_sky_and_sun)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
