/* tests/gpu/test_embed_state.c: what embedding must not break (tests/gpu/host_util.h is the host): every item of
 * the GL state contract as the host left it after each cumulo call, and finite images at the projection extremes
 * (the camera inside a cloud with near 0.01 m and far 1e7 m, an infinite far plane, reversed Z, orthographic). */
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
#include "renderer.h"
#include "scene_camera.h"

#define UNITS 14 /* the texture units cumulo's contract covers */

/* The contract's items, as the host would read them with glGet, flattened into out; returns how many. */
static int gl_state(GLint *out, int max)
{
    int n = 0;
    static const GLenum ints[] = {GL_DRAW_FRAMEBUFFER_BINDING, GL_READ_FRAMEBUFFER_BINDING, GL_CURRENT_PROGRAM,
        GL_VERTEX_ARRAY_BINDING, GL_ARRAY_BUFFER_BINDING, GL_RENDERBUFFER_BINDING, GL_ACTIVE_TEXTURE,
        GL_BLEND_SRC_RGB, GL_BLEND_DST_RGB, GL_BLEND_SRC_ALPHA, GL_BLEND_DST_ALPHA, GL_BLEND_EQUATION_RGB,
        GL_BLEND_EQUATION_ALPHA, GL_DEPTH_FUNC, GL_STENCIL_FUNC, GL_STENCIL_REF, GL_STENCIL_VALUE_MASK,
        GL_STENCIL_WRITEMASK, GL_STENCIL_FAIL, GL_STENCIL_PASS_DEPTH_FAIL, GL_STENCIL_PASS_DEPTH_PASS,
        GL_STENCIL_BACK_FUNC, GL_STENCIL_BACK_REF, GL_STENCIL_BACK_VALUE_MASK, GL_STENCIL_BACK_WRITEMASK,
        GL_STENCIL_BACK_FAIL, GL_STENCIL_BACK_PASS_DEPTH_FAIL, GL_STENCIL_BACK_PASS_DEPTH_PASS,
        GL_STENCIL_CLEAR_VALUE, GL_PACK_ALIGNMENT, GL_UNPACK_ALIGNMENT};
    static const GLenum caps[] = {GL_BLEND, GL_DEPTH_TEST, GL_STENCIL_TEST, GL_CULL_FACE, GL_SCISSOR_TEST,
        GL_POLYGON_OFFSET_FILL, GL_RASTERIZER_DISCARD, GL_SAMPLE_ALPHA_TO_COVERAGE, GL_SAMPLE_COVERAGE};
    for (size_t i = 0; i < sizeof ints / sizeof *ints; i++)
        glGetIntegerv(ints[i], &out[n++]);
    for (size_t i = 0; i < sizeof caps / sizeof *caps; i++)
        out[n++] = glIsEnabled(caps[i]);
    GLint active;
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    for (int u = 0; u < UNITS; u++) {
        glActiveTexture(GL_TEXTURE0 + u);
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &out[n++]);
        glGetIntegerv(GL_TEXTURE_BINDING_3D, &out[n++]);
        glGetIntegerv(GL_SAMPLER_BINDING, &out[n++]);
    }
    glActiveTexture((GLenum)active);
    glGetIntegerv(GL_VIEWPORT, &out[n]);
    n += 4;
    glGetIntegerv(GL_SCISSOR_BOX, &out[n]);
    n += 4;
    GLboolean b[4];
    glGetBooleanv(GL_COLOR_WRITEMASK, b);
    for (int i = 0; i < 4; i++)
        out[n++] = b[i];
    glGetBooleanv(GL_DEPTH_WRITEMASK, b);
    out[n++] = b[0];
    float f[5];
    glGetFloatv(GL_COLOR_CLEAR_VALUE, f);
    glGetFloatv(GL_DEPTH_CLEAR_VALUE, &f[4]);
    for (int i = 0; i < 5; i++)
        memcpy(&out[n++], &f[i], sizeof(GLint));
    assert_true(n <= max);
    return n;
}

