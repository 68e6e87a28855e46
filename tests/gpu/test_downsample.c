/* tests/gpu/test_downsample.c: quality.cloud_downsample, the clouds drawn at 1/N resolution and upsampled
 * (src/gpu/pass_upsample.c): the error against the full-resolution clouds grows with N and stays bounded; no halo
 * against the sky (pixels that no cloud is near stay exactly as they were, and the edge never over- or undershoots
 * the full-resolution values about it); no halo against the host's depth (a host quad in front of the cloud keeps
 * its colour to the pixel at its edge, where plain bilinear upsampling would bleed the cloud behind it over it).
 * The host is tests/gpu/host_util.c's (two ellipsoids on the view axis, noise off). */
#include "host_util.h"
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

static double edge_refine; /* quality.edge_refine for the frames of use_downsample (0: off) */

static void use_downsample(int n)
{
    char set[64], refine[64];
    cu_error e;
    snprintf(set, sizeof set, "quality.cloud_downsample=%d", n);
    snprintf(refine, sizeof refine, "quality.edge_refine=%.9g", edge_refine);
    if (cu_scene_set(host_scene, set, &e) || cu_scene_set(host_scene, refine, &e) ||
        cu_renderer_set_scene(host_ctx.r, host_scene, &e))
        fail_msg("%s: %s", set, e.msg);
}

/* Linear clouds-only frame (premultiplied radiance and coverage) at downsample n, no host depth. */
static void clouds(int n, float *px, const float *view, const float *proj)
{
    use_downsample(n);
    host_draw(fbo32, BLACK0, BLACK0, 0, proj);
    host_render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1, .clouds_only = 1, .view = view,
                           .projection = proj});
    host_read(fbo32, 1, px);
}

/* The error of coverage and radiance against N = 1 grows with N, within bounds: mean over the 633 pixels the cloud
 * covers at full resolution in this 96x72 view (small: edges are a large share), measured on llvmpipe: coverage
 * 0.032 and radiance 5.3 % at N = 2, 0.064 and 10.7 % at N = 4; the bounds are half as much again. */
static void test_error_grows_with_n(void **st)
{
    (void)st;
    static float ref[N * 4], px[N * 4];
    float view[16], proj[16];
    host_matrices(view, proj, 0.5, 5000.0);
    clouds(1, ref, view, proj);
    double err[5] = {0}, rad[5] = {0};
    for (int n = 2; n <= 4; n += 2) {
        clouds(n, px, view, proj);
        int count = 0;
        double sum_ref = 0;
        for (int i = 0; i < N; i++) {
            if (!(ref[i * 4 + 3] > 0.02))
                continue;
            count++;
            err[n] += fabs(px[i * 4 + 3] - ref[i * 4 + 3]);
            rad[n] += fabs(px[i * 4 + 1] - ref[i * 4 + 1]);
            sum_ref += ref[i * 4 + 1];
            assert_true(isfinite(px[i * 4]) && isfinite(px[i * 4 + 3]));
        }
        assert_true(count > N / 20);
        err[n] /= count;
        rad[n] /= sum_ref; /* relative to the mean radiance */
        printf("N = %d: mean |coverage error| %.4f, mean |radiance error| / mean radiance %.4f over %d pixels\n", n,
               err[n], rad[n], count);
    }
    assert_true(err[2] > 0 && err[2] < 0.048 && rad[2] < 0.08);
    assert_true(err[4] > err[2] && err[4] < 0.096 && rad[4] < 0.16);
    use_downsample(1);
}

/* Against the sky: a pixel with no cloud within N + 1 pixels at full resolution is not touched; every other one lies
 * within the full-resolution values of the (2N + 1)^2 pixels about it (no ring brighter or darker than the cloud). */
