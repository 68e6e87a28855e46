/* platform/display/drm.c: full-screen back end on DRM/KMS + GBM + EGL (kmscube-style): flips pages on vsync through
 * atomic modesetting where the driver has it and the legacy API otherwise, and puts the previous CRTC back on close.
 * The device and output are chosen by drm_probe.c. */
#include "drm_priv.h"
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <gbm.h>
#include <poll.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <xf86drm.h>
#include <xf86drmMode.h>
#include <drm_fourcc.h>


static uint32_t prop_id(int fd, uint32_t obj, uint32_t type, const char *name)
{
    drmModeObjectProperties *props = drmModeObjectGetProperties(fd, obj, type);
    uint32_t id = 0;
    for (uint32_t i = 0; props && i < props->count_props && !id; i++) {
        drmModePropertyRes *p = drmModeGetProperty(fd, props->props[i]);
        if (p && !strcmp(p->name, name))
            id = p->prop_id;
        drmModeFreeProperty(p);
    }
    drmModeFreeObjectProperties(props);
    return id;
}

static uint64_t prop_value(int fd, uint32_t obj, uint32_t type, const char *name, int *found)
{
    drmModeObjectProperties *props = drmModeObjectGetProperties(fd, obj, type);
    uint64_t v = 0;
    *found = 0;
    for (uint32_t i = 0; props && i < props->count_props && !*found; i++) {
        drmModePropertyRes *p = drmModeGetProperty(fd, props->props[i]);
        if (p && !strcmp(p->name, name)) {
            v = props->prop_values[i];
            *found = 1;
        }
        drmModeFreeProperty(p);
    }
    drmModeFreeObjectProperties(props);
    return v;
}

/* Atomic needs the primary plane of our CRTC and the property ids; any gap means legacy. */
static int setup_atomic(cu_display *d)
{
    const char *force = getenv("CUMULO_DRM_LEGACY");
    if (force && *force && strcmp(force, "0"))
        return 0;
    if (drmSetClientCap(d->fd, DRM_CLIENT_CAP_UNIVERSAL_PLANES, 1) || drmSetClientCap(d->fd, DRM_CLIENT_CAP_ATOMIC, 1))
        return 0;
    drmModePlaneRes *pr = drmModeGetPlaneResources(d->fd);
    uint32_t any = 0, primary = 0;
    for (uint32_t i = 0; pr && i < pr->count_planes && !primary; i++) {
        drmModePlane *pl = drmModeGetPlane(d->fd, pr->planes[i]);
        if (pl && (pl->possible_crtcs & (1u << d->crtc_index))) {
            int found;
            uint64_t type = prop_value(d->fd, pl->plane_id, DRM_MODE_OBJECT_PLANE, "type", &found);
            if (found && type == DRM_PLANE_TYPE_PRIMARY)
                primary = pl->plane_id;
            else if (!any)
                any = pl->plane_id;
        }
        drmModeFreePlane(pl);
    }
    drmModeFreePlaneResources(pr);
    d->plane_id = primary ? primary : any;
    if (!d->plane_id)
        goto legacy;
    d->p_conn_crtc = prop_id(d->fd, d->conn_id, DRM_MODE_OBJECT_CONNECTOR, "CRTC_ID");
    d->p_crtc_mode = prop_id(d->fd, d->crtc_id, DRM_MODE_OBJECT_CRTC, "MODE_ID");
    d->p_crtc_active = prop_id(d->fd, d->crtc_id, DRM_MODE_OBJECT_CRTC, "ACTIVE");
    uint32_t pl = d->plane_id, t = DRM_MODE_OBJECT_PLANE;
    d->p_fb = prop_id(d->fd, pl, t, "FB_ID");
    d->p_crtc = prop_id(d->fd, pl, t, "CRTC_ID");
    d->p_sx = prop_id(d->fd, pl, t, "SRC_X");
    d->p_sy = prop_id(d->fd, pl, t, "SRC_Y");
    d->p_sw = prop_id(d->fd, pl, t, "SRC_W");
    d->p_sh = prop_id(d->fd, pl, t, "SRC_H");
    d->p_cx = prop_id(d->fd, pl, t, "CRTC_X");
    d->p_cy = prop_id(d->fd, pl, t, "CRTC_Y");
    d->p_cw = prop_id(d->fd, pl, t, "CRTC_W");
    d->p_ch = prop_id(d->fd, pl, t, "CRTC_H");
    if (!d->p_conn_crtc || !d->p_crtc_mode || !d->p_crtc_active || !d->p_fb || !d->p_crtc || !d->p_sx ||
        !d->p_sy || !d->p_sw || !d->p_sh || !d->p_cx || !d->p_cy || !d->p_cw || !d->p_ch)
        goto legacy;
    return 1;
legacy:
    drmSetClientCap(d->fd, DRM_CLIENT_CAP_ATOMIC, 0);
    return 0;
}

