/* examples/host_scene.c: a host renderer with cumulo's clouds in its picture. Its own EGL context and framebuffer
 * (colour + a depth texture), its own sky, a height-field terrain and a box drawn with depth, its own camera flying
 * a path that passes through the cloud; each frame cumulo draws the clouds only, cut by the host's depth and
 * composited over its colour, and the frame is written as a PNG.
 *
 *     cc host_scene.c -o host_scene $(pkg-config --cflags --libs cumulo egl glesv2) -lm
 *     ./host_scene /usr/share/cumulo/scenes/cumulus.scene out/ 8 320x240
 *
 * Prints one line per frame: the camera, cumulo's time for the frame and how many pixels the clouds changed. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES3/gl3.h>
#include <cumulo.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define GRID 96          /* terrain vertices per side */
#define EXTENT 6000.0f   /* terrain side, metres, centred on the origin */

static int die(const char *what, const char *detail)
{
    fprintf(stderr, "host_scene: %s%s%s\n", what, detail ? ": " : "", detail ? detail : "");
    return 1;
}

/* ---- the host's maths: column-major 4x4, OpenGL conventions ---- */
static void look_at(float m[16], const float eye[3], const float at[3])
{
    float f[3] = {at[0] - eye[0], at[1] - eye[1], at[2] - eye[2]};
    float l = sqrtf(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (int i = 0; i < 3; i++)
        f[i] /= l;
    float s[3] = {-f[2], 0, f[0]}; /* f x (0, 1, 0) */
    l = sqrtf(s[0] * s[0] + s[2] * s[2]);
    s[0] /= l;
    s[2] /= l;
    float u[3] = {s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2], s[0] * f[1] - s[1] * f[0]};
    float r[16] = {s[0], u[0], -f[0], 0, s[1], u[1], -f[1], 0, s[2], u[2], -f[2], 0,
                   -(s[0] * eye[0] + s[1] * eye[1] + s[2] * eye[2]), -(u[0] * eye[0] + u[1] * eye[1] + u[2] * eye[2]),
                   f[0] * eye[0] + f[1] * eye[1] + f[2] * eye[2], 1};
    memcpy(m, r, sizeof r);
}

static void perspective(float m[16], float fovy_deg, float aspect, float n, float f)
{
    float t = 1.0f / tanf(fovy_deg * 3.14159265f / 360.0f);
    float r[16] = {t / aspect, 0, 0, 0, 0, t, 0, 0, 0, 0, (f + n) / (n - f), -1, 0, 0, 2 * f * n / (n - f), 0};
    memcpy(m, r, sizeof r);
}

static void mul(float out[16], const float a[16], const float b[16])
{
    float r[16];
    for (int c = 0; c < 4; c++)
        for (int i = 0; i < 4; i++) {
            float s = 0;
            for (int k = 0; k < 4; k++)
                s += a[k * 4 + i] * b[c * 4 + k];
            r[c * 4 + i] = s;
        }
    memcpy(out, r, sizeof r);
}

/* Rolling hills, and one hill whose top reaches into the cloud of scenes/cumulus.scene, beside the flight path. */
static float height(float x, float z)
{
    float h = 40.0f * sinf(x * 0.0021f) * cosf(z * 0.0017f) + 25.0f * sinf(x * 0.0057f + z * 0.0043f);
    float d2 = ((x - 180.0f) * (x - 180.0f) + (z - 20.0f) * (z - 20.0f)) / (220.0f * 220.0f);
    return h + 250.0f * expf(-d2) + 20.0f;
}

/* ---- the host's drawing ---- */
static const char *VS = "#version 300 es\n"
                        "layout(location = 0) in vec3 a_pos;\nlayout(location = 1) in vec3 a_col;\n"
                        "uniform mat4 u_mvp;\nout vec3 v_col;\n"
                        "void main() { v_col = a_col; gl_Position = u_mvp * vec4(a_pos, 1.0); }\n";
static const char *FS = "#version 300 es\nprecision mediump float;\nin vec3 v_col;\nout vec4 o;\n"
                        "void main() { o = vec4(v_col, 1.0); }\n";
