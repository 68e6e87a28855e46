/* platform/display/egl_common.c: EGL display/config/context/surface set-up shared by the DRM, X11 and Wayland back
 * ends. */
#include "egl_common.h"
#include <GLES3/gl3.h>
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef EGL_OPENGL_ES3_BIT
#define EGL_OPENGL_ES3_BIT 0x00000040 /* EGL_OPENGL_ES3_BIT_KHR: same value, in EGL 1.5 core */
#endif

const char *cu_egl_error(void)
{
    static const char *names[] = {"EGL_SUCCESS", "EGL_NOT_INITIALIZED", "EGL_BAD_ACCESS", "EGL_BAD_ALLOC",
                                  "EGL_BAD_ATTRIBUTE", "EGL_BAD_CONFIG", "EGL_BAD_CONTEXT", "EGL_BAD_CURRENT_SURFACE",
                                  "EGL_BAD_DISPLAY", "EGL_BAD_MATCH", "EGL_BAD_NATIVE_PIXMAP",
                                  "EGL_BAD_NATIVE_WINDOW", "EGL_BAD_PARAMETER", "EGL_BAD_SURFACE",
                                  "EGL_CONTEXT_LOST"};
    EGLint e = eglGetError();
    if (e >= EGL_SUCCESS && e <= EGL_CONTEXT_LOST)
        return names[e - EGL_SUCCESS];
    return "unknown EGL error";
}

void *cu_egl_proc(const char *name)
{
    /* ISO C has no cast from a function pointer to void *: copy the bits. */
    __eglMustCastToProperFunctionPointerType f = eglGetProcAddress(name);
    void *p = NULL;
    memcpy(&p, &f, sizeof p);
    if (p)
        return p;
    /* EGL before 1.5 without EGL_KHR_get_all_proc_addresses returns only extension functions. */
    static void *gles;
    if (!gles)
        gles = dlopen("libGLESv2.so.2", RTLD_LAZY | RTLD_LOCAL);
    return gles ? dlsym(gles, name) : NULL;
}