static int atomic_commit(cu_display *d, uint32_t fb, uint32_t flags)
{
    drmModeAtomicReq *req = drmModeAtomicAlloc();
    if (!req)
        return -ENOMEM;
    if (flags & DRM_MODE_ATOMIC_ALLOW_MODESET) {
        if (!d->mode_blob && drmModeCreatePropertyBlob(d->fd, &d->mode, sizeof d->mode, &d->mode_blob)) {
            drmModeAtomicFree(req);
            return -errno;
        }
        drmModeAtomicAddProperty(req, d->conn_id, d->p_conn_crtc, d->crtc_id);
        drmModeAtomicAddProperty(req, d->crtc_id, d->p_crtc_mode, d->mode_blob);
        drmModeAtomicAddProperty(req, d->crtc_id, d->p_crtc_active, 1);
    }
    uint32_t p = d->plane_id;
    drmModeAtomicAddProperty(req, p, d->p_fb, fb);
    drmModeAtomicAddProperty(req, p, d->p_crtc, d->crtc_id);
    drmModeAtomicAddProperty(req, p, d->p_sx, 0);
    drmModeAtomicAddProperty(req, p, d->p_sy, 0);
    drmModeAtomicAddProperty(req, p, d->p_sw, (uint64_t)d->mode.hdisplay << 16); /* 16.16 fixed point */
    drmModeAtomicAddProperty(req, p, d->p_sh, (uint64_t)d->mode.vdisplay << 16);
    drmModeAtomicAddProperty(req, p, d->p_cx, 0);
    drmModeAtomicAddProperty(req, p, d->p_cy, 0);
    drmModeAtomicAddProperty(req, p, d->p_cw, d->mode.hdisplay);
    drmModeAtomicAddProperty(req, p, d->p_ch, d->mode.vdisplay);
    int r = drmModeAtomicCommit(d->fd, req, flags, d);
    int e = errno;
    drmModeAtomicFree(req);
    return r ? -e : 0;
}

/* ---------------------------------------------------------------- buffers and flips */

static void fb_destroy(struct gbm_bo *bo, void *data)
{
    uint32_t *fb = data;
    int fd = gbm_device_get_fd(gbm_bo_get_device(bo));
    if (*fb)
        drmModeRmFB(fd, *fb);
    free(fb);
}

/* The KMS framebuffer of a GBM buffer, made once and kept as the buffer's user data (GBM recycles buffers). */
static uint32_t fb_for_bo(cu_display *d, struct gbm_bo *bo)
{
    uint32_t *fb = gbm_bo_get_user_data(bo);
    if (fb)
        return *fb;
    fb = calloc(1, sizeof *fb);
    if (!fb)
        return 0;
    uint32_t w = gbm_bo_get_width(bo), h = gbm_bo_get_height(bo), format = gbm_bo_get_format(bo);
    uint32_t handles[4] = {0}, strides[4] = {0}, offsets[4] = {0};
    uint64_t mods[4] = {0};
    uint64_t mod = gbm_bo_get_modifier(bo);
    int planes = gbm_bo_get_plane_count(bo);
    for (int i = 0; i < planes && i < 4; i++) {
        handles[i] = gbm_bo_get_handle_for_plane(bo, i).u32;
        strides[i] = gbm_bo_get_stride_for_plane(bo, i);
        offsets[i] = gbm_bo_get_offset(bo, i);
        mods[i] = mod;
    }
    int r = -1;
    if (mod != DRM_FORMAT_MOD_INVALID)
        r = drmModeAddFB2WithModifiers(d->fd, w, h, format, handles, strides, offsets, mods, fb,
                                       DRM_MODE_FB_MODIFIERS);
    if (r)
        r = drmModeAddFB2(d->fd, w, h, format, handles, strides, offsets, fb, 0);
    if (r)
        r = drmModeAddFB(d->fd, w, h, 24, 32, gbm_bo_get_stride(bo), gbm_bo_get_handle(bo).u32, fb);
    if (r) {
        free(fb);
        return 0;
    }
    gbm_bo_set_user_data(bo, fb, fb_destroy);
    return *fb;
}

