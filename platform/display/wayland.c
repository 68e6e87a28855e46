/* platform/display/wayland.c: a desktop window on Wayland (xdg-shell) through EGL (GLES 3), windowed or full screen. */
#include "display.h"
#include "egl_common.h"
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <wayland-client.h>
#include <wayland-egl.h>
#include "xdg-shell-client-protocol.h" /* generated into $(B)/gen by platform/devices.mk */
#include "xdg-shell-protocol.inc"      /* the interface tables, compiled into this file only */

struct cu_display {
    struct wl_display *wl;
    struct wl_registry *reg;
    struct wl_compositor *comp;
    struct xdg_wm_base *wm;
    struct wl_surface *surf;
    struct xdg_surface *xsurf;
    struct xdg_toplevel *top;
    struct wl_egl_window *ewin;
    int w, h, pending_w, pending_h, configured, closed, fullscreen;
    cu_egl egl;
};

static void reg_global(void *data, struct wl_registry *reg, uint32_t name, const char *iface, uint32_t version)
{
    cu_display *d = data;
    (void)version;
    if (!strcmp(iface, wl_compositor_interface.name))
        d->comp = wl_registry_bind(reg, name, &wl_compositor_interface, 1);
    else if (!strcmp(iface, xdg_wm_base_interface.name))
        d->wm = wl_registry_bind(reg, name, &xdg_wm_base_interface, 1);
}

static void reg_remove(void *data, struct wl_registry *reg, uint32_t name)
{
    (void)data; (void)reg; (void)name;
}

static const struct wl_registry_listener reg_listener = { .global = reg_global, .global_remove = reg_remove };

static void wm_ping(void *data, struct xdg_wm_base *wm, uint32_t serial)
{
    (void)data;
    xdg_wm_base_pong(wm, serial);
}

static const struct xdg_wm_base_listener wm_listener = { .ping = wm_ping };

static void xsurf_configure(void *data, struct xdg_surface *xs, uint32_t serial)
{
    cu_display *d = data;
    xdg_surface_ack_configure(xs, serial);
    d->configured = 1;
}

static const struct xdg_surface_listener xsurf_listener = { .configure = xsurf_configure };

static void top_configure(void *data, struct xdg_toplevel *t, int32_t w, int32_t h, struct wl_array *states)
{
    cu_display *d = data;
    (void)t; (void)states;
    if (w > 0 && h > 0) { /* 0 means "your choice" */
        d->pending_w = w;
        d->pending_h = h;
    }
}

static void top_close(void *data, struct xdg_toplevel *t)
{
    (void)t;
    ((cu_display *)data)->closed = 1;
}

static const struct xdg_toplevel_listener top_listener = { .configure = top_configure, .close = top_close };

static void wl_close(cu_display *d)
{
    if (!d)
        return;
    cu_egl_terminate(&d->egl);
    if (d->ewin) wl_egl_window_destroy(d->ewin);
    if (d->top) xdg_toplevel_destroy(d->top);
    if (d->xsurf) xdg_surface_destroy(d->xsurf);
    if (d->surf) wl_surface_destroy(d->surf);
    if (d->wm) xdg_wm_base_destroy(d->wm);
    if (d->comp) wl_compositor_destroy(d->comp);
    if (d->reg) wl_registry_destroy(d->reg);
    if (d->wl) wl_display_disconnect(d->wl);
    free(d);
}