/* Every item of the state contract is as the host set it after each cumulo call. */
static void test_state_contract(void **st)
{
    (void)st;
    float view[16], proj[16];
    host_matrices(view, proj, 0.5, 5000.0);
    GLuint vao, buf, rb, tex[UNITS], tex3, samp;
    glGenVertexArrays(1, &vao);
    glGenBuffers(1, &buf);
    glGenRenderbuffers(1, &rb);
    glGenTextures(UNITS, tex);
    glGenTextures(1, &tex3);
    glGenSamplers(1, &samp);
    for (int u = 0; u < UNITS; u++) {
        glActiveTexture(GL_TEXTURE0 + u);
        glBindTexture(GL_TEXTURE_2D, tex[u]);
        if (u == 5)
            glBindTexture(GL_TEXTURE_3D, tex3);
    }
    glBindSampler(3, samp);
    glActiveTexture(GL_TEXTURE7);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo8);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo32);
    glUseProgram(host_quad_prog);
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, buf);
    glBindRenderbuffer(GL_RENDERBUFFER, rb);
    glViewport(3, 4, 50, 40);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_COLOR, GL_DST_ALPHA, GL_ZERO, GL_CONSTANT_COLOR);
    glBlendEquationSeparate(GL_FUNC_SUBTRACT, GL_MAX);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GEQUAL);
    glDepthMask(GL_FALSE);
    glEnable(GL_STENCIL_TEST);
    glStencilFuncSeparate(GL_FRONT, GL_NOTEQUAL, 7, 0x3c);
    glStencilFuncSeparate(GL_BACK, GL_LEQUAL, 3, 0x0f);
    glStencilOpSeparate(GL_FRONT, GL_INVERT, GL_DECR, GL_INCR_WRAP);
    glStencilOpSeparate(GL_BACK, GL_ZERO, GL_REPLACE, GL_DECR_WRAP);
    glStencilMaskSeparate(GL_FRONT, 0x55);
    glStencilMaskSeparate(GL_BACK, 0xaa);
    glEnable(GL_CULL_FACE);
    glEnable(GL_SCISSOR_TEST);
    glScissor(1, 2, 3, 4);
    glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
    glClearColor(0.25f, 0.5f, 0.75f, 0.125f);
    glClearDepthf(0.375f);
    glClearStencil(9);
    glPixelStorei(GL_PACK_ALIGNMENT, 2);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 8);

    GLint before[128], after[128];
    int n = gl_state(before, 128);
    cu_error e;
    /* A new host_scene, a sun move (dirty sun maps, the energy closure's read-back) and two frames, one with depth. */
    assert_int_equal(cu_renderer_set_scene(host_ctx.r, host_scene, &e), 0);
    gl_state(after, 128);
    assert_memory_equal(before, after, sizeof(GLint) * (size_t)n);
    assert_int_equal(cu_renderer_set_sun(host_ctx.r, 40, 200, &e), 0);
    host_render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1});
    gl_state(after, 128);
    assert_memory_equal(before, after, sizeof(GLint) * (size_t)n);
    host_render((cu_frame){.fbo = fbo8, .width = W, .height = H, .clouds_only = 1, .view = view, .projection = proj,
                      .depth_texture = depth_tex});
    gl_state(after, 128);
    for (int i = 0; i < n; i++)
        if (before[i] != after[i])
            fail_msg("state item %d: %d before, %d after", i, before[i], after[i]);
    assert_int_equal(glGetError(), GL_NO_ERROR);

    /* Put the defaults back for the other tests. */
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
    glDepthMask(GL_TRUE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glStencilMask(0xff);
    glBlendEquation(GL_FUNC_ADD);
    glBindSampler(3, 0);
    glActiveTexture(GL_TEXTURE0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    assert_int_equal(cu_renderer_set_sun(host_ctx.r, 30, 135, &e), 0);
}

static void assert_finite_image(const char *label, const float *px, int *covered)
{
    *covered = 0;
    for (int i = 0; i < N * 4; i++)
        if (!isfinite(px[i]) || px[i] < 0)
            fail_msg("%s: pixel %d channel %d = %g", label, i / 4, i % 4, px[i]);
    for (int i = 0; i < N; i++)
        *covered += px[i * 4 + 3] > 0.01f;
}

/* Clouds only over a host whose depth is cleared (to 0 when reversed): every pixel inside the cloud is covered. */
static void inside_frame(const float *view, const float *proj, int reversed, float *px, const char *label)
{
    int covered;
    glBindFramebuffer(GL_FRAMEBUFFER, fbo32);
    glClearDepthf(reversed ? 0.0f : 1.0f);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glClearDepthf(1.0f);
    host_render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1, .clouds_only = 1, .view = view,
                           .projection = proj, .depth_texture = depth_tex, .depth_reversed = reversed});
    host_read(fbo32, 1, px);
    assert_finite_image(label, px, &covered);
    assert_int_equal(covered, N);
}

