/* tests/gpu/test_embed.c: cumulo inside a host's renderer (tests/gpu/host_util.h is the host): the host's view and
 * projection against the scene's [camera] and against asymmetric frusta, clouds composited over the host's colour,
 * and the host's depth cutting the march, checked against the CPU twin of the density. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "density.h"
#include "host_util.h"
#include "scene_camera.h"

/* The host_scene's [camera] and the same view as matrices give the same image, bit for bit; a view turned by 2 degrees
 * does not (the matrices are used), and matrices built here, independently, agree to rounding. */
static void test_matrices_equal_scene_camera(void **st)
{
    (void)st;
    static float a[N * 4], b[N * 4];
    float view[16], proj[16];
    host_matrices(view, proj, 0.5, 5000.0);
    host_render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1});
    host_read(fbo32, 1, a);
    host_render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1, .view = view, .projection = proj});
    host_read(fbo32, 1, b);
    assert_memory_equal(a, b, sizeof a);

    /* The same look from a lookAt and a frustum written out here in float. */
    float v2[16] = {0}, p2[16] = {0};
    float t = 1.0f / tanf(25.0f * 3.14159265f / 180.0f);
    p2[0] = t / ((float)W / H);
    p2[5] = t;
    p2[10] = -(5000.0f + 0.5f) / (5000.0f - 0.5f);
    p2[11] = -1.0f;
    p2[14] = -2.0f * 5000.0f * 0.5f / (5000.0f - 0.5f);
    /* looking along +z from (0, 250, -900): right = -x, up = +y, back = -z */
    v2[0] = -1; v2[5] = 1; v2[10] = -1; v2[15] = 1;
    v2[13] = -250; v2[14] = -900;
    host_render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1, .view = v2, .projection = p2});
    host_read(fbo32, 1, b);
    double worst = 0;
    for (int i = 0; i < N * 4; i++)
        worst = fmax(worst, fabs(a[i] - b[i]) / fmax(fabs(a[i]), 1e-3));
    printf("independent matrices: largest relative difference %.3g\n", worst);
    assert_true(worst < 1e-3);

    /* Turned 2 degrees about y (forward (sin a, 0, cos a), right (-cos a, 0, sin a)): the picture moves. */
    double ca = cos(2.0 * CU_PI / 180), sa = sin(2.0 * CU_PI / 180);
    float v3m[16];
    memcpy(v3m, v2, sizeof v3m);
    v3m[0] = (float)-ca; v3m[8] = (float)sa; v3m[2] = (float)-sa; v3m[10] = (float)-ca;
    v3m[12] = (float)(900.0 * sa);
    v3m[14] = (float)(-900.0 * ca);
    host_render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1, .view = v3m, .projection = p2});
    host_read(fbo32, 1, b);
    int moved = 0;
    for (int i = 0; i < N; i++)
        moved += fabs(a[i * 4 + 1] - b[i * 4 + 1]) > 0.05 * fabs(a[i * 4 + 1]) + 1e-3;
    printf("turned 2 degrees: %d of %d pixels changed\n", moved, N);
    assert_true(moved > N / 50);
}

/* A glFrustum-style matrix: l, r, b, t at the near plane n, far f. */
static void frustum(float m[16], double l, double r, double b, double t, double n, double f)
{
    memset(m, 0, sizeof(float) * 16);
    m[0] = (float)(2 * n / (r - l));
    m[5] = (float)(2 * n / (t - b));
    m[8] = (float)((r + l) / (r - l));
    m[9] = (float)((t + b) / (t - b));
    m[10] = (float)(-(f + n) / (f - n));
    m[11] = -1.0f;
    m[14] = (float)(-2 * f * n / (f - n));
}

/* Two channels of a multi-channel display: the left and right halves of one wide view, each an asymmetric frustum,
 * are the halves of the wide symmetric view's image. */
