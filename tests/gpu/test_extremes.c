/* tests/gpu/test_extremes.c: numerical stability at the extremes (issue 7's matrix): sun below, at and above the
 * horizon and at the zenith, sun exactly in front of and behind the camera, camera inside / on / at the centre of an
 * ellipsoid, tangent rays, clouds 10 m and 100 km away, radii from 1 m to 50 km, density from 0 to 1e6 cm^-3, h = 0
 * and h larger than the radii, 64 ellipsoids through one point. Every render: finite, non-negative, bounded; and
 * small steps of an input give small changes of the image; and over the matrix, four moving frames with the temporal
 * grid, half resolution and impostors leave every history and impostor image finite. CUMULO_STRESS=1 (make stress)
 * renders larger images and takes finer, longer sweeps. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <GLES3/gl3.h>
#include "scene.h"
#include "render_util.h"
#include "renderer.h"

static int W = 64, H = 48;
static tr_ctx ctx;

#define BASE                                                                                                    \
    "[camera]\nposition = 0 250 -900\nlook_at = 0 250 0\nfov = 50\n[sun]\nelevation = 30\nazimuth = 135\n"   \
    "[cloud]\n[ellipsoid]\ncenter = 0 250 0\nradii = 200 120 160\n[ellipsoid]\ncenter = 150 230 40\n"         \
    "radii = 140 100 120\n"

/* Radiance bound: nothing in a frame can exceed the sun disk's radiance (irradiance / 6.8e-5 sr, 128 klx at most)
 * — a NaN, an Inf or an exploding exponential would. */
#define MAX_RADIANCE (128.0 / 6.8e-5 * 1.01)

static int setup(void **st)
{
    (void)st;
    if (getenv("CUMULO_STRESS")) {
        W = 320;
        H = 240;
    }
    if (tr_open(&ctx, &cu_display_egl, W, H, 1)) {
        fprintf(stderr, "%s\n", ctx.err);
        return 1;
    }
    return 0;
}

static int teardown(void **st)
{
    (void)st;
    tr_close(&ctx);
    return 0;
}

/* Renders BASE (or `scene`) with the overrides; checks every value; returns a malloc'd float image. */
static float *render_checked(const char *scene, const char *const *sets, const char *label)
{
    if (tr_render(&ctx, scene ? scene : BASE, sets))
        fail_msg("%s: %s", label, ctx.err);
    float *px = malloc(sizeof(float) * 3 * (size_t)W * H);
    tr_read_rgbf(&ctx, px);
    for (long i = 0; i < (long)W * H * 3; i++)
        if (!isfinite(px[i]) || px[i] < 0.0f || px[i] > MAX_RADIANCE)
            fail_msg("%s: pixel %ld channel %ld = %g", label, i / 3, i % 3, px[i]);
    return px;
}

typedef struct ecase {
    const char *label;
    const char *sets[8];
} ecase;