/* The host's own sky: a gradient by the view direction's height (the camera's inverse rotation and projection). */
static const char *SKY_VS = "#version 300 es\nout vec2 v_ndc;\nvoid main() {\n"
                            "  v_ndc = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);\n"
                            "  gl_Position = vec4(v_ndc, 1.0, 1.0);\n}\n";
static const char *SKY_FS = "#version 300 es\nprecision highp float;\nin vec2 v_ndc;\nuniform mat4 u_inv;\n"
                            "out vec4 o;\nvoid main() {\n  vec4 w = u_inv * vec4(v_ndc, 1.0, 1.0);\n"
                            "  float y = normalize(w.xyz / w.w).y;\n"
                            "  o = vec4(mix(vec3(0.75, 0.85, 0.95), vec3(0.25, 0.45, 0.85), clamp(y * 2.0, 0.0, 1.0)), 1.0);\n}\n";

static GLuint program(const char *vs, const char *fs)
{
    GLuint p = glCreateProgram();
    const char *src[2] = {vs, fs};
    GLenum type[2] = {GL_VERTEX_SHADER, GL_FRAGMENT_SHADER};
    for (int i = 0; i < 2; i++) {
        GLuint s = glCreateShader(type[i]);
        glShaderSource(s, 1, &src[i], NULL);
        glCompileShader(s);
        glAttachShader(p, s);
        glDeleteShader(s);
    }
    glLinkProgram(p);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    return ok ? p : 0;
}

typedef struct mesh {
    GLuint vao, vbo, ibo;
    int count;
} mesh;

static void mesh_upload(mesh *m, const float *v, int nv, const unsigned *idx, int ni)
{
    glGenVertexArrays(1, &m->vao);
    glBindVertexArray(m->vao);
    glGenBuffers(1, &m->vbo);
    glBindBuffer(GL_ARRAY_BUFFER, m->vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(float) * 6 * (size_t)nv), v, GL_STATIC_DRAW);
    glGenBuffers(1, &m->ibo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m->ibo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(sizeof(unsigned) * (size_t)ni), idx, GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 24, (void *)0);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 24, (void *)12);
    glBindVertexArray(0);
    m->count = ni;
}

/* The terrain, lit by the same sun as the clouds (Lambert, from cumulo's sun angles). */
static int terrain(mesh *m, const float sun[3])
{
    float *v = malloc(sizeof(float) * 6 * GRID * GRID);
    unsigned *idx = malloc(sizeof(unsigned) * 6 * (GRID - 1) * (GRID - 1));
    if (!v || !idx) {
        free(v);
        free(idx);
        return 1;
    }
    float step = EXTENT / (GRID - 1);
    for (int j = 0; j < GRID; j++)
        for (int i = 0; i < GRID; i++) {
            float x = -EXTENT / 2 + i * step, z = -EXTENT / 2 + j * step, y = height(x, z);
            float nx = height(x - 1, z) - height(x + 1, z), nz = height(x, z - 1) - height(x, z + 1), ny = 2.0f;
            float l = sqrtf(nx * nx + ny * ny + nz * nz);
            float lit = 0.5f + 0.5f * fmaxf(0.0f, (nx * sun[0] + ny * sun[1] + nz * sun[2]) / l);
            float rock = fminf(1.0f, fmaxf(0.0f, (y - 120.0f) / 100.0f));
            float *p = v + 6 * (j * GRID + i);
            p[0] = x; p[1] = y; p[2] = z;
            p[3] = lit * (0.25f + 0.25f * rock); p[4] = lit * (0.45f - 0.05f * rock); p[5] = lit * (0.18f + 0.2f * rock);
        }
    int n = 0;
    for (int j = 0; j + 1 < GRID; j++)
        for (int i = 0; i + 1 < GRID; i++) {
            unsigned a = (unsigned)(j * GRID + i), b = a + 1, c = a + GRID, d = c + 1;
            unsigned q[6] = {a, c, b, b, c, d};
            memcpy(idx + n, q, sizeof q);
            n += 6;
        }
    mesh_upload(m, v, GRID * GRID, idx, n);
    free(v);
    free(idx);
    return 0;
}