/* The camera inside the cloud with near 0.01 m and far 1e7 m, an infinite far plane, a reversed-Z depth, an
 * orthographic view: finite, non-negative, and the cloud is there. The orthographic view straight through the
 * first ellipsoid's centre matches the closed form of a uniform core. */
static void test_projection_extremes(void **st)
{
    (void)st;
    static float px[N * 4], first[N * 4];
    float view[16], proj[16];
    int covered;
    cu_error e;
    cu_scene *in;
    assert_int_equal(cu_scene_parse(&in, "inside.scene", HOST_SCENE_TEXT, strlen(HOST_SCENE_TEXT), &e), 0);
    assert_int_equal(cu_scene_set(in, "camera.position=0 250 -50", &e), 0);
    assert_int_equal(cu_renderer_set_scene(host_ctx.r, in, &e), 0);
    assert_int_equal(cu_scene_camera_matrices(in, (double)W / H, 0.01, 1e7, view, proj, &e), 0);
    inside_frame(view, proj, 0, first, "inside, near 0.01 far 1e7");

    /* Infinite far: m10 = -1, m14 = -2 near; the host's cleared depth (1) unprojects to w = 0. The depth row is
     * cumulo's own, so the image is the same. */
    proj[10] = -1.0f;
    proj[14] = -0.02f;
    inside_frame(view, proj, 0, px, "inside, infinite far");
    assert_memory_equal(px, first, sizeof px);

    /* Reversed Z (near -> +1, far -> -1 in clip z), depth cleared to 0. */
    proj[10] = (float)((0.01 + 1e7) / (1e7 - 0.01));
    proj[14] = (float)(2.0 * 1e7 * 0.01 / (1e7 - 0.01));
    inside_frame(view, proj, 1, px, "inside, reversed Z");
    assert_memory_equal(px, first, sizeof px);
    cu_scene_free(in);

    /* Orthographic, 600 m x 450 m, along +z through the first ellipsoid's centre (0, 250, 0), near plane 10 m. */
    assert_int_equal(cu_renderer_set_scene(host_ctx.r, host_scene, &e), 0);
    host_matrices(view, proj, 0.5, 5000.0);
    float ortho[16] = {0};
    ortho[0] = 2.0f / 600.0f;
    ortho[5] = 2.0f / 450.0f;
    ortho[10] = -2.0f / (5000.0f - 10.0f);
    ortho[14] = -(5000.0f + 10.0f) / (5000.0f - 10.0f);
    ortho[15] = 1.0f;
    host_draw(fbo32, BLACK0, BLACK0, 0, proj);
    host_render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1, .clouds_only = 1, .view = view,
                      .projection = ortho});
    host_read(fbo32, 1, px);
    assert_finite_image("orthographic", px, &covered);
    /* The first ellipsoid covers x in [-200, 200] of 600 and y in [130, 370] of [25, 475]; the second adds to it. */
    printf("orthographic: %d of %d pixels covered\n", covered, N);
    assert_true(covered > N / 5 && covered < N * 3 / 4);
    /* The central pixel's ray (x = 0, y = 250) crosses the first ellipsoid along z: 2 x 160 m, of which the
     * boundary ramps; the CPU twin integrates the same line. */
    cu_cloud cl;
    cu_cloud_build(&cl, host_scene, NULL);
    double tau = 0, dt = 0.25;
    for (double z = -400; z < 400; z += dt)
        tau += dt * cu_cloud_extinction(&cl, v3_sub(v3(0, 250, z + 0.5 * dt), cl.origin));
    /* pixel centres straddle the axis: average the four around it */
    double a = 0;
    for (int dy = 0; dy < 2; dy++)
        for (int dx = 0; dx < 2; dx++)
            a += 0.25 * px[((H / 2 - 1 + dy) * W + W / 2 - 1 + dx) * 4 + 3];
    printf("orthographic centre: alpha %.5f, CPU 1 - e^-tau %.5f (tau %.4f)\n", a, 1 - exp(-tau), tau);
    assert_true(fabs(a - (1 - exp(-tau))) < 0.01);

    /* The host's near plane through the centre (900 m from the eye): only the far half is seen (the full-screen
     * path, as the near plane cuts the hulls). */
    ortho[10] = -2.0f / (5000.0f - 900.0f);
    ortho[14] = -(5000.0f + 900.0f) / (5000.0f - 900.0f);
    host_draw(fbo32, BLACK0, BLACK0, 0, proj);
    host_render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1, .clouds_only = 1, .view = view,
                      .projection = ortho});
    host_read(fbo32, 1, px);
    assert_finite_image("orthographic, near plane in the cloud", px, &covered);
    double tau_half = 0;
    for (double z = 0; z < 400; z += dt)
        tau_half += dt * cu_cloud_extinction(&cl, v3_sub(v3(0, 250, z + 0.5 * dt), cl.origin));
    a = 0;
    for (int dy = 0; dy < 2; dy++)
        for (int dx = 0; dx < 2; dx++)
            a += 0.25 * px[((H / 2 - 1 + dy) * W + W / 2 - 1 + dx) * 4 + 3];
    printf("orthographic, near plane at the centre: alpha %.5f, CPU %.5f\n", a, 1 - exp(-tau_half));
    assert_true(fabs(a - (1 - exp(-tau_half))) < 0.01);

    /* Not a projection: refused with a message. */
    float bad[16] = {1, 0, 0, 0.5f, 0, 1, 0, 0, 0, 0, 1, -1, 0, 0, 0, 0};
    cu_frame f = {.fbo = fbo32, .width = W, .height = H, .linear = 1, .view = view, .projection = bad};
    assert_int_not_equal(cu_render(host_ctx.r, &f, &e), 0);
    assert_non_null(strstr(e.msg, "bottom row"));
    f.projection = NULL;
    assert_int_not_equal(cu_render(host_ctx.r, &f, &e), 0);
}
/* What a frame costs follows what is on screen: the scene's view rasterises the hulls (the near plane cuts none),
 * the camera in the cloud takes the full-screen path, and a view turned away from the clouds skips the cloud pass and
 * is the sky alone, bit for bit the same as the same view of a cloud of zero density. */