static const ecase cases[] = {
    {"sun -5 deg", {"sun.elevation=-5"}},
    {"sun 0 deg", {"sun.elevation=0"}},
    {"sun 0.01 deg", {"sun.elevation=0.01"}},
    {"sun 45 deg", {"sun.elevation=45"}},
    {"sun 89.99 deg", {"sun.elevation=89.99"}},
    {"sun 90 deg", {"sun.elevation=90"}},
    {"sun -90 deg", {"sun.elevation=-90"}},
    {"sun in front (Theta = 0)", {"sun.elevation=0", "sun.azimuth=180"}},
    {"sun behind (Theta = 180)", {"sun.elevation=0", "sun.azimuth=0"}},
    {"camera at an ellipsoid centre", {"camera.look_at=0 250 100", "camera.position=0 250 0"}},
    {"camera on the surface", {"camera.position=0 250 -160", "camera.look_at=0 250 0"}},
    {"camera on the surface looking out", {"camera.position=0 250 -160", "camera.look_at=0 250 -1000"}},
    {"camera inside, looking up", {"camera.look_at=0 1000 0", "camera.position=0 250 0"}},
    {"camera looking straight down", {"camera.position=0 2000 0", "camera.look_at=0 0 0"}},
    {"tangent rays over the top", {"camera.position=0 370 -900", "camera.look_at=0 370 0"}},
    {"cloud 10 m away, 1 m radii",
     {"camera.position=0 0 -10", "camera.look_at=0 0 0", "ellipsoid.1.center=0 0 0", "ellipsoid.1.radii=1 1 1",
      "ellipsoid.2.center=0.5 0 0", "ellipsoid.2.radii=1 0.5 1", "cloud.boundary=0.3"}},
    {"cloud 100 km away",
     {"camera.position=0 10 0", "camera.look_at=0 1000 100000", "ellipsoid.1.center=0 1000 100000",
      "ellipsoid.1.radii=2000 800 1500", "ellipsoid.2.center=800 1000 100500", "ellipsoid.2.radii=1000 600 900",
      "camera.fov=5"}},
    {"radii 50 km, camera outside",
     {"camera.position=0 2000 -120000", "camera.look_at=0 2000 0", "ellipsoid.1.radii=50000 1000 50000",
      "ellipsoid.2.radii=40000 1500 30000"}},
    {"radii 50 km, camera inside",
     {"camera.position=0 250 -100", "camera.look_at=1000 300 0", "ellipsoid.1.radii=50000 1000 50000"}},
    {"radii 1 m", {"ellipsoid.1.radii=1 1 1", "ellipsoid.2.radii=1 1 1", "cloud.boundary=0.5"}},
    {"density 0", {"cloud.density=0"}},
    {"density 1e-3", {"cloud.density=1e-3"}},
    {"density 1e6", {"cloud.density=1e6"}},
    {"density 1e6, camera inside", {"cloud.density=1e6", "camera.look_at=0 250 100", "camera.position=0 250 0"}},
    {"boundary 0", {"cloud.boundary=0"}},
    {"boundary larger than the radii", {"cloud.boundary=100000"}},
    {"boundary larger than the radii, kol profile", {"cloud.boundary=100000", "cloud.profile=kol"}},
    {"hg g = 0.99 looking at the sun", {"cloud.phase=hg", "cloud.g=0.99", "sun.elevation=0", "sun.azimuth=180"}},
    {"one segment, 64 intervals off", {"quality.segments=1", "quality.max_intervals=1"}},
    {"64 segments, steep ratio", {"quality.segments=64", "quality.segment_ratio=10"}},
    {"octaves", {"ms.mode=octaves", "ms.octaves=8"}},
    {"no multiple scattering", {"ms.mode=none"}},
    {"collector search, sun at the zenith", {"ms.mode=collector", "sun.elevation=90"}},
    {"collector search, density 1e6, radii 50 km",
     {"ms.mode=collector", "cloud.density=1e6", "ellipsoid.1.radii=50000 1000 50000"}},
    {"slab model, blur 1 m", {"ms.blur=1"}},
    {"slab model, blur 1e6 m", {"ms.blur=1000000"}},
    {"opacity shadow maps, 4 slices", {"light.shadow=osm", "light.osm_slices=4"}},
    {"Fourier opacity maps, 1 coefficient, density 1e6", {"light.shadow=fom", "light.fom_coefficients=1", "cloud.density=1e6"}},
    {"constant sky, no sun", {"sky.model=constant", "sky.color=1 1 1", "sun.irradiance=0 0 0"}},
    {"tiny sun map", {"quality.sun_map_size=16"}},
    {"turbid atmosphere, low sun", {"sun.turbidity=10", "sun.elevation=1"}},
};

static void test_matrix(void **st)
{
    (void)st;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const char *sets[9] = {0};
        for (int k = 0; k < 8 && cases[i].sets[k]; k++)
            sets[k] = cases[i].sets[k];
        free(render_checked(NULL, sets, cases[i].label));
    }
}

/* A float target's colour attachment `a` (w x h RGBA), read back and checked finite (colour: non-negative). */
static void check_target(GLuint fbo, int a, int w, int h, const char *what, const char *label)
{
    float *px = malloc(sizeof(float) * 4 * (size_t)w * h);
    assert_non_null(px);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0 + (GLenum)a);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, px);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    assert_int_equal(glGetError(), GL_NO_ERROR);
    for (long i = 0; i < 4L * w * h; i++)
        if (!isfinite(px[i]) || (a == 0 && px[i] < 0.0f))
            fail_msg("%s: %s, texel %ld channel %ld = %g", label, what, i / 4, i % 4, px[i]);
    free(px);
}