static void test_asymmetric_frusta(void **st)
{
    (void)st;
    static float wide[2 * N * 4], half[N * 4];
    float view[16], proj[16];
    host_matrices(view, proj, 0.5, 5000.0);
    GLuint fw, cw;
    glGenFramebuffers(1, &fw);
    glBindFramebuffer(GL_FRAMEBUFFER, fw);
    glGenRenderbuffers(1, &cw);
    glBindRenderbuffer(GL_RENDERBUFFER, cw);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA32F, 2 * W, H);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, cw);
    assert_int_equal(glCheckFramebufferStatus(GL_FRAMEBUFFER), GL_FRAMEBUFFER_COMPLETE);
    double n = 0.5, t = n * tan(25.0 * CU_PI / 180), r = t * 2.0 * W / H;
    frustum(proj, -r, r, -t, t, n, 5000);
    host_render((cu_frame){.fbo = fw, .width = 2 * W, .height = H, .linear = 1, .view = view, .projection = proj});
    glBindFramebuffer(GL_FRAMEBUFFER, fw);
    glReadPixels(0, 0, 2 * W, H, GL_RGBA, GL_FLOAT, wide);
    int cloudy = 0;
    double worst = 0;
    for (int side = 0; side < 2; side++) {
        frustum(proj, side ? 0 : -r, side ? r : 0, -t, t, n, 5000);
        host_render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1, .view = view, .projection = proj});
        host_read(fbo32, 1, half);
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++)
                for (int c = 0; c < 3; c++) {
                    float a = half[(y * W + x) * 4 + c], b = wide[(y * 2 * W + side * W + x) * 4 + c];
                    worst = fmax(worst, fabs(a - b) / fmax(fabs(b), 1.0));
                    cloudy += c == 0 && fabs(b - wide[(y * 2 * W) * 4]) > 0.05 * fabs(b);
                }
    }
    printf("asymmetric frusta: largest difference from the wide view %.3g (relative, floor 1), %d pixels differ "
           "from the corner\n", worst, cloudy);
    assert_true(cloudy > N / 20);
    assert_true(worst < 1e-3);
    glDeleteFramebuffers(1, &fw);
    glDeleteRenderbuffers(1, &cw);
}

/* Clouds only: wherever no cloud is, the host's colour stays bit for bit; where one is, it changes. */
static void test_clouds_only_keeps_host_pixels(void **st)
{
    (void)st;
    static float alpha[N], px[N * 4];
    float view[16], proj[16];
    host_matrices(view, proj, 0.5, 5000.0);
    host_coverage(alpha, 0, view, proj);
    const float bg[4] = {0.8f, 0.1f, 0.3f, 1.0f};
    float want[4];
    host_draw(fbo8, bg, bg, 0, proj);
    host_read(fbo8, 0, px);
    memcpy(want, px, sizeof want); /* the host's colour as its framebuffer holds it */
    host_render((cu_frame){.fbo = fbo8, .width = W, .height = H, .clouds_only = 1, .view = view, .projection = proj});
    host_read(fbo8, 0, px);
    int clear = 0, cloudy = 0, kept = 0, changed = 0;
    for (int i = 0; i < N; i++) {
        int same = 1;
        for (int c = 0; c < 4; c++)
            same &= px[i * 4 + c] == want[c];
        if (alpha[i] == 0) {
            clear++;
            kept += same;
        } else if (alpha[i] > 0.05) {
            cloudy++;
            changed += !same;
        }
    }
    printf("clouds only: %d clear pixels (%d kept), %d cloudy (%d changed)\n", clear, kept, cloudy, changed);
    assert_true(clear > N / 2 && cloudy > N / 20);
    assert_int_equal(kept, clear);
    assert_int_equal(changed, cloudy);

    /* With the sky (clouds_only = 0) the host's colour is gone everywhere. */
    host_render((cu_frame){.fbo = fbo8, .width = W, .height = H, .view = view, .projection = proj});
    host_read(fbo8, 0, px);
    int red = 0;
    for (int i = 0; i < N; i++)
        red += px[i * 4] == want[0] && px[i * 4 + 1] == want[1] && px[i * 4 + 2] == want[2];
    assert_true(red < N / 100);
}

/* Optical depth along the pixel's ray from the eye to eye distance `dist` (the quad's plane), from the CPU twin. */
static double cpu_tau(const cu_cloud *cl, int px, int py, double dist)
{
    double t = tan(25.0 * CU_PI / 180.0), aspect = (double)W / H;
    double x = ((px + 0.5) / W * 2 - 1) * t * aspect, y = ((py + 0.5) / H * 2 - 1) * t;
    /* eye frame: right = -x world, up = +y, forward = +z */
    vec3 dir = v3_norm(v3(-x, y, 1.0));
    double len = dist / dir.z; /* the plane z_eye = -dist */
    vec3 eye = v3_sub(v3(0, 250, -900), cl->origin);
    int steps = 4000;
    double tau = 0, dt = len / steps;
    for (int i = 0; i < steps; i++)
        tau += dt * cu_cloud_extinction(cl, v3_add(eye, v3_scale(dir, (i + 0.5) * dt)));
    return tau;
}

