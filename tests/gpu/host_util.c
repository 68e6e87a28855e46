/* tests/gpu/host_util.c: the embedding tests' host (see host_util.h). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include "host_util.h"
#include <stdio.h>
#include <string.h>

/* Many segments, so that the march is close to the exact optical depth the tests compare it with. */
const char HOST_SCENE_TEXT[] =
    "[camera]\nposition = 0 250 -900\nlook_at = 0 250 0\nfov = 50\n[sun]\nelevation = 30\nazimuth = 135\n"
    "[cloud]\nphase = hg\ndensity = 40\nboundary = 30\n[ellipsoid]\ncenter = 0 250 0\nradii = 200 120 160\n"
    "[ellipsoid]\ncenter = 150 230 40\nradii = 140 100 120\n[quality]\nnoise = off\nsegments = 32\n";

tr_ctx host_ctx;
cu_scene *host_scene;
GLuint fbo8, fbo32, depth_tex;
GLuint host_quad_prog;
static GLuint col8, col32;
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

int host_setup(void **st)
{
    (void)st;
    cu_error e;
    if (tr_open(&host_ctx, &cu_display_egl, W, H, 1)) {
        fprintf(stderr, "%s\n", host_ctx.err);
        return 1;
    }
    if (cu_scene_parse(&host_scene, "embed.scene", HOST_SCENE_TEXT, strlen(HOST_SCENE_TEXT), &e) || cu_renderer_set_scene(host_ctx.r, host_scene, &e)) {
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
    host_quad_prog = glCreateProgram();
    glAttachShader(host_quad_prog, shader(GL_VERTEX_SHADER, quad_vs));
    glAttachShader(host_quad_prog, shader(GL_FRAGMENT_SHADER, quad_fs));
    glLinkProgram(host_quad_prog);
    quad_depth_loc = glGetUniformLocation(host_quad_prog, "u_z");
    quad_color_loc = glGetUniformLocation(host_quad_prog, "u_color");
    return 0;
}

int host_teardown(void **st)
{
    (void)st;
    cu_scene_free(host_scene);
    tr_close(&host_ctx);
    return 0;
}

void host_matrices(float view[16], float proj[16], double znear, double zfar)
{
    cu_error e;
    assert_int_equal(cu_scene_camera_matrices(host_scene, (double)W / H, znear, zfar, view, proj, &e), 0);
}

void host_draw(GLuint fbo, const float bg[4], const float fg[4], double eye_dist, const float proj[16])
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
    glUseProgram(host_quad_prog);
    glUniform1f(quad_depth_loc, (float)zndc);
    glUniform4fv(quad_color_loc, 1, fg);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_DEPTH_TEST);
}

void host_render(cu_frame f)
{
    cu_error e;
    if (cu_render(host_ctx.r, &f, &e))
        fail_msg("cu_render: %s", e.msg);
}

void host_read(GLuint fbo, int is_float, float *px)
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

const float BLACK0[4] = {0, 0, 0, 0};

void host_coverage(float *alpha, double quad_dist, const float *view, const float *proj)
{
    static float px[N * 4];
    host_draw(fbo32, BLACK0, BLACK0, quad_dist, proj);
    cu_frame f = {.fbo = fbo32, .width = W, .height = H, .linear = 1, .clouds_only = 1, .view = view,
                  .projection = proj, .depth_texture = quad_dist > 0 ? depth_tex : 0};
    host_render(f);
    host_read(fbo32, 1, px);
    for (int i = 0; i < N; i++)
        alpha[i] = px[i * 4 + 3];
}