static void flip_done(int fd, unsigned seq, unsigned sec, unsigned usec, void *data)
{
    (void)fd; (void)seq; (void)sec; (void)usec;
    ((cu_display *)data)->flip_pending = 0;
}

static void flip_done2(int fd, unsigned seq, unsigned sec, unsigned usec, unsigned crtc, void *data)
{
    (void)crtc;
    flip_done(fd, seq, sec, usec, data);
}

/* Blocks until the flip completes: that is the vsync. A signal does not abandon a queued flip (the buffers it
 * references must stay alive until the display stops reading them). */
static int wait_flip(cu_display *d, char *err, size_t errlen)
{
    drmEventContext ev = { .version = 3, .page_flip_handler = flip_done, .page_flip_handler2 = flip_done2 };
    while (d->flip_pending) {
        struct pollfd p = { .fd = d->fd, .events = POLLIN };
        int r = poll(&p, 1, 1000);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0) {
            snprintf(err, errlen, "drm: page flip on %s did not complete within 1 s (display off or unplugged?)",
                     d->conn_name);
            return 1;
        }
        if (drmHandleEvent(d->fd, &ev)) {
            snprintf(err, errlen, "drm: reading events from %s failed: %s", d->path, strerror(errno));
            return 1;
        }
    }
    return 0;
}

static int drm_present(cu_display *d, char *err, size_t errlen)
{
    if (!eglSwapBuffers(d->egl.dpy, d->egl.surf)) {
        snprintf(err, errlen, "drm: eglSwapBuffers failed (%s)", cu_egl_error());
        return 1;
    }
    struct gbm_bo *next = gbm_surface_lock_front_buffer(d->gs);
    uint32_t fb = next ? fb_for_bo(d, next) : 0;
    if (!fb) {
        snprintf(err, errlen, "drm: cannot make a scan-out framebuffer (%s)", strerror(errno));
        if (next)
            gbm_surface_release_buffer(d->gs, next);
        return 1;
    }
    int r;
    if (!d->modeset_done) {
        /* The first frame sets the mode (blocking); this is where DRM master is needed. */
        if (d->atomic)
            r = atomic_commit(d, fb, DRM_MODE_ATOMIC_ALLOW_MODESET);
        else
            r = drmModeSetCrtc(d->fd, d->crtc_id, fb, 0, 0, &d->conn_id, 1, &d->mode) ? -errno : 0;
        if (r) {
            if (r == -EACCES || r == -EPERM || r == -EBUSY)
                snprintf(err, errlen, "drm: cannot set the mode on %s (%s): another display server (X, Wayland, "
                         "a kiosk) owns the screen: stop it, or use --platform x11|wayland", d->path, strerror(-r));
            else
                snprintf(err, errlen, "drm: setting %dx%d on %s failed: %s", d->mode.hdisplay, d->mode.vdisplay,
                         d->conn_name, strerror(-r));
            gbm_surface_release_buffer(d->gs, next);
            return 1;
        }
        d->modeset_done = 1;
    } else {
        d->flip_pending = 1;
        if (d->atomic)
            r = atomic_commit(d, fb, DRM_MODE_ATOMIC_NONBLOCK | DRM_MODE_PAGE_FLIP_EVENT);
        else
            r = drmModePageFlip(d->fd, d->crtc_id, fb, DRM_MODE_PAGE_FLIP_EVENT, d) ? -errno : 0;
        if (r) {
            d->flip_pending = 0;
            snprintf(err, errlen, "drm: page flip on %s failed: %s", d->conn_name, strerror(-r));
            gbm_surface_release_buffer(d->gs, next);
            return 1;
        }
        if (wait_flip(d, err, errlen))
            return 1;
    }
    /* The previous buffer is off screen now: give it back to GBM for the next frame. */
    if (d->bo)
        gbm_surface_release_buffer(d->gs, d->bo);
    d->bo = next;
    return 0;
}