/* A hangar-sized box beside the path, in front of the cloud for most of the flight. */
static void box(mesh *m)
{
    float x0 = -260, x1 = -140, z0 = -700, z1 = -620, y0 = height(-200, -660) - 5, y1 = y0 + 60;
    float v[8 * 6];
    for (int k = 0; k < 8; k++) {
        float *p = v + 6 * k;
        p[0] = k & 1 ? x1 : x0; p[1] = k & 2 ? y1 : y0; p[2] = k & 4 ? z1 : z0;
        float shade = 0.5f + 0.1f * (float)(k & 3);
        p[3] = 0.8f * shade; p[4] = 0.2f * shade; p[5] = 0.15f * shade;
    }
    unsigned idx[36] = {0, 1, 3, 0, 3, 2, 4, 6, 7, 4, 7, 5, 0, 4, 5, 0, 5, 1,
                        2, 3, 7, 2, 7, 6, 0, 2, 6, 0, 6, 4, 1, 5, 7, 1, 7, 3};
    mesh_upload(m, v, 8, idx, 36);
}

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

int main(int argc, char **argv)
{
    int frames = 8, w = 320, h = 240;
    if (argc < 3 || argc > 5 || (argc > 3 && sscanf(argv[3], "%d", &frames) != 1) ||
        (argc > 4 && sscanf(argv[4], "%dx%d", &w, &h) != 2) || frames < 2 || frames > 10000 || w < 16 || h < 16 ||
        w > 4096 || h > 4096)
        return die("usage: host_scene SCENE OUTDIR [FRAMES >= 2] [WxH]", NULL);
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    EGLDisplay dpy = get_display ? get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL)
                                 : eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, NULL, NULL))
        return die("eglInitialize failed", NULL);
    const EGLint cfg_attr[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_ES3_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_NONE};
    EGLConfig cfg;
    EGLint n = 0;
    if (!eglBindAPI(EGL_OPENGL_ES_API) || !eglChooseConfig(dpy, cfg_attr, &cfg, 1, &n) || n < 1)
        return die("no GLES 3 config", NULL);
    const EGLint ctx_attr[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_NONE};
    EGLContext ctx = eglCreateContext(dpy, cfg, EGL_NO_CONTEXT, ctx_attr);
    if (ctx == EGL_NO_CONTEXT || !eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx))
        return die("no current GLES 3 context (surfaceless)", NULL);

    /* The host's framebuffer: colour and a depth texture, the one cumulo reads. */
    GLuint fbo, color, depth;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glGenRenderbuffers(1, &color);
    glBindRenderbuffer(GL_RENDERBUFFER, color);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color);
    glGenTextures(1, &depth);
    glBindTexture(GL_TEXTURE_2D, depth);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, w, h, 0, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, NULL);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth, 0);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return die("framebuffer incomplete", NULL);

    cu_desc desc = {0}; /* GL through dlsym, the installed tables (or $CUMULO_DATA_DIR), no log */
    cu_scene *scene;
    cu_renderer *r;
    cu_error e;
    if (cu_scene_load(&scene, argv[1], &e) || cu_renderer_create(&r, &desc, &e) ||
        cu_renderer_set_scene(r, scene, &e))
        return die(e.msg, NULL);
    double el, az;
    cu_renderer_get_sun(r, &el, &az);
    el *= 3.14159265 / 180;
    az *= 3.14159265 / 180;
    float sun[3] = {(float)(cos(el) * sin(az)), (float)sin(el), (float)(-cos(el) * cos(az))};

    GLuint prog = program(VS, FS), sky = program(SKY_VS, SKY_FS);
    if (!prog || !sky)
        return die("host shaders did not build", NULL);
    mesh ground, hangar;
    if (terrain(&ground, sun))
        return die("out of memory", NULL);
    box(&hangar);
    GLint mvp_loc = glGetUniformLocation(prog, "u_mvp"), inv_loc = glGetUniformLocation(sky, "u_inv");
    GLuint empty_vao;
    glGenVertexArrays(1, &empty_vao);

    unsigned char *px = malloc((size_t)w * h * 4 * 2);
    if (!px)
        return die("out of memory", NULL);
    unsigned char *before = px + (size_t)w * h * 4;
    float proj[16], view[16], vp[16];
    perspective(proj, 60.0f, (float)w / h, 0.5f, 50000.0f);
    for (int k = 0; k < frames; k++) {
        /* The flight: from 1.4 km south of the cloud, level at 300 m, through its middle, and out the far side. */
        float s = (float)k / (frames - 1);
        float eye[3] = {20.0f, 300.0f, -1400.0f + 2400.0f * s};
        float at[3] = {eye[0] - 60.0f * s, eye[1] - 40.0f, eye[2] + 500.0f};
        look_at(view, eye, at);
        mul(vp, proj, view);

        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glViewport(0, 0, w, h);
        glDisable(GL_DEPTH_TEST);
        glUseProgram(sky);
        float rot[16], inv_rot[16];
        memcpy(rot, view, sizeof rot);
        rot[12] = rot[13] = rot[14] = 0;
        /* the inverse of P R: R^T P^-1, with P^-1 of a symmetric frustum written out */
        float pinv[16] = {1 / proj[0], 0, 0, 0, 0, 1 / proj[5], 0, 0, 0, 0, 0, 1 / proj[14], 0, 0, -1, proj[10] / proj[14]};
        float rt[16] = {rot[0], rot[4], rot[8], 0, rot[1], rot[5], rot[9], 0, rot[2], rot[6], rot[10], 0, 0, 0, 0, 1};
        mul(inv_rot, rt, pinv);
        glUniformMatrix4fv(inv_loc, 1, GL_FALSE, inv_rot);
        glBindVertexArray(empty_vao);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glClear(GL_DEPTH_BUFFER_BIT);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glUseProgram(prog);
        glUniformMatrix4fv(mvp_loc, 1, GL_FALSE, vp);
        glBindVertexArray(ground.vao);
        glDrawElements(GL_TRIANGLES, ground.count, GL_UNSIGNED_INT, 0);
        glBindVertexArray(hangar.vao);
        glDrawElements(GL_TRIANGLES, hangar.count, GL_UNSIGNED_INT, 0);
        glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, before);

        /* cumulo: the same camera, the clouds only, cut by this framebuffer's own depth attachment. */
        cu_frame f = {.fbo = fbo, .width = w, .height = h, .view = view, .projection = proj, .depth_texture = depth,
                      .clouds_only = 1};
        double t0 = now_ms();
        if (cu_render(r, &f, &e))
            return die(e.msg, NULL);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, px); /* also waits for the frame */
        double ms = now_ms() - t0;
        long changed = 0;
        for (long i = 0; i < (long)w * h; i++)
            changed += memcmp(px + 4 * i, before + 4 * i, 4) != 0;
        /* PNG rows top first; GL's first row is the bottom one. */
        for (int y = 0; y < h / 2; y++)
            for (int x = 0; x < w * 4; x++) {
                unsigned char t = px[(size_t)y * w * 4 + x];
                px[(size_t)y * w * 4 + x] = px[(size_t)(h - 1 - y) * w * 4 + x];
                px[(size_t)(h - 1 - y) * w * 4 + x] = t;
            }
        char path[4096];
        snprintf(path, sizeof path, "%s/frame_%03d.png", argv[2], k);
        if (cu_write_png(path, px, w, h, &e))
            return die(e.msg, NULL);
        printf("frame %d: eye %.0f %.0f %.0f, cumulo %.1f ms, clouds changed %ld of %ld pixels, %s\n", k, eye[0],
               eye[1], eye[2], ms, changed, (long)w * h, path);
    }
    free(px);
    cu_renderer_destroy(r);
    cu_scene_free(scene);
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, ctx);
    eglTerminate(dpy);
    return 0;
}
