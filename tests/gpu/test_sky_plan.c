/* tests/gpu/test_sky_plan.c: where the sky's grid may use larger cells (cu_sky_grid_plan, sky_grid.c). The plan
 * estimates each band's interpolation error at a few points a cell; this checks its choice against every pixel: the
 * sky of the tables at each pixel's centre against the value sky.vert's two triangles a cell interpolate there, on
 * views level, up, rolled, toward a low sun and away from it, a clear and a hazy sky. No GL. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "scene.h"
#include "sky_grid.h"
#include "tonemap.h"

typedef struct view {
    double elevation, turbidity; /* the sun */
    double yaw, pitch, roll;     /* degrees from the sun's azimuth, above the horizon, about the view direction */
    int w, h;
    double fov;
} view;

typedef struct sky_ctx {
    float tables[2 * 4 * CU_SKY_TABLE];
    vec3 sun;
    float m[16];
    int w, h;
    double display[4];  /* the exposure's scale by channel and the cap, as the renderer gives them (fp16 target) */
    int toned;          /* sky_px gives the display's values (0..1) */
} sky_ctx;

static const int no_sun[4] = {1 << 30, 1 << 30, 0, 0};

static void make(sky_ctx *c, const view *v)
{
    cu_scene *s;
    cu_error e;
    char set[64];
    assert_int_equal(cu_scene_load(&s, "scenes/cumulus.scene", &e), 0);
    snprintf(set, sizeof set, "sun.elevation=%g", v->elevation);
    assert_int_equal(cu_scene_set(s, set, &e), 0);
    snprintf(set, sizeof set, "sun.turbidity=%g", v->turbidity);
    assert_int_equal(cu_scene_set(s, set, &e), 0);
    assert_int_equal(cu_scene_set(s, "sky.model=preetham", &e), 0);
    cu_sky sky;
    cu_sky_compute(&sky, s);
    double white[3];
    cu_sky_white_balance(s, white);
    for (int k = 0; k < 3; k++)
        c->display[k] = (float)(s->exposure / white[k]);
    c->display[3] = 30000.0f;
    c->toned = 0;
    cu_scene_free(s);
    cu_sky_tables(&sky, c->tables, c->tables + 4 * CU_SKY_TABLE);
    c->sun = sky.sun_dir;
    double az = atan2(sky.sun_dir.x, sky.sun_dir.z) + v->yaw * CU_PI / 180, el = v->pitch * CU_PI / 180;
    vec3 dir = v3(sin(az) * cos(el), sin(el), cos(az) * cos(el));
    vec3 side = v3_norm(v3_cross(dir, fabs(dir.y) > 0.99 ? v3(1, 0, 0) : v3(0, 1, 0)));
    vec3 up = v3_cross(side, dir), r = v3_add(v3_scale(up, cos(v->roll * CU_PI / 180)),
                                              v3_scale(side, sin(v->roll * CU_PI / 180)));
    /* as camera.c makes the sky's matrix: the rotation alone, fixed planes 1 and 2 */
    mat4 rot_vp = m4_mul(m4_perspective(v->fov * CU_PI / 180, (double)v->w / v->h, 1.0, 2.0),
                         m4_look_dir(v3(0, 0, 0), dir, r));
    mat4 inv = m4_inverse(rot_vp);
    for (int i = 0; i < 16; i++)
        c->m[i] = (float)inv.m[i];
    c->w = v->w;
    c->h = v->h;
}

static void sky_px(const sky_ctx *c, double x, double y, double out[3])
{
    vec3 d = cu_sky_dir(c->m, 2.0 * x / c->w - 1.0, 2.0 * y / c->h - 1.0);
    cu_sky_from_tables(c->tables, c->tables + 4 * CU_SKY_TABLE, c->sun, d, out);
    if (c->toned)
        for (int k = 0; k < 3; k++)
            out[k] = cu_tonemap_srgb(cu_tonemap_aces(fmax(fmin(out[k] * c->display[k], c->display[3]), 0.0)));
}

/* The largest error of any channel (relative, or with c->toned in the display's levels), over every pixel of the rows
 * of sky alone (kind 0) or near the horizon (kind 1) outside the sun's box, of cells `grid` pixels (the horizon's a
 * quarter as high) times the scale of each band (NULL: scale `all` everywhere; a band's 0: not counted), as sky.vert
 * lays them: corners at multiples of the cell from the viewport's corner, clamped to it; triangles (lower left, upper
 * left, lower right) and (upper left, lower right, upper right). */