/* Issue 17: no NaN in any history buffer over the matrix. Every case again with the temporal grid (2 x 2), the clouds
 * at half resolution and every cloud that may be drawn from an impostor drawn from one, over four frames of a camera
 * turning a degree and moving 20 m a frame (the frames after the first reproject history): the output as above, and
 * both temporal history images (colour; distance and motion) and every impostor image read back finite. */
static void test_matrix_history(void **st)
{
    (void)st;
    long histories = 0, images = 0;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        cu_scene *s;
        cu_error e;
        if (cu_scene_parse(&s, "extremes", BASE, strlen(BASE), &e))
            fail_msg("%s", e.msg);
        const char *extra[] = {"quality.temporal_grid=2", "quality.cloud_downsample=2", "quality.impostor_pixels=4096"};
        for (int k = 0; k < 3; k++)
            if (cu_scene_set(s, extra[k], &e))
                fail_msg("%s", e.msg);
        for (int k = 0; k < 8 && cases[i].sets[k]; k++)
            if (cu_scene_set(s, cases[i].sets[k], &e))
                fail_msg("%s: %s", cases[i].label, e.msg);
        if (cu_renderer_set_scene(ctx.r, s, &e))
            fail_msg("%s: %s", cases[i].label, e.msg);
        for (int f = 0; f < 4; f++) {
            cu_scene *m;
            if (cu_scene_parse(&m, "extremes", BASE, strlen(BASE), &e))
                fail_msg("%s", e.msg);
            memcpy(m->cam_pos, s->cam_pos, sizeof m->cam_pos);
            memcpy(m->cam_look, s->cam_look, sizeof m->cam_look);
            m->cam_fov = s->cam_fov;
            double a = f * CU_PI / 180.0, dx = m->cam_look[0] - m->cam_pos[0], dz = m->cam_look[2] - m->cam_pos[2];
            m->cam_look[0] = m->cam_pos[0] + dx * cos(a) - dz * sin(a) + 20.0 * f;
            m->cam_look[2] = m->cam_pos[2] + dx * sin(a) + dz * cos(a);
            m->cam_pos[0] += 20.0 * f;
            float view[16], proj[16];
            if (cu_scene_camera_matrices(m, (double)W / H, 1.0, 1.0e5, view, proj, &e))
                fail_msg("%s: %s", cases[i].label, e.msg);
            unsigned fbo;
            int w, h;
            ctx.be->frame(ctx.disp, &fbo, &w, &h);
            cu_frame fr = {.fbo = fbo, .width = w, .height = h, .linear = 1, .view = view, .projection = proj};
            if (cu_render(ctx.r, &fr, &e))
                fail_msg("%s, frame %d: %s", cases[i].label, f, e.msg);
            float *px = malloc(sizeof(float) * 3 * (size_t)W * H);
            tr_read_rgbf(&ctx, px);
            for (long q = 0; q < (long)W * H * 3; q++)
                if (!isfinite(px[q]) || px[q] < 0.0f || px[q] > MAX_RADIANCE)
                    fail_msg("%s, frame %d: pixel %ld channel %ld = %g", cases[i].label, f, q / 3, q % 3, px[q]);
            free(px);
            cu_scene_free(m);
        }
        const cu_pass_temporal *t = &ctx.r->pass_temporal;
        for (int k = 0; k < 2; k++)
            if (t->hist[k].fbo) {
                check_target(t->hist[k].fbo, 0, t->hist[k].width, t->hist[k].height, "history colour", cases[i].label);
                check_target(t->hist[k].fbo, 1, t->hist[k].width, t->hist[k].height, "history distance and motion",
                             cases[i].label);
                histories++;
            }
        for (int c = 0; c < ctx.r->clouds.n; c++) {
            const cu_impostor *im = &ctx.r->clouds.slot[c].imp;
            if (im->valid) {
                check_target(im->image.fbo, 0, im->size, im->size, "impostor image", cases[i].label);
                images++;
            }
        }
        cu_scene_free(s);
    }
    printf("%ld history images and %ld impostor images over %zu cases: finite\n", histories, images,
           sizeof cases / sizeof cases[0]);
    assert_true(histories >= 2 * (long)(sizeof cases / sizeof cases[0]) - 8); /* density 0 and the like draw none */
    assert_true(images > 0);
}

