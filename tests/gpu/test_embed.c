/* tests/gpu/test_embed.c: cumulo inside a host's renderer: the host's view and projection against the scene's
 * [camera], clouds composited over the host's colour, the host's depth cutting the march (checked against the CPU
 * twin of the density), the GL state contract, and finite images at the projection extremes. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <GLES3/gl3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "density.h"
#include "render_util.h"
#include "scene.h"
#include "scene_camera.h"

#define W 96
#define H 72
#define N (W * H)
#define UNITS 11 /* the texture units cumulo's contract covers */

/* Two ellipsoids on the view axis, noise off so the CPU twin needs no noise texture; many segments so the march
 * is close to the exact optical depth. */
#define SCENE                                                                                                  \
    "[camera]\nposition = 0 250 -900\nlook_at = 0 250 0\nfov = 50\n[sun]\nelevation = 30\nazimuth = 135\n"   \
    "[cloud]\nphase = hg\ndensity = 40\nboundary = 30\n[ellipsoid]\ncenter = 0 250 0\nradii = 200 120 160\n" \
    "[ellipsoid]\ncenter = 150 230 40\nradii = 140 100 120\n[quality]\nnoise = off\nsegments = 32\n"

static tr_ctx ctx;
static cu_scene *scene;
static GLuint fbo8, fbo32, col8, col32, depth_tex, quad_prog;
static GLint quad_depth_loc, quad_color_loc;

static const char *quad_vs = "#version 300 es\nuniform float u_z;\nvoid main() {\n"
                             "  vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);\n"
                             "  gl_Position = vec4(p, u_z, 1.0);\n}\n";
static const char *quad_fs = "#version 300 es\nprecision mediump float;\nuniform vec4 u_color;\nout vec4 o;\n"
                             "void main() { o = u_color; }\n";

static GLuint shader(GLenum type, const char *src)
{
    GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &src, NULL);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    assert_true(ok);
    return s;
}

static GLuint make_fbo(GLuint *col, GLenum internal)
{
    GLuint f;
    glGenFramebuffers(1, &f);
    glBindFramebuffer(GL_FRAMEBUFFER, f);
    glGenRenderbuffers(1, col);
    glBindRenderbuffer(GL_RENDERBUFFER, *col);
    glRenderbufferStorage(GL_RENDERBUFFER, internal, W, H);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, *col);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth_tex, 0);
    assert_int_equal(glCheckFramebufferStatus(GL_FRAMEBUFFER), GL_FRAMEBUFFER_COMPLETE);
    return f;
}

static int setup(void **st)
{
    (void)st;
    cu_error e;
    if (tr_open(&ctx, &cu_display_egl, W, H, 1)) {
        fprintf(stderr, "%s\n", ctx.err);
        return 1;
    }
    if (cu_scene_parse(&scene, "embed.scene", SCENE, strlen(SCENE), &e) || cu_renderer_set_scene(ctx.r, scene, &e)) {
        fprintf(stderr, "%s\n", e.msg);
        return 1;
    }
    glGenTextures(1, &depth_tex);
    glBindTexture(GL_TEXTURE_2D, depth_tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, W, H, 0, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, NULL);
    /* The host's own sampling state, which cumulo must override and leave alone: linear filtering and a compare
     * mode would make a plain sampler2D read undefined. */
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    fbo8 = make_fbo(&col8, GL_RGBA8);
    fbo32 = make_fbo(&col32, GL_RGBA32F);
    quad_prog = glCreateProgram();
    glAttachShader(quad_prog, shader(GL_VERTEX_SHADER, quad_vs));
    glAttachShader(quad_prog, shader(GL_FRAGMENT_SHADER, quad_fs));
    glLinkProgram(quad_prog);
    quad_depth_loc = glGetUniformLocation(quad_prog, "u_z");
    quad_color_loc = glGetUniformLocation(quad_prog, "u_color");
    return 0;
}

