/* tests/build/embed_example.c: a program outside the tree, built against an installed libcumulo through
 * `pkg-config --cflags --libs cumulo`: its own EGL surfaceless GLES 3 context and framebuffer, one frame of the scene
 * named on the command line and of the same view with a nearly transparent cloud, pixels read back and compared:
 * the sky is blue and the same in both, the cloud changes enough pixels. */
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES3/gl3.h>
#include <cumulo.h>
#include <stdio.h>
#include <stdlib.h>

#define W 160
#define H 120

static int die(const char *what)
{
    fprintf(stderr, "embed_example: %s\n", what);
    return 1;
}

int main(int argc, char **argv)
{
    if (argc != 2)
        return die("usage: embed_example SCENE");
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    if (!get_display)
        return die("no eglGetPlatformDisplayEXT");
    EGLDisplay dpy = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, NULL, NULL))
        return die("eglInitialize failed");
    const EGLint cfg_attr[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_ES3_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_NONE};
    EGLConfig cfg;
    EGLint n = 0;
    if (!eglBindAPI(EGL_OPENGL_ES_API) || !eglChooseConfig(dpy, cfg_attr, &cfg, 1, &n) || n < 1)
        return die("no GLES 3 config");
    const EGLint ctx_attr[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_NONE};
    EGLContext ctx = eglCreateContext(dpy, cfg, EGL_NO_CONTEXT, ctx_attr);
    if (ctx == EGL_NO_CONTEXT || !eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx))
        return die("no current GLES 3 context");

    GLuint fbo, rb;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glGenRenderbuffers(1, &rb);
    glBindRenderbuffer(GL_RENDERBUFFER, rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, W, H);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return die("framebuffer incomplete");

    cu_desc desc = {0}; /* GL through dlsym, the installed tables, no log */
    cu_scene *scene;
    cu_renderer *r;
    cu_error e;
    if (cu_scene_load(&scene, argv[1], &e) || cu_renderer_create(&r, &desc, &e) ||
        cu_renderer_set_scene(r, scene, &e))
        return die(e.msg);
    cu_frame f = {.fbo = fbo, .width = W, .height = H};
    if (cu_render(r, &f, &e))
        return die(e.msg);

    static unsigned char px[W * H * 4], thin[W * H * 4];
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, px);
    /* The same view with a nearly transparent cloud: the sky must not change, the cloud's pixels must. */
    if (cu_scene_set(scene, "cloud.density=1", &e) || cu_renderer_set_scene(r, scene, &e) || cu_render(r, &f, &e))
        return die(e.msg);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, thin);
    int sky_changed = 0, cloud_pixels = 0;
    for (int i = 0; i < W * H; i++) {
        int d = 0;
        for (int c = 0; c < 3; c++)
            d = abs(px[i * 4 + c] - thin[i * 4 + c]) > d ? abs(px[i * 4 + c] - thin[i * 4 + c]) : d;
        cloud_pixels += d > 8;
        sky_changed += i >= (H - 1) * W && d > 2; /* the top row is sky in cumulus.scene */
    }
    const unsigned char *top = px + (size_t)(H - 1) * W * 4;
    printf("embed_example: libcumulo %s, data %s, top-left sky %d %d %d, %d cloud pixels, %d sky pixels changed\n",
           cu_version(), cu_default_data_dir(), top[0], top[1], top[2], cloud_pixels, sky_changed);
    int ok = top[2] > top[0] && sky_changed == 0 && cloud_pixels > W * H / 200;
    cu_renderer_destroy(r);
    cu_scene_free(scene);
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, ctx);
    eglTerminate(dpy);
    return ok ? 0 : die("wrong picture: no blue sky above, the sky changed, or no cloud");
}
