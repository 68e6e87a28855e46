/* platform/display/x11.c: a desktop window on X11 through EGL (GLES 3), windowed or full screen (EWMH), vsync on. */
#include "display.h"
#include "egl_common.h"
#include <X11/Xatom.h>
#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <X11/keysym.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct cu_display {
    Display *x;
    Window win;
    Colormap cmap;
    Atom wm_delete;
    int w, h, fullscreen;
    cu_egl egl;
};

static void x11_close(cu_display *d)
{
    if (!d)
        return;
    cu_egl_terminate(&d->egl);
    if (d->x) {
        if (d->win)
            XDestroyWindow(d->x, d->win);
        if (d->cmap)
            XFreeColormap(d->x, d->cmap);
        XCloseDisplay(d->x);
    }
    free(d);
}

static int x11_open(cu_display **out, const cu_display_opts *o, char *err, size_t errlen)
{
    *out = NULL;
    cu_display *d = calloc(1, sizeof *d);
    if (!d) {
        snprintf(err, errlen, "x11: out of memory");
        return 1;
    }
    d->egl.dpy = EGL_NO_DISPLAY;
    d->x = XOpenDisplay(NULL);
    if (!d->x) {
        const char *env = getenv("DISPLAY");
        snprintf(err, errlen, "x11: cannot open display '%s': run inside an X session (or set DISPLAY), or use "
                 "--platform drm|wayland|headless", env ? env : "(DISPLAY unset)");
        free(d);
        return 1;
    }
    if (cu_egl_init(&d->egl, EGL_PLATFORM_X11_KHR, d->x, 0, "x11", err, errlen))
        goto fail;
    /* The window must use the visual of the EGL config, or the surface cannot be created on some servers. */
    EGLint vid = 0;
    eglGetConfigAttrib(d->egl.dpy, d->egl.cfg, EGL_NATIVE_VISUAL_ID, &vid);
    XVisualInfo tmpl = { .visualid = (VisualID)vid };
    int nvi = 0;
    XVisualInfo *vi = XGetVisualInfo(d->x, VisualIDMask, &tmpl, &nvi);
    if (!vi) {
        snprintf(err, errlen, "x11: the EGL config's visual 0x%x is not on this X server", (unsigned)vid);
        goto fail;
    }
    int screen = DefaultScreen(d->x);
    Window root = RootWindow(d->x, screen);
    d->w = o->width > 0 ? o->width : 640;
    d->h = o->height > 0 ? o->height : 480;
    d->fullscreen = o->fullscreen;
    if (d->fullscreen) {
        d->w = DisplayWidth(d->x, screen);
        d->h = DisplayHeight(d->x, screen);
    }
    d->cmap = XCreateColormap(d->x, root, vi->visual, AllocNone);
    XSetWindowAttributes wa = { .colormap = d->cmap, .border_pixel = 0,
                                .event_mask = StructureNotifyMask | KeyPressMask };
    d->win = XCreateWindow(d->x, root, 0, 0, (unsigned)d->w, (unsigned)d->h, 0, vi->depth, InputOutput, vi->visual,
                           CWColormap | CWBorderPixel | CWEventMask, &wa);
    XFree(vi);
    XStoreName(d->x, d->win, "cumulo");
    d->wm_delete = XInternAtom(d->x, "WM_DELETE_WINDOW", False);
    XSetWMProtocols(d->x, d->win, &d->wm_delete, 1);
    if (d->fullscreen) {
        /* EWMH: set the state before mapping, the window manager honours it when it maps the window. */
        Atom state = XInternAtom(d->x, "_NET_WM_STATE", False);
        Atom fs = XInternAtom(d->x, "_NET_WM_STATE_FULLSCREEN", False);
        XChangeProperty(d->x, d->win, state, XA_ATOM, 32, PropModeReplace, (unsigned char *)&fs, 1);
    }
    XMapWindow(d->x, d->win);
    if (cu_egl_make_current(&d->egl, &d->win, "x11", err, errlen))
        goto fail;
    eglSwapInterval(d->egl.dpy, 1); /* vsync, as on the kiosk */
    *out = d;
    return 0;
fail:
    x11_close(d);
    return 1;
}

static int x11_present(cu_display *d, char *err, size_t errlen)
{
    if (!eglSwapBuffers(d->egl.dpy, d->egl.surf)) {
        snprintf(err, errlen, "x11: eglSwapBuffers failed (%s)", cu_egl_error());
        return 1;
    }
    while (XPending(d->x)) {
        XEvent ev;
        XNextEvent(d->x, &ev);
        if (ev.type == ConfigureNotify) {
            d->w = ev.xconfigure.width;
            d->h = ev.xconfigure.height;
        } else if ((ev.type == ClientMessage && (Atom)ev.xclient.data.l[0] == d->wm_delete) ||
                   (ev.type == KeyPress && (XLookupKeysym(&ev.xkey, 0) == XK_Escape ||
                                            XLookupKeysym(&ev.xkey, 0) == XK_q))) {
            /* Negative: the user closed the window, a normal end rather than an error. */
            snprintf(err, errlen, "x11: window closed");
            return -1;
        }
    }
    return 0;
}

static void *x11_proc(cu_display *d, const char *name)
{
    (void)d;
    return cu_egl_proc(name);
}

static void x11_frame(cu_display *d, unsigned *fbo, int *w, int *h)
{
    *fbo = 0;
    *w = d->w;
    *h = d->h;
}

static void x11_describe(cu_display *d, char *buf, size_t len)
{
    char egl[200];
    cu_egl_describe(&d->egl, egl, sizeof egl);
    snprintf(buf, len, "%s; %dx%d %s on X11 '%s'", egl, d->w, d->h, d->fullscreen ? "fullscreen" : "window",
             DisplayString(d->x));
}

const cu_display_backend cu_display_x11 = {
    .name = "x11",
    .open = x11_open,
    .get_proc_address = x11_proc,
    .frame = x11_frame,
    .present = x11_present,
    .describe = x11_describe,
    .close = x11_close,
};