static void test_culling(void **st)
{
    (void)st;
    static float px[N * 4], sky[N * 4];
    float view[16], proj[16];
    cu_error e;
    const cu_gpu_scene *g = &host_ctx.r->ctx;
    host_matrices(view, proj, 0.5, 5000.0);
    host_render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1, .view = view, .projection = proj});
    assert_true(g->camera.visible);
    assert_false(cu_pass_cloud_fullscreen(g));

    cu_scene *s;
    assert_int_equal(cu_scene_parse(&s, "turned.scene", HOST_SCENE_TEXT, strlen(HOST_SCENE_TEXT), &e), 0);
    assert_int_equal(cu_scene_set(s, "camera.position=0 250 -100", &e), 0);
    assert_int_equal(cu_renderer_set_scene(host_ctx.r, s, &e), 0);
    host_render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1});
    assert_true(g->camera.visible);
    assert_true(cu_pass_cloud_fullscreen(g));

    /* Looking 73 degrees to the side of the cloud (fov 50 x 64 degrees): the cloud is in front of the eye (the depth
     * range does not cull it), outside the frustum's side plane (this test is what culls it). */
    assert_int_equal(cu_scene_set(s, "camera.position=0 250 -900", &e), 0);
    assert_int_equal(cu_scene_set(s, "camera.look_at=1000 250 -600", &e), 0);
    assert_int_equal(cu_renderer_set_scene(host_ctx.r, s, &e), 0);
    host_render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1});
    host_read(fbo32, 1, px);
    assert_false(g->camera.visible);
    assert_int_equal(cu_scene_set(s, "cloud.density=0", &e), 0);
    assert_int_equal(cu_renderer_set_scene(host_ctx.r, s, &e), 0);
    host_render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1});
    host_read(fbo32, 1, sky);
    assert_memory_equal(px, sky, sizeof px);
    /* Looking at the cloud again, it is culled no longer. */
    assert_int_equal(cu_scene_set(s, "camera.look_at=0 250 0", &e), 0);
    assert_int_equal(cu_scene_set(s, "cloud.density=40", &e), 0);
    assert_int_equal(cu_renderer_set_scene(host_ctx.r, s, &e), 0);
    host_render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1});
    assert_true(g->camera.visible);
    cu_scene_free(s);
    assert_int_equal(cu_renderer_set_scene(host_ctx.r, host_scene, &e), 0);
}