static double dense_error(const sky_ctx *c, int grid, unsigned char scale[CU_SKY_BANDS][2], int all, const int sun[4],
                          int *pixels)
{
    double worst = 0;
    for (int y = 0; y < c->h; y++) {
        int part = cu_sky_rows(c->m, -1.0 + 2.0 * y / c->h, -1.0 + 2.0 * (y + 1) / c->h);
        int k = part == CU_SKY_ABOVE ? 0 : part == CU_SKY_LOW ? 1 : -1;
        if (k < 0)
            continue;
        int s = scale ? scale[y / CU_SKY_BAND][k] : all, cw = grid * s, ch = (k && grid > 4 ? grid / 4 : grid) * s;
        for (int x = 0; x < c->w && s > 0; x++) {
            double px = x + 0.5, py = y + 0.5;
            if (px >= sun[0] && px < sun[2] && py >= sun[1] && py < sun[3])
                continue;
            double x0 = x / cw * cw, ya = y / ch * ch;
            double x1 = fmin(x0 + cw, c->w), yb = fmin(ya + ch, c->h);
            double a[3], b[3], cc[3], d[3], exact[3];
            sky_px(c, x0, ya, a);
            sky_px(c, x1, ya, b);
            sky_px(c, x0, yb, cc);
            sky_px(c, x1, yb, d);
            sky_px(c, px, py, exact);
            double u = (px - x0) / (x1 - x0), v = (py - ya) / (yb - ya);
            for (int ch3 = 0; ch3 < 3; ch3++) {
                double got = u + v <= 1 ? a[ch3] + u * (b[ch3] - a[ch3]) + v * (cc[ch3] - a[ch3])
                                        : d[ch3] + (1 - u) * (cc[ch3] - d[ch3]) + (1 - v) * (b[ch3] - d[ch3]);
                worst = fmax(worst, c->toned ? 255.0 * fabs(got - exact[ch3])
                                             : fabs(got - exact[ch3]) / fmax(exact[ch3], 1e-9));
            }
            ++*pixels;
        }
    }
    return worst;
}

static const view views[] = {
    {30, 2.5, 180, 5, 0, 800, 480, 50},  /* level, away from the sun: the default scene's empty view */
    {30, 2.5, 0, 5, 0, 800, 480, 50},    /* level, toward it */
    {30, 2.5, 90, 60, 0, 800, 480, 50},  /* up, beside it */
    {30, 8, 120, 20, 35, 400, 300, 60},  /* hazy, rolled */
    {3, 2, 40, 2, 0, 400, 300, 60},      /* a low sun, beside it, at the horizon */
    {3, 2, 180, 10, -20, 800, 480, 50},  /* a low sun behind, rolled */
    {30, 2.5, 180, -3, 0, 96, 72, 50},   /* small, the horizon inside the first band: its cells reach below it */
    {30, 2.5, 150, 2, 0, 192, 72, 50},   /* the same twice as wide (test_embed's two channels) */
};

/* Where the plan grows the cells, every pixel is within its bound of the sky (with room for what a few points a cell
 * cannot see: measured 0.0095 at most, against the bound's 0.01), or no worse than the 16-pixel cells' own error; and
 * it grows them on the views where the sky is smooth. */
static void test_plan_keeps_its_bound(void **st)
{
    (void)st;
    static unsigned char scale[CU_SKY_BANDS][2];
    int grew_level = 0;
    for (size_t i = 0; i < sizeof views / sizeof views[0]; i++) {
        sky_ctx c;
        make(&c, &views[i]);
        int cells = cu_sky_grid_plan(c.tables, c.sun, c.m, c.w, c.h, 16, no_sun, scale);
        int n = 0, grown = 0;
        for (int b = 0; b * CU_SKY_BAND < c.h; b++)
            grown += (scale[b][0] > 1) + (scale[b][1] > 1);
        double planned = dense_error(&c, 16, scale, 1, no_sun, &n), base = dense_error(&c, 16, NULL, 1, no_sun, &n);
        printf("view %zu: %d bands grown, %d cells; every pixel within %.4f of the sky (16-pixel cells: %.4f)\n", i,
               grown, cells, planned, base);
        /* the grown cells' error stays within 1.5 times the estimate's bound, or the base grid's own error */
        assert_true(planned <= fmax(1.5 * CU_SKY_GRID_REL, base * 1.0001));
        if (i == 0)
            grew_level = grown;
    }
    assert_true(grew_level >= 3); /* the empty view's sky grows (measured: 5 bands) */
}

/* The bound can fail: toward a low sun, cells four times as large everywhere are off by more than it, and the plan
 * does not take them there. */
static void test_plan_keeps_small_cells_where_the_sky_bends(void **st)
{
    (void)st;
    static unsigned char scale[CU_SKY_BANDS][2];
    sky_ctx c;
    make(&c, &views[4]);
    int n = 0;
    double coarse = dense_error(&c, 16, NULL, 4, no_sun, &n);
    cu_sky_grid_plan(c.tables, c.sun, c.m, c.w, c.h, 16, no_sun, scale);
    int all4 = 1;
    for (int b = 0; b * CU_SKY_BAND < c.h; b++)
        all4 = all4 && scale[b][0] == 4 && scale[b][1] == 4;
    printf("low sun: 64-pixel cells everywhere %.4f off\n", coarse);
    assert_true(coarse > 2 * CU_SKY_GRID_REL);
    assert_false(all4);
}