/* The host's depth: a quad in front of the cloud keeps its colour exactly; a quad inside it is veiled by the part in
 * front of it only (1 - e^-tau up to the quad, from the CPU density); a quad behind it gets the whole cloud over it. */
static void test_host_depth(void **st)
{
    (void)st;
    static float full[N], cut[N], px[N * 4], ref[N * 4];
    float view[16], proj[16];
    host_matrices(view, proj, 0.5, 5000.0);
    host_coverage(full, 0, view, proj);

    /* In front: 300 m from the eye, the cloud begins near 700 m. */
    const float bg[4] = {0.2f, 0.4f, 0.9f, 1.0f}, fg[4] = {0.1f, 0.7f, 0.2f, 1.0f};
    float fg8[4];
    host_draw(fbo8, bg, fg, 300.0, proj);
    host_read(fbo8, 0, px);
    memcpy(fg8, px, sizeof fg8); /* pixel (0, 0) lies under the quad */
    host_render((cu_frame){.fbo = fbo8, .width = W, .height = H, .clouds_only = 1, .view = view, .projection = proj,
                      .depth_texture = depth_tex});
    host_read(fbo8, 0, px);
    int covered = 0, exact = 0;
    for (int i = 0; i < N; i++)
        if (i % W < W / 2 && full[i] > 0.05) {
            covered++;
            exact += px[i * 4] == fg8[0] && px[i * 4 + 1] == fg8[1] && px[i * 4 + 2] == fg8[2];
        }
    printf("quad in front: %d cloud pixels behind it, %d exact\n", covered, exact);
    assert_true(covered > N / 40);
    assert_int_equal(exact, covered);

    /* Inside: 900 m, the first ellipsoid's centre. */
    host_coverage(cut, 900.0, view, proj);
    cu_cloud cl;
    cu_cloud_build(&cl, host_scene, NULL);
    int checked = 0, veiled_less = 0;
    double worst = 0;
    for (int y = 0; y < H; y += 3)
        for (int x = 0; x < W / 2; x += 3) {
            int i = y * W + x;
            if (full[i] < 0.05)
                continue;
            double want = 1.0 - exp(-cpu_tau(&cl, x, y, 900.0));
            worst = fmax(worst, fabs(cut[i] - want));
            assert_true(fabs(cut[i] - want) < 0.01 + 0.03 * want);
            checked++;
            veiled_less += cut[i] < full[i] - 0.02;
        }
    /* Right of the quad the whole cloud is there. */
    for (int i = 0; i < N; i++)
        if (i % W >= W / 2)
            assert_float_equal(cut[i], full[i], 1e-6);
    printf("quad inside: %d pixels against the CPU optical depth, worst |alpha - alpha_cpu| %.4f, %d veiled less\n",
           checked, worst, veiled_less);
    assert_true(checked > 20 && veiled_less > checked / 2);

    /* Behind: 3000 m. The same as the cloud composited over a host without depth. */
    host_draw(fbo8, bg, fg, 3000.0, proj);
    host_render((cu_frame){.fbo = fbo8, .width = W, .height = H, .clouds_only = 1, .view = view, .projection = proj,
                      .depth_texture = depth_tex});
    host_read(fbo8, 0, px);
    host_draw(fbo8, bg, fg, 3000.0, proj);
    host_render((cu_frame){.fbo = fbo8, .width = W, .height = H, .clouds_only = 1, .view = view, .projection = proj});
    host_read(fbo8, 0, ref);
    assert_memory_equal(px, ref, sizeof px);
}
int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_matrices_equal_scene_camera),
        cmocka_unit_test(test_asymmetric_frusta),
        cmocka_unit_test(test_clouds_only_keeps_host_pixels),
        cmocka_unit_test(test_host_depth),
    };
    return cmocka_run_group_tests(tests, host_setup, host_teardown);
}