static int teardown(void **st)
{
    (void)st;
    cu_scene_free(scene);
    tr_close(&ctx);
    return 0;
}

/* The host's matrices: the scene's view, a projection with the host's own planes. */
static void host_matrices(float view[16], float proj[16], double znear, double zfar)
{
    cu_error e;
    assert_int_equal(cu_scene_camera_matrices(scene, (double)W / H, znear, zfar, view, proj, &e), 0);
}

/* The host's frame: colour cleared to `bg`, depth cleared to 1, then (eye_dist > 0) a quad of colour `fg` at eye
 * distance eye_dist over the pixels x < W/2, written with depth under proj. */
static void host_draw(GLuint fbo, const float bg[4], const float fg[4], double eye_dist, const float proj[16])
{
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, W, H);
    glClearColor(bg[0], bg[1], bg[2], bg[3]);
    glClearDepthf(1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    if (eye_dist <= 0)
        return;
    /* clip z / w of a point at z_eye = -d: (m10 (-d) + m14) / d */
    double zndc = (proj[10] * -eye_dist + proj[14]) / eye_dist;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 0, W / 2, H);
    glUseProgram(quad_prog);
    glUniform1f(quad_depth_loc, (float)zndc);
    glUniform4fv(quad_color_loc, 1, fg);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_DEPTH_TEST);
}

static void render(cu_frame f)
{
    cu_error e;
    if (cu_render(ctx.r, &f, &e))
        fail_msg("cu_render: %s", e.msg);
}

/* Pixels of fbo, bottom row first (GL's order), as floats in [0, 1] for RGBA8 or radiance for RGBA32F. */
static void read_fbo(GLuint fbo, int is_float, float *px)
{
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    if (is_float) {
        glReadPixels(0, 0, W, H, GL_RGBA, GL_FLOAT, px);
        return;
    }
    static unsigned char b[N * 4];
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, b);
    for (int i = 0; i < N * 4; i++)
        px[i] = b[i];
}

static const float BLACK0[4] = {0, 0, 0, 0};

/* The clouds' coverage per pixel: clouds only, linear, over a transparent black host without depth. */
static void coverage(float *alpha, double quad_dist, const float *view, const float *proj)
{
    static float px[N * 4];
    host_draw(fbo32, BLACK0, BLACK0, quad_dist, proj);
    cu_frame f = {.fbo = fbo32, .width = W, .height = H, .linear = 1, .clouds_only = 1, .view = view,
                  .projection = proj, .depth_texture = quad_dist > 0 ? depth_tex : 0};
    render(f);
    read_fbo(fbo32, 1, px);
    for (int i = 0; i < N; i++)
        alpha[i] = px[i * 4 + 3];
}

/* The scene's [camera] and the same view as matrices give the same image, bit for bit; a view turned by 2 degrees
 * does not (the matrices are used), and matrices built here, independently, agree to rounding. */
static void test_matrices_equal_scene_camera(void **st)
{
    (void)st;
    static float a[N * 4], b[N * 4];
    float view[16], proj[16];
    host_matrices(view, proj, 0.5, 5000.0);
    render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1});
    read_fbo(fbo32, 1, a);
    render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1, .view = view, .projection = proj});
    read_fbo(fbo32, 1, b);
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
    render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1, .view = v2, .projection = p2});
    read_fbo(fbo32, 1, b);
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
    render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1, .view = v3m, .projection = p2});
    read_fbo(fbo32, 1, b);
    int moved = 0;
    for (int i = 0; i < N; i++)
        moved += fabs(a[i * 4 + 1] - b[i * 4 + 1]) > 0.05 * fabs(a[i * 4 + 1]) + 1e-3;
    printf("turned 2 degrees: %d of %d pixels changed\n", moved, N);
    assert_true(moved > N / 50);
}