static int has_ext(const char *list, const char *ext)
{
    size_t n = strlen(ext);
    for (const char *p = list; p && (p = strstr(p, ext)); p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0'))
            return 1;
    return 0;
}

static int count_configs(EGLDisplay dpy, EGLint renderable)
{
    EGLint attr[] = { EGL_SURFACE_TYPE, EGL_WINDOW_BIT, EGL_RENDERABLE_TYPE, renderable, EGL_NONE };
    EGLint n = 0;
    if (!eglChooseConfig(dpy, attr, NULL, 0, &n))
        return 0;
    return n;
}

/* What a GLES-2-only device offers, for the error message: GL_VERSION of a GLES 2 context if one can be made. */
static void gles2_version(EGLDisplay dpy, char *buf, size_t len)
{
    snprintf(buf, len, "OpenGL ES 2 only");
    EGLint attr[] = { EGL_RENDERABLE_TYPE, EGL_OPENGL_ES2_BIT, EGL_NONE };
    EGLConfig cfg;
    EGLint n = 0;
    if (!eglChooseConfig(dpy, attr, &cfg, 1, &n) || n < 1)
        return;
    EGLint cattr[] = { EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE };
    EGLContext ctx = eglCreateContext(dpy, cfg, EGL_NO_CONTEXT, cattr);
    if (ctx == EGL_NO_CONTEXT)
        return;
    /* Without a surface this needs EGL_KHR_surfaceless_context; if it is missing the generic text stays. */
    if (eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
        const GLubyte *(*get_string)(GLenum) = NULL;
        void *p = cu_egl_proc("glGetString");
        memcpy(&get_string, &p, sizeof p);
        const GLubyte *v = get_string ? get_string(GL_VERSION) : NULL;
        const GLubyte *r = get_string ? get_string(GL_RENDERER) : NULL;
        if (v)
            snprintf(buf, len, "'%s' on '%s'", (const char *)v, r ? (const char *)r : "?");
        eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }
    eglDestroyContext(dpy, ctx);
}

static EGLDisplay platform_display(EGLenum platform, void *native)
{
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (client && has_ext(client, "EGL_EXT_platform_base")) {
        PFNEGLGETPLATFORMDISPLAYEXTPROC get =
            (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
        if (get)
            return get(platform, native, NULL);
    }
    /* Old EGL: the native display's type tells Mesa which platform it is. */
    return eglGetDisplay((EGLNativeDisplayType)native);
}

#ifdef __SANITIZE_ADDRESS__
/* Sanitizer builds only (make sanitize): keeps Mesa's DRI driver mapped after eglTerminate. The driver keeps a few
 * allocations past its unload (112 bytes, the same every run); once it is unmapped LeakSanitizer reports them from an
 * "<unknown module>" that no suppression can name. Pinned, they are reported from swrast_dri.so, which
 * tests/sanitize/lsan.supp suppresses, and a leak of ours still shows. */
void cu_egl_keep_driver(void)
{
    FILE *maps = fopen("/proc/self/maps", "r");
    char line[4096];
    while (maps && fgets(line, sizeof line, maps)) {
        char *path = strchr(line, '/');
        if (!path || !strstr(path, "/dri/"))
            continue;
        path[strcspn(path, "\n")] = 0;
        void *h = dlopen(path, RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE); /* NOLOAD: only what is loaded already */
        if (h)
            dlclose(h);
    }
    if (maps)
        fclose(maps);
}
#else
void cu_egl_keep_driver(void)
{
}
#endif

int cu_egl_init(cu_egl *e, EGLenum platform, void *native_display, EGLint visual_id, const char *who,
                char *err, size_t errlen)
{
    e->dpy = EGL_NO_DISPLAY;
    e->ctx = EGL_NO_CONTEXT;
    e->surf = EGL_NO_SURFACE;
    e->dpy = platform_display(platform, native_display);
    if (e->dpy == EGL_NO_DISPLAY || !eglInitialize(e->dpy, &e->major, &e->minor)) {
        snprintf(err, errlen, "%s: eglInitialize failed (%s): is Mesa's EGL installed (libegl-mesa0) and the "
                 "GPU driver loaded?", who, cu_egl_error());
        e->dpy = EGL_NO_DISPLAY;
        return 1;
    }
    cu_egl_keep_driver();
    if (!eglBindAPI(EGL_OPENGL_ES_API)) {
        snprintf(err, errlen, "%s: this EGL has no OpenGL ES (%s)", who, cu_egl_error());
        return 1;
    }
    /* GLES 3 asked for by name: EGL_OPENGL_ES3_BIT in the config, major version 3 in the context. Depth is
     * needed by the camera depth pre-pass when drawing to the window's own framebuffer. */
    static const EGLint depths[] = { 24, 16 };
    EGLConfig configs[256];
    EGLint n = 0, candidates = 0;
    int found = 0;
    for (int k = 0; k < 2 && !found; k++) {
        EGLint attr[] = { EGL_SURFACE_TYPE, EGL_WINDOW_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_ES3_BIT,
                          EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_DEPTH_SIZE, depths[k],
                          EGL_NONE };
        if (!eglChooseConfig(e->dpy, attr, configs, 256, &n))
            n = 0;
        candidates += n;
        /* Scan-out needs the config's pixel format to equal the GBM surface's (kmscube's match_config_to_visual);
         * windows take the first (best) config. */
        for (EGLint i = 0; i < n && !found; i++) {
            EGLint id = 0;
            if (!visual_id || (eglGetConfigAttrib(e->dpy, configs[i], EGL_NATIVE_VISUAL_ID, &id) && id == visual_id)) {
                e->cfg = configs[i];
                found = 1;
            }
        }
    }
    if (!found && candidates > 0) {
        snprintf(err, errlen, "%s: no GLES 3 config matches the scan-out format 0x%08x (%d candidates)", who,
                 (unsigned)visual_id, (int)candidates);
        return 1;
    }
    if (!found) {
        int es2 = count_configs(e->dpy, EGL_OPENGL_ES2_BIT);
        int es3 = count_configs(e->dpy, EGL_OPENGL_ES3_BIT);
        if (es2 > 0 && es3 == 0) {
            char offers[200];
            gles2_version(e->dpy, offers, sizeof offers);
            snprintf(err, errlen, "%s: the GPU offers only OpenGL ES 2 (%s; %d window configs with "
                     "EGL_OPENGL_ES2_BIT, none with EGL_OPENGL_ES3_BIT, EGL %d.%d '%s'): cumulo needs OpenGL ES 3.0 "
                     "(Raspberry Pi 4 or newer; the VideoCore IV of a Pi 0-3 has OpenGL ES 2 only)", who, offers,
                     es2, e->major, e->minor, eglQueryString(e->dpy, EGL_VENDOR));
        } else {
            snprintf(err, errlen, "%s: no EGL window config with 8-bit RGB and a depth buffer that renders OpenGL "
                     "ES 3 (%d ES 3 configs in all, EGL %d.%d '%s')", who, es3, e->major, e->minor,
                     eglQueryString(e->dpy, EGL_VENDOR));
        }
        return 1;
    }
    const char *ext = eglQueryString(e->dpy, EGL_EXTENSIONS);
    int create_context = (e->major > 1 || e->minor >= 5) || has_ext(ext, "EGL_KHR_create_context");
    EGLint cattr[] = { EGL_CONTEXT_MAJOR_VERSION, 3, create_context ? EGL_CONTEXT_MINOR_VERSION : EGL_NONE, 0,
                       EGL_NONE };
    e->ctx = eglCreateContext(e->dpy, e->cfg, EGL_NO_CONTEXT, cattr);
    if (e->ctx == EGL_NO_CONTEXT) {
        char offers[200];
        const char *why = cu_egl_error();
        gles2_version(e->dpy, offers, sizeof offers);
        snprintf(err, errlen, "%s: creating an OpenGL ES 3.0 context failed (%s); the device offers %s: cumulo "
                 "needs OpenGL ES 3.0", who, why, offers);
        return 1;
    }
    return 0;
}

int cu_egl_make_current(cu_egl *e, void *native_window, const char *who, char *err, size_t errlen)
{
    PFNEGLCREATEPLATFORMWINDOWSURFACEEXTPROC create =
        (PFNEGLCREATEPLATFORMWINDOWSURFACEEXTPROC)eglGetProcAddress("eglCreatePlatformWindowSurfaceEXT");
    if (!create) {
        snprintf(err, errlen, "%s: EGL lacks EGL_EXT_platform_base (eglCreatePlatformWindowSurfaceEXT): update "
                 "Mesa", who);
        return 1;
    }
    e->surf = create(e->dpy, e->cfg, native_window, NULL);
    if (e->surf == EGL_NO_SURFACE) {
        snprintf(err, errlen, "%s: eglCreatePlatformWindowSurfaceEXT failed (%s)", who, cu_egl_error());
        return 1;
    }
    if (!eglMakeCurrent(e->dpy, e->surf, e->surf, e->ctx)) {
        snprintf(err, errlen, "%s: eglMakeCurrent failed (%s)", who, cu_egl_error());
        return 1;
    }
    const GLubyte *(*get_string)(GLenum) = NULL;
    void *p = cu_egl_proc("glGetString");
    memcpy(&get_string, &p, sizeof p);
    const char *v = get_string ? (const char *)get_string(GL_VERSION) : NULL;
    int major = 0;
    if (!v || sscanf(v, "OpenGL ES %d", &major) != 1 || major < 3) {
        snprintf(err, errlen, "%s: asked for OpenGL ES 3.0 but the context says '%s': cumulo needs OpenGL ES 3.0",
                 who, v ? v : "(no GL_VERSION)");
        return 1;
    }
    return 0;
}

void cu_egl_describe(const cu_egl *e, char *buf, size_t len)
{
    EGLint id = 0, bs = 0, r = 0, g = 0, b = 0, a = 0, d = 0, s = 0, ms = 0;
    eglGetConfigAttrib(e->dpy, e->cfg, EGL_CONFIG_ID, &id);
    eglGetConfigAttrib(e->dpy, e->cfg, EGL_BUFFER_SIZE, &bs);
    eglGetConfigAttrib(e->dpy, e->cfg, EGL_RED_SIZE, &r);
    eglGetConfigAttrib(e->dpy, e->cfg, EGL_GREEN_SIZE, &g);
    eglGetConfigAttrib(e->dpy, e->cfg, EGL_BLUE_SIZE, &b);
    eglGetConfigAttrib(e->dpy, e->cfg, EGL_ALPHA_SIZE, &a);
    eglGetConfigAttrib(e->dpy, e->cfg, EGL_DEPTH_SIZE, &d);
    eglGetConfigAttrib(e->dpy, e->cfg, EGL_STENCIL_SIZE, &s);
    eglGetConfigAttrib(e->dpy, e->cfg, EGL_SAMPLES, &ms);
    const char *vendor = eglQueryString(e->dpy, EGL_VENDOR);
    snprintf(buf, len, "EGL %d.%d (%s) config 0x%x: buf=%d r=%d g=%d b=%d a=%d depth=%d stencil=%d samples=%d",
             e->major, e->minor, vendor ? vendor : "?", id, bs, r, g, b, a, d, s, ms);
}

void cu_egl_terminate(cu_egl *e)
{
    if (e->dpy == EGL_NO_DISPLAY)
        return;
    eglMakeCurrent(e->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (e->surf != EGL_NO_SURFACE)
        eglDestroySurface(e->dpy, e->surf);
    if (e->ctx != EGL_NO_CONTEXT)
        eglDestroyContext(e->dpy, e->ctx);
    eglTerminate(e->dpy);
    e->dpy = EGL_NO_DISPLAY;
    e->surf = EGL_NO_SURFACE;
    e->ctx = EGL_NO_CONTEXT;
}