static void test_no_halo_against_sky(void **st)
{
    (void)st;
    static float ref[N * 4], px[N * 4];
    float view[16], proj[16];
    host_matrices(view, proj, 0.5, 5000.0);
    clouds(1, ref, view, proj);
    for (int n = 2; n <= 4; n += 2) {
        clouds(n, px, view, proj);
        int clear = 0, edge = 0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                int i = y * W + x, r = n + 1, near_cloud = 0;
                for (int dy = -r; dy <= r; dy++)
                    for (int dx = -r; dx <= r; dx++) {
                        int xx = x + dx, yy = y + dy;
                        if (xx >= 0 && xx < W && yy >= 0 && yy < H && ref[(yy * W + xx) * 4 + 3] > 0)
                            near_cloud = 1;
                    }
                if (!near_cloud) {
                    clear++;
                    for (int c = 0; c < 4; c++)
                        if (px[i * 4 + c] != 0.0f)
                            fail_msg("N = %d: pixel (%d, %d) far from any cloud has %g in channel %d", n, x, y,
                                     px[i * 4 + c], c);
                    continue;
                }
                for (int c = 0; c < 4; c++) {
                    float lo = 1e30f, hi = -1e30f;
                    for (int dy = -2 * n; dy <= 2 * n; dy++)
                        for (int dx = -2 * n; dx <= 2 * n; dx++) {
                            int xx = x + dx, yy = y + dy;
                            if (xx < 0 || xx >= W || yy < 0 || yy >= H)
                                continue;
                            lo = fminf(lo, ref[(yy * W + xx) * 4 + c]);
                            hi = fmaxf(hi, ref[(yy * W + xx) * 4 + c]);
                        }
                    float v = px[i * 4 + c], tol = 1e-4f * fmaxf(hi, 1e-3f);
                    if (v < lo - tol || v > hi + tol)
                        fail_msg("N = %d: pixel (%d, %d) channel %d = %g outside the full-resolution %g .. %g about it",
                                 n, x, y, c, v, lo, hi);
                }
                edge++;
            }
        printf("N = %d: %d pixels far from cloud untouched, %d within their neighbourhood's range\n", n, clear,
               edge);
        assert_true(clear > N / 10 && edge > N / 10);
    }
    use_downsample(1);
}

/* Against the host's depth: a quad 300 m from the eye over x < W/2, the cloud behind it from about 700 m. Every
 * pixel of the quad keeps the host's colour exactly, up to its edge; right of the edge the cloud is there. The same
 * with quality.edge_refine near 0 (every pixel a cloud reaches marched again at full resolution, against the host's
 * depth at that pixel): pass_refine.c through upsample.frag. */
static void host_edge(void);
static void test_no_halo_at_host_edge(void **st)
{
    (void)st;
    edge_refine = 0;
    host_edge();
    edge_refine = 1e-6;
    host_edge();
    edge_refine = 0;
    use_downsample(1);
}

static void host_edge(void)
{
    static float px[N * 4], alone[N * 4];
    float view[16], proj[16], fg8[4];
    host_matrices(view, proj, 0.5, 5000.0);
    const float bg[4] = {0.2f, 0.4f, 0.9f, 1.0f}, fg[4] = {0.1f, 0.7f, 0.2f, 1.0f};
    for (int n = 2; n <= 4; n += 2) {
        clouds(n, alone, view, proj);
        host_draw(fbo8, bg, fg, 300.0, proj);
        host_read(fbo8, 0, px);
        memcpy(fg8, px, sizeof fg8); /* pixel (0, 0) lies under the quad */
        host_render((cu_frame){.fbo = fbo8, .width = W, .height = H, .clouds_only = 1, .view = view,
                               .projection = proj, .depth_texture = depth_tex});
        host_read(fbo8, 0, px);
        int behind = 0, kept = 0, right = 0;
        for (int i = 0; i < N; i++) {
            int x = i % W;
            if (x < W / 2 && alone[i * 4 + 3] > 0.02) {
                behind++;
                kept += px[i * 4] == fg8[0] && px[i * 4 + 1] == fg8[1] && px[i * 4 + 2] == fg8[2];
            }
            if (x >= W / 2 && alone[i * 4 + 3] > 0.5)
                right += px[i * 4] != bg[0] * 255.0f || px[i * 4 + 1] != bg[1] * 255.0f; /* the cloud shows */
        }
        /* the column at the quad's edge, where plain bilinear would mix the cloud behind into the quad */
        int edge_behind = 0, edge_kept = 0;
        for (int y = 0; y < H; y++) {
            int i = y * W + W / 2 - 1;
            if (alone[i * 4 + 3] > 0.02) {
                edge_behind++;
                edge_kept += px[i * 4] == fg8[0] && px[i * 4 + 1] == fg8[1] && px[i * 4 + 2] == fg8[2];
            }
        }
        printf("N = %d, edge_refine %g: quad pixels with cloud behind %d, kept exactly %d (edge column %d of %d); %d "
               "cloud pixels right of it\n", n, edge_refine, behind, kept, edge_kept, edge_behind, right);
        assert_true(behind > N / 40 && edge_behind > 3 && right > N / 40);
        assert_int_equal(kept, behind);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_error_grows_with_n),
        cmocka_unit_test(test_no_halo_against_sky),
        cmocka_unit_test(test_no_halo_at_host_edge),
    };
    return cmocka_run_group_tests(tests, host_setup, host_teardown);
}