/* Clouds only: wherever no cloud is, the host's colour stays bit for bit; where one is, it changes. */
static void test_clouds_only_keeps_host_pixels(void **st)
{
    (void)st;
    static float alpha[N], px[N * 4];
    float view[16], proj[16];
    host_matrices(view, proj, 0.5, 5000.0);
    coverage(alpha, 0, view, proj);
    const float bg[4] = {0.8f, 0.1f, 0.3f, 1.0f};
    float want[4];
    host_draw(fbo8, bg, bg, 0, proj);
    read_fbo(fbo8, 0, px);
    memcpy(want, px, sizeof want); /* the host's colour as its framebuffer holds it */
    render((cu_frame){.fbo = fbo8, .width = W, .height = H, .clouds_only = 1, .view = view, .projection = proj});
    read_fbo(fbo8, 0, px);
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
    render((cu_frame){.fbo = fbo8, .width = W, .height = H, .view = view, .projection = proj});
    read_fbo(fbo8, 0, px);
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
    coverage(full, 0, view, proj);

    /* In front: 300 m from the eye, the cloud begins near 700 m. */
    const float bg[4] = {0.2f, 0.4f, 0.9f, 1.0f}, fg[4] = {0.1f, 0.7f, 0.2f, 1.0f};
    float fg8[4];
    host_draw(fbo8, bg, fg, 300.0, proj);
    read_fbo(fbo8, 0, px);
    memcpy(fg8, px, sizeof fg8); /* pixel (0, 0) lies under the quad */
    render((cu_frame){.fbo = fbo8, .width = W, .height = H, .clouds_only = 1, .view = view, .projection = proj,
                      .depth_texture = depth_tex});
    read_fbo(fbo8, 0, px);
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
    coverage(cut, 900.0, view, proj);
    cu_cloud cl;
    cu_cloud_build(&cl, scene, NULL);
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
    render((cu_frame){.fbo = fbo8, .width = W, .height = H, .clouds_only = 1, .view = view, .projection = proj,
                      .depth_texture = depth_tex});
    read_fbo(fbo8, 0, px);
    host_draw(fbo8, bg, fg, 3000.0, proj);
    render((cu_frame){.fbo = fbo8, .width = W, .height = H, .clouds_only = 1, .view = view, .projection = proj});
    read_fbo(fbo8, 0, ref);
    assert_memory_equal(px, ref, sizeof px);
}

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
    glUseProgram(quad_prog);
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
    /* A new scene, a sun move (dirty sun maps, the energy closure's read-back) and two frames, one with depth. */
    assert_int_equal(cu_renderer_set_scene(ctx.r, scene, &e), 0);
    gl_state(after, 128);
    assert_memory_equal(before, after, sizeof(GLint) * (size_t)n);
    assert_int_equal(cu_renderer_set_sun(ctx.r, 40, 200, &e), 0);
    render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1});
    gl_state(after, 128);
    assert_memory_equal(before, after, sizeof(GLint) * (size_t)n);
    render((cu_frame){.fbo = fbo8, .width = W, .height = H, .clouds_only = 1, .view = view, .projection = proj,
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
    assert_int_equal(cu_renderer_set_sun(ctx.r, 30, 135, &e), 0);
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

/* The camera inside the cloud with near 0.01 m and far 1e7 m, an infinite far plane, a reversed-Z depth, an
 * orthographic view: finite, non-negative, and the cloud is there. The orthographic view straight through the
 * first ellipsoid's centre matches the closed form of a uniform core. */
static void test_projection_extremes(void **st)
{
    (void)st;
    static float px[N * 4];
    float view[16], proj[16];
    int covered;
    cu_error e;
    cu_scene *in;
    assert_int_equal(cu_scene_parse(&in, "inside.scene", SCENE, strlen(SCENE), &e), 0);
    assert_int_equal(cu_scene_set(in, "camera.position=0 250 -50", &e), 0);
    assert_int_equal(cu_renderer_set_scene(ctx.r, in, &e), 0);
    assert_int_equal(cu_scene_camera_matrices(in, (double)W / H, 0.01, 1e7, view, proj, &e), 0);
    host_draw(fbo32, BLACK0, BLACK0, 0, proj);
    render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1, .clouds_only = 1, .view = view,
                      .projection = proj, .depth_texture = depth_tex});
    read_fbo(fbo32, 1, px);
    assert_finite_image("inside, near 0.01 far 1e7", px, &covered);
    assert_int_equal(covered, N);

    /* Infinite far: m10 = -1, m14 = -2 near; the host's cleared depth (1) unprojects to w = 0. */
    proj[10] = -1.0f;
    proj[14] = -0.02f;
    host_draw(fbo32, BLACK0, BLACK0, 0, proj);
    render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1, .clouds_only = 1, .view = view,
                      .projection = proj, .depth_texture = depth_tex});
    read_fbo(fbo32, 1, px);
    assert_finite_image("inside, infinite far", px, &covered);
    assert_int_equal(covered, N);

    /* Reversed Z (near -> +1, far -> -1 in clip z), depth cleared to 0. */
    proj[10] = (float)((0.01 + 1e7) / (1e7 - 0.01));
    proj[14] = (float)(2.0 * 1e7 * 0.01 / (1e7 - 0.01));
    glBindFramebuffer(GL_FRAMEBUFFER, fbo32);
    glClearDepthf(0.0f);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glClearDepthf(1.0f);
    render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1, .clouds_only = 1, .view = view,
                      .projection = proj, .depth_texture = depth_tex, .depth_reversed = 1});
    read_fbo(fbo32, 1, px);
    assert_finite_image("inside, reversed Z", px, &covered);
    assert_int_equal(covered, N);
    cu_scene_free(in);

    /* Orthographic, 600 m x 450 m, along +z through the first ellipsoid's centre (0, 250, 0), near plane 10 m. */
    assert_int_equal(cu_renderer_set_scene(ctx.r, scene, &e), 0);
    host_matrices(view, proj, 0.5, 5000.0);
    float ortho[16] = {0};
    ortho[0] = 2.0f / 600.0f;
    ortho[5] = 2.0f / 450.0f;
    ortho[10] = -2.0f / (5000.0f - 10.0f);
    ortho[14] = -(5000.0f + 10.0f) / (5000.0f - 10.0f);
    ortho[15] = 1.0f;
    host_draw(fbo32, BLACK0, BLACK0, 0, proj);
    render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1, .clouds_only = 1, .view = view,
                      .projection = ortho});
    read_fbo(fbo32, 1, px);
    assert_finite_image("orthographic", px, &covered);
    /* The first ellipsoid covers x in [-200, 200] of 600 and y in [130, 370] of [25, 475]; the second adds to it. */
    printf("orthographic: %d of %d pixels covered\n", covered, N);
    assert_true(covered > N / 5 && covered < N * 3 / 4);
    /* The central pixel's ray (x = 0, y = 250) crosses the first ellipsoid along z: 2 x 160 m, of which the
     * boundary ramps; the CPU twin integrates the same line. */
    cu_cloud cl;
    cu_cloud_build(&cl, scene, NULL);
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
    render((cu_frame){.fbo = fbo32, .width = W, .height = H, .linear = 1, .clouds_only = 1, .view = view,
                      .projection = ortho});
    read_fbo(fbo32, 1, px);
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
    assert_int_not_equal(cu_render(ctx.r, &f, &e), 0);
    assert_non_null(strstr(e.msg, "bottom row"));
    f.projection = NULL;
    assert_int_not_equal(cu_render(ctx.r, &f, &e), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_matrices_equal_scene_camera),
        cmocka_unit_test(test_clouds_only_keeps_host_pixels),
        cmocka_unit_test(test_host_depth),
        cmocka_unit_test(test_state_contract),
        cmocka_unit_test(test_projection_extremes),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