/* The tone-mapped frame's fp16 target never overflows on the brightest legal scene (the sun and sky at their
 * largest, exposure 1e6): GPUs store Inf there (NaN after the tone curve), llvmpipe saturates at 65504; the passes
 * store exposed values capped below it, which the tone curve shows as white anyway. */
static void test_fp16_target_finite(void **st)
{
    (void)st;
    static float px[N * 4];
    cu_error e;
    cu_scene *s;
    assert_int_equal(cu_scene_parse(&s, "bright.scene", HOST_SCENE_TEXT, strlen(HOST_SCENE_TEXT), &e), 0);
    assert_int_equal(cu_scene_set(s, "sun.irradiance=1e6 1e6 1e6", &e), 0);
    assert_int_equal(cu_scene_set(s, "sky.model=constant", &e), 0);
    assert_int_equal(cu_scene_set(s, "sky.color=1e6 1e6 1e6", &e), 0);
    assert_int_equal(cu_scene_set(s, "output.exposure=1e6", &e), 0);
    assert_int_equal(cu_renderer_set_scene(host_ctx.r, s, &e), 0);
    host_render((cu_frame){.fbo = fbo8, .width = W, .height = H});
    const cu_target *hdr = &host_ctx.r->pass_tonemap.hdr;
    if (hdr->format != GL_RGBA16F)
        skip();
    host_read(hdr->fbo, 1, px);
    for (int i = 0; i < N * 4; i++)
        if (!isfinite(px[i]) || px[i] >= 65504.0f) /* Inf, or saturated at the largest half (llvmpipe's overflow) */
            fail_msg("fp16 target pixel %d channel %d = %g: overflowed", i / 4, i % 4, px[i]);
    host_read(fbo8, 0, px);
    for (int i = 0; i < N * 4; i++)
        assert_true(px[i] == 255.0f);
    cu_scene_free(s);
    assert_int_equal(cu_renderer_set_scene(host_ctx.r, host_scene, &e), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_state_contract),
        cmocka_unit_test(test_projection_extremes),
        cmocka_unit_test(test_culling),
        cmocka_unit_test(test_fp16_target_finite),
    };
    return cmocka_run_group_tests(tests, host_setup, host_teardown);
}