static int wl_open(cu_display **out, const cu_display_opts *o, char *err, size_t errlen)
{
    *out = NULL;
    cu_display *d = calloc(1, sizeof *d);
    if (!d) {
        snprintf(err, errlen, "wayland: out of memory");
        return 1;
    }
    d->egl.dpy = EGL_NO_DISPLAY;
    /* Without XDG_RUNTIME_DIR libwayland prints its own complaint; there is no compositor to find anyway. */
    int no_session = !getenv("WAYLAND_SOCKET") && !getenv("XDG_RUNTIME_DIR");
    d->wl = no_session ? NULL : wl_display_connect(NULL);
    if (!d->wl) {
        const char *env = getenv("WAYLAND_DISPLAY");
        snprintf(err, errlen, "wayland: cannot connect to a compositor (WAYLAND_DISPLAY=%s): run inside a Wayland "
                 "session, or use --platform x11|drm|headless", env ? env : "unset");
        free(d);
        return 1;
    }
    d->reg = wl_display_get_registry(d->wl);
    wl_registry_add_listener(d->reg, &reg_listener, d);
    wl_display_roundtrip(d->wl);
    if (!d->comp || !d->wm) {
        snprintf(err, errlen, "wayland: the compositor lacks %s: it cannot show an xdg-shell window",
                 !d->comp ? "wl_compositor" : "xdg_wm_base");
        goto fail;
    }
    xdg_wm_base_add_listener(d->wm, &wm_listener, d);
    d->w = o->width > 0 ? o->width : 640;
    d->h = o->height > 0 ? o->height : 480;
    d->fullscreen = o->fullscreen;
    d->surf = wl_compositor_create_surface(d->comp);
    d->xsurf = xdg_wm_base_get_xdg_surface(d->wm, d->surf);
    xdg_surface_add_listener(d->xsurf, &xsurf_listener, d);
    d->top = xdg_surface_get_toplevel(d->xsurf);
    xdg_toplevel_add_listener(d->top, &top_listener, d);
    xdg_toplevel_set_title(d->top, "cumulo");
    xdg_toplevel_set_app_id(d->top, "cumulo");
    if (d->fullscreen)
        xdg_toplevel_set_fullscreen(d->top, NULL);
    wl_surface_commit(d->surf);
    /* xdg-shell: no buffer may be attached before the first configure has been acknowledged. */
    while (!d->configured)
        if (wl_display_dispatch(d->wl) < 0) {
            snprintf(err, errlen, "wayland: lost the compositor while waiting for the window");
            goto fail;
        }
    if (d->pending_w) {
        d->w = d->pending_w;
        d->h = d->pending_h;
    }
    d->ewin = wl_egl_window_create(d->surf, d->w, d->h);
    if (!d->ewin) {
        snprintf(err, errlen, "wayland: wl_egl_window_create failed");
        goto fail;
    }
    if (cu_egl_init(&d->egl, EGL_PLATFORM_WAYLAND_KHR, d->wl, 0, "wayland", err, errlen) ||
        cu_egl_make_current(&d->egl, d->ewin, "wayland", err, errlen))
        goto fail;
    eglSwapInterval(d->egl.dpy, 1);
    *out = d;
    return 0;
fail:
    wl_close(d);
    return 1;
}

static int wl_present(cu_display *d, char *err, size_t errlen)
{
    if (!eglSwapBuffers(d->egl.dpy, d->egl.surf)) {
        snprintf(err, errlen, "wayland: eglSwapBuffers failed (%s)", cu_egl_error());
        return 1;
    }
    if (wl_display_dispatch_pending(d->wl) < 0) {
        snprintf(err, errlen, "wayland: lost the connection to the compositor");
        return 1;
    }
    if (d->closed) {
        snprintf(err, errlen, "wayland: window closed");
        return -1; /* the user closed the window: a normal end */
    }
    if (d->pending_w && (d->pending_w != d->w || d->pending_h != d->h)) {
        d->w = d->pending_w;
        d->h = d->pending_h;
        wl_egl_window_resize(d->ewin, d->w, d->h, 0, 0);
    }
    return 0;
}

static void *wl_proc(cu_display *d, const char *name)
{
    (void)d;
    return cu_egl_proc(name);
}

static void wl_frame(cu_display *d, unsigned *fbo, int *w, int *h)
{
    *fbo = 0;
    *w = d->w;
    *h = d->h;
}

static void wl_describe(cu_display *d, char *buf, size_t len)
{
    char egl[200];
    cu_egl_describe(&d->egl, egl, sizeof egl);
    snprintf(buf, len, "%s; %dx%d %s on Wayland", egl, d->w, d->h, d->fullscreen ? "fullscreen" : "window");
}

const cu_display_backend cu_display_wayland = {
    .name = "wayland",
    .open = wl_open,
    .get_proc_address = wl_proc,
    .frame = wl_frame,
    .present = wl_present,
    .describe = wl_describe,
    .close = wl_close,
};