/* ---------------------------------------------------------------- open / close */

static void drm_close(cu_display *d)
{
    if (!d)
        return;
    if (d->fd >= 0 && d->modeset_done) {
        char err[128];
        wait_flip(d, err, sizeof err);
        /* Put the console (or whatever was there) back; legacy SetCrtc works on atomic drivers too. */
        if (d->saved && d->saved->mode_valid)
            drmModeSetCrtc(d->fd, d->saved->crtc_id, d->saved->buffer_id, d->saved->x, d->saved->y, &d->conn_id, 1,
                           &d->saved->mode);
        else
            drmModeSetCrtc(d->fd, d->crtc_id, 0, 0, 0, NULL, 0, NULL);
    }
    cu_egl_terminate(&d->egl);
    if (d->bo)
        gbm_surface_release_buffer(d->gs, d->bo);
    if (d->gs)
        gbm_surface_destroy(d->gs);
    if (d->gbm)
        gbm_device_destroy(d->gbm);
    if (d->saved)
        drmModeFreeCrtc(d->saved);
    if (d->mode_blob)
        drmModeDestroyPropertyBlob(d->fd, d->mode_blob);
    if (d->fd >= 0) {
        drmDropMaster(d->fd);
        close(d->fd);
    }
    free(d);
}

static int drm_open(cu_display **out, const cu_display_opts *o, char *err, size_t errlen)
{
    *out = NULL;
    cu_display *d = calloc(1, sizeof *d);
    if (!d) {
        snprintf(err, errlen, "drm: out of memory");
        return 1;
    }
    d->egl.dpy = EGL_NO_DISPLAY;
    d->fd = cu_drm_probe(o->device, d->path, sizeof d->path, err, errlen);
    if (d->fd < 0 || cu_drm_pick_output(d, o, err, errlen))
        goto fail;
    d->atomic = setup_atomic(d);
    d->gbm = gbm_create_device(d->fd);
    if (!d->gbm) {
        snprintf(err, errlen, "drm: gbm_create_device on %s failed: is Mesa's GBM (libgbm1) installed?", d->path);
        goto fail;
    }
    d->gs = gbm_surface_create(d->gbm, d->mode.hdisplay, d->mode.vdisplay, GBM_FORMAT_XRGB8888,
                               GBM_BO_USE_SCANOUT | GBM_BO_USE_RENDERING);
    if (!d->gs) {
        snprintf(err, errlen, "drm: gbm_surface_create %dx%d XRGB8888 on %s failed: %s", d->mode.hdisplay,
                 d->mode.vdisplay, d->path, strerror(errno));
        goto fail;
    }
    if (cu_egl_init(&d->egl, EGL_PLATFORM_GBM_KHR, d->gbm, GBM_FORMAT_XRGB8888, "drm", err, errlen) ||
        cu_egl_make_current(&d->egl, d->gs, "drm", err, errlen))
        goto fail;
    *out = d;
    return 0;
fail:
    drm_close(d);
    return 1;
}

static void *drm_proc(cu_display *d, const char *name)
{
    (void)d;
    return cu_egl_proc(name);
}

static void drm_frame(cu_display *d, unsigned *fbo, int *w, int *h)
{
    *fbo = 0;
    *w = d->mode.hdisplay;
    *h = d->mode.vdisplay;
}

static void drm_describe(cu_display *d, char *buf, size_t len)
{
    char egl[200];
    cu_egl_describe(&d->egl, egl, sizeof egl);
    snprintf(buf, len, "%s; %dx%d@%.2f fullscreen on %s via %s (%s modesetting)", egl, d->mode.hdisplay,
             d->mode.vdisplay, d->hz, d->conn_name, d->path, d->atomic ? "atomic" : "legacy");
}

const cu_display_backend cu_display_drm = {
    .name = "drm",
    .open = drm_open,
    .get_proc_address = drm_proc,
    .frame = drm_frame,
    .present = drm_present,
    .describe = drm_describe,
    .close = drm_close,
};