/* A frame of sky alone takes the display's values at the corners where the plan allows (cu_sky_grid_toned): there
 * every pixel's interpolated display value is within 1.5 times the bound of the curve of its sky (measured 0.29
 * levels at most, against the bound's 0.3); and it does so somewhere on the views where the sky is smooth. Cells
 * four times as large everywhere toward the low sun are off by more: the bound can fail. */
static void test_toned_plan(void **st)
{
    (void)st;
    static unsigned char scale[CU_SKY_BANDS][2], toned[CU_SKY_BANDS][2];
    int toned_level = 0;
    for (size_t i = 0; i < sizeof views / sizeof views[0]; i++) {
        sky_ctx c;
        make(&c, &views[i]);
        cu_sky_grid_plan(c.tables, c.sun, c.m, c.w, c.h, 16, no_sun, scale);
        int cells = cu_sky_grid_toned(c.tables, c.sun, c.m, c.w, c.h, 16, no_sun, c.display, toned);
        int bands = 0, n = 0;
        for (int b = 0; b < CU_SKY_BANDS; b++)
            for (int k = 0; k < 2; k++) {
                assert_true(toned[b][k] <= 4);
                bands += toned[b][k] > 0;
            }
        c.toned = 1;
        double levels = dense_error(&c, 16, toned, 1, no_sun, &n);
        printf("view %zu: %d bands with the curve at the corners, %d cells, %d pixels: within %.3f levels\n", i, bands,
               cells, n, levels);
        assert_true(levels <= 1.5 * CU_SKY_GRID_LEVELS);
        if (i == 0)
            toned_level = bands;
    }
    assert_true(toned_level >= 3);
    sky_ctx c;
    make(&c, &views[4]);
    c.toned = 1;
    int n = 0;
    double coarse = dense_error(&c, 16, NULL, 4, no_sun, &n);
    printf("low sun: the curve at the corners of 64-pixel cells everywhere: %.2f levels off\n", coarse);
    assert_true(coarse > 2 * CU_SKY_GRID_LEVELS);
}

/* Grids that cannot grow (64 pixels: the largest cell already; 0: no grid; 33: twice is past 64; 4: too fine to be
 * worth the plan's cost), a one-pixel viewport, and a degenerate camera (NaN directions) keep every band at 1; bands
 * past the viewport are 1. */
static void test_plan_degenerate(void **st)
{
    (void)st;
    static unsigned char scale[CU_SKY_BANDS][2];
    sky_ctx c;
    make(&c, &views[0]);
    const int grids[] = {64, 0, 33, 4}; /* 4: finer than CU_SKY_PLAN_LEAST */
    for (int g = 0; g < 4; g++) {
        cu_sky_grid_plan(c.tables, c.sun, c.m, c.w, c.h, grids[g], no_sun, scale);
        for (int b = 0; b < CU_SKY_BANDS; b++)
            for (int k = 0; k < 2; k++)
                assert_int_equal(scale[b][k], 1);
    }
    cu_sky_grid_plan(c.tables, c.sun, c.m, 1, 1, 16, no_sun, scale);
    for (int b = 0; b < CU_SKY_BANDS; b++)
        assert_true(scale[b][0] >= 1 && scale[b][0] <= 4 && (b == 0 || scale[b][0] == 1));
    float nan_m[16];
    for (int i = 0; i < 16; i++)
        nan_m[i] = NAN;
    static unsigned char toned[CU_SKY_BANDS][2];
    cu_sky_grid_plan(c.tables, c.sun, nan_m, c.w, c.h, 16, no_sun, scale);
    cu_sky_grid_toned(c.tables, c.sun, nan_m, c.w, c.h, 16, no_sun, c.display, toned);
    for (int b = 0; b < CU_SKY_BANDS; b++)
        for (int k = 0; k < 2; k++) {
            assert_int_equal(scale[b][k], 1);
            assert_int_equal(toned[b][k], 0); /* a NaN sky: the curve at every pixel (it makes the NaN black) */
        }
    cu_sky_grid_plan(c.tables, c.sun, c.m, c.w, c.h, 0, no_sun, scale);
    cu_sky_grid_toned(c.tables, c.sun, c.m, c.w, c.h, 0, no_sun, c.display, toned);
    for (int b = 0; b < CU_SKY_BANDS; b++)
        assert_true(toned[b][0] == 0 && toned[b][1] == 0);
    cu_sky_grid_plan(c.tables, c.sun, c.m, c.w, c.h, 16, no_sun, scale);
    for (int b = (c.h + CU_SKY_BAND - 1) / CU_SKY_BAND; b < CU_SKY_BANDS; b++)
        assert_true(scale[b][0] == 1 && scale[b][1] == 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_plan_keeps_its_bound),
                                       cmocka_unit_test(test_plan_keeps_small_cells_where_the_sky_bends),
                                       cmocka_unit_test(test_toned_plan),
                                       cmocka_unit_test(test_plan_degenerate)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