static void test_64_ellipsoids_through_one_point(void **st)
{
    (void)st;
    char *text = malloc(64 * 128 + 512);
    int n = sprintf(text, "[camera]\nposition = 0 250 -900\nlook_at = 0 250 0\n[sun]\nelevation = 20\n[cloud]\n");
    for (int i = 0; i < 64; i++) {
        double a = i * 2.399963; /* golden angle: spread the ellipsoids around the common point */
        n += sprintf(text + n, "[ellipsoid]\ncenter = %.3f %.3f %.3f\nradii = %.1f %.1f %.1f\n", 60 * cos(a),
                     250 + 30 * sin(1.7 * a), 60 * sin(a), 80 + (i % 5) * 10.0, 60 + (i % 3) * 15.0, 90.0);
    }
    free(render_checked(text, NULL, "64 ellipsoids through one point"));
    static const char *const inside[] = {"camera.look_at=0 250 100", "camera.position=0 250 0", NULL};
    free(render_checked(text, inside, "64 ellipsoids, camera at the common point"));
    free(text);
}

static double mean_abs(const float *a, const float *b)
{
    double s = 0;
    for (long i = 0; i < (long)W * H * 3; i++)
        s += fabs((double)a[i] - b[i]);
    return s / ((double)W * H * 3);
}

/* Sweeps one input in small steps; no step may change the image by more than `factor` times the median step (plus
 * a floor for sweeps where most steps change nothing). */
static void sweep(const char *label, const char *fmt, double from, double to, int steps, double factor)
{
    float *prev = NULL;
    double *d = malloc(sizeof(double) * (size_t)steps);
    int nd = 0;
    for (int k = 0; k <= steps; k++) {
        char set[128];
        snprintf(set, sizeof set, fmt, from + (to - from) * k / steps);
        const char *sets[] = {set, NULL};
        float *cur = render_checked(NULL, sets, set);
        if (prev)
            d[nd++] = mean_abs(prev, cur);
        free(prev);
        prev = cur;
    }
    free(prev);
    double *s = malloc(sizeof(double) * (size_t)nd);
    memcpy(s, d, sizeof(double) * (size_t)nd);
    for (int i = 1; i < nd; i++)
        for (int j = i; j > 0 && s[j - 1] > s[j]; j--) {
            double t = s[j]; s[j] = s[j - 1]; s[j - 1] = t;
        }
    double med = s[nd / 2], worst = s[nd - 1];
    printf("%-40s median step %.5f, largest %.5f\n", label, med, worst);
    if (worst > factor * med + 1e-4)
        fail_msg("%s: a step changes the image by %.5f, %.1fx the median %.5f", label, worst, worst / med, med);
    free(s);
    free(d);
}

static void test_continuity(void **st)
{
    (void)st;
    int stress = getenv("CUMULO_STRESS") != NULL;
    int n = stress ? 80 : 16;
    sweep("sun elevation across the horizon", "sun.elevation=%.4f", -2.0, 2.0, n, 5.0);
    sweep("sun elevation to the zenith", "sun.elevation=%.4f", 88.0, 90.0, n, 5.0);
    sweep("sun azimuth through the view axis", "sun.azimuth=%.4f", 175.0, 185.0, n, 5.0);
    sweep("camera through the surface", "camera.position=0 250 %.4f", -175.0, -145.0, n, 5.0);
    /* Down to 0.5 m, not 0: below ~0.25 m the boundary is thinner than the 5 cm offset of the interval's end samples
     * (cloud.frag) and the end trapezoids switch from seeing the ramp to seeing the core within a few centimetres of
     * h: continuous, but steep (a 0.25 m step then changes the image 25x more than the median step). h = 0 itself is
     * exact (Beer-Lambert test) and in the matrix above. Known limitation, in the issue notes. */
    sweep("boundary thickness toward 0.5 m", "cloud.boundary=%.4f", 4.0, 0.5, n, 5.0);
    sweep("density toward 0", "cloud.density=%.6f", 2.0, 0.0, n, 5.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_matrix),
        cmocka_unit_test(test_64_ellipsoids_through_one_point),
        cmocka_unit_test(test_continuity),
        cmocka_unit_test(test_matrix_history),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
