/* tests/platform/test_drm.c: the DRM/KMS back end (drm.c) against a fake Raspberry-Pi-like display stack: libdrm,
 * GBM and
 * the EGL helpers are defined here, /dev/dri is faked through ld --wrap of open/stat/opendir. Checks device probing
 * (by-path first, render-only V3D skipped), connector and mode choice, atomic and legacy page flipping with vsync
 * events, restoring the console's CRTC on close, and the one-line errors. No GPU or /dev/dri needed. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cmocka.h>
#include <gbm.h>
#include <xf86drm.h>
#include <xf86drmMode.h>
#include "display.h"
#include "egl_common.h"
#include "fake_dir.h"

extern const cu_display_backend cu_display_drm;

/* ---------------------------------------------------------------- the fake machine */
#define CONSOLE_FB 7
static struct fake {
    int no_dev_dri, no_by_path, card1_denied, hdmi2_connected, atomic_ok, modeset_errno;
    int rd[2], wr[2];                    /* card0, card1: pipes standing in for the DRM fds */
    void *flip_user;
    int flips_queued;
    struct { uint32_t crtc, fb, conn; int nconn; uint16_t w; uint32_t hz; } setcrtc[16];
    int nsetcrtc;
    struct { uint32_t flags, fb, mode_blob, active; } commit[64];
    int ncommit, npageflip, naddfb, nrmfb, locked, max_locked;
} F;

static int card_of_fd(int fd)
{
    for (int i = 0; i < 2; i++)
        if (F.rd[i] >= 0 && F.rd[i] == fd)
            return i;
    return -1;
}

int __real_open(const char *path, int flags, ...);
int __wrap_open(const char *path, int flags, ...)
{
    int card = -1;
    if (!strcmp(path, "/dev/dri/card0") || !strcmp(path, "/dev/dri/by-path/platform-fec00000.v3d-card"))
        card = 0;
    else if (!strcmp(path, "/dev/dri/card1") || !strcmp(path, "/dev/dri/by-path/platform-gpu-card"))
        card = 1;
    else if (!strncmp(path, "/dev/dri/", 9)) {
        errno = ENOENT;
        return -1;
    } else
        return __real_open(path, flags, 0);
    if (F.no_dev_dri) {
        errno = ENOENT;
        return -1;
    }
    if (card == 1 && F.card1_denied) {
        errno = EACCES;
        return -1;
    }
    int p[2];
    if (pipe(p))
        return -1;
    for (int i = 0; i < 2; i++)
        if (F.rd[i] == p[0]) /* that card's fd was closed and the number reused */
            F.rd[i] = -1;
    F.rd[card] = p[0];
    F.wr[card] = p[1];
    return p[0];
}

int __real_stat(const char *path, struct stat *st);
int __wrap_stat(const char *path, struct stat *st)
{
    if (!strncmp(path, "/dev/dri", 8)) {
        if (F.no_dev_dri || (F.no_by_path && strstr(path, "by-path"))) {
            errno = ENOENT;
            return -1;
        }
        memset(st, 0, sizeof *st);
        return 0;
    }
    return __real_stat(path, st);
}

/* As udev names them on a Pi 4: the V3D render GPU first, then the vc4 display controller. */
static const char *const by_path_names[] = {".", "..", "platform-fec00000.v3d-card", "platform-fec00000.v3d-render",
                                            "platform-gpu-card"};
static int by_path_missing(void) { return F.no_dev_dri || F.no_by_path; }
static const fake_dir by_path = {"/dev/dri/by-path", by_path_names, 5, by_path_missing};

/* ---------------------------------------------------------------- libdrm */
static drmModeModeInfo mk_mode(int w, int h, int hz, int preferred)
{
    drmModeModeInfo m;
    memset(&m, 0, sizeof m);
    m.hdisplay = (uint16_t)w;
    m.vdisplay = (uint16_t)h;
    m.htotal = (uint16_t)(w + 280);
    m.vtotal = (uint16_t)(h + 45);
    m.clock = (uint32_t)((double)m.htotal * m.vtotal * hz / 1000.0 + 0.5);
    m.vrefresh = (uint32_t)hz;
    m.type = preferred ? DRM_MODE_TYPE_PREFERRED : 0;
    snprintf(m.name, sizeof m.name, "%dx%d", w, h);
    return m;
}

static drmModeModeInfo modes[3];
static uint32_t conns[2] = { 41, 42 }, encs[2] = { 51, 52 }, crtcs[2] = { 100, 101 };
static uint32_t enc42[1] = { 52 }, enc41[1] = { 51 };
static drmModeRes res = { .count_connectors = 2, .connectors = conns, .count_encoders = 2, .encoders = encs,
                          .count_crtcs = 2, .crtcs = crtcs };
static drmModeConnector conn41, conn42;
static drmModeEncoder enc51 = { .encoder_id = 51, .crtc_id = 0, .possible_crtcs = 3 };
static drmModeEncoder enc52 = { .encoder_id = 52, .crtc_id = 100, .possible_crtcs = 3 };
static drmModeCrtc crtc100, crtc101;

drmModeResPtr drmModeGetResources(int fd) { return card_of_fd(fd) == 1 ? &res : NULL; /* card0: render only */ }
void drmModeFreeResources(drmModeResPtr p) { (void)p; }
drmModeConnectorPtr drmModeGetConnector(int fd, uint32_t id)
{
    (void)fd;
    conn41 = (drmModeConnector){ .connector_id = 41, .connector_type = DRM_MODE_CONNECTOR_HDMIA,
                                 .connector_type_id = 1, .connection = DRM_MODE_DISCONNECTED,
                                 .count_encoders = 1, .encoders = enc41 };
    conn42 = (drmModeConnector){ .connector_id = 42, .encoder_id = 52, .connector_type = DRM_MODE_CONNECTOR_HDMIA,
                                 .connector_type_id = 2,
                                 .connection = F.hdmi2_connected ? DRM_MODE_CONNECTED : DRM_MODE_DISCONNECTED,
                                 .count_modes = 3, .modes = modes, .count_encoders = 1, .encoders = enc42 };
    return id == 41 ? &conn41 : id == 42 ? &conn42 : NULL;
}
void drmModeFreeConnector(drmModeConnectorPtr p) { (void)p; }
drmModeEncoderPtr drmModeGetEncoder(int fd, uint32_t id) { (void)fd; return id == 51 ? &enc51 : id == 52 ? &enc52 : NULL; }
void drmModeFreeEncoder(drmModeEncoderPtr p) { (void)p; }
drmModeCrtcPtr drmModeGetCrtc(int fd, uint32_t id)
{
    (void)fd;
    crtc100 = (drmModeCrtc){ .crtc_id = 100, .buffer_id = CONSOLE_FB, .mode_valid = 1, .mode = modes[0] };
    crtc101 = (drmModeCrtc){ .crtc_id = 101 };
    return id == 100 ? &crtc100 : id == 101 ? &crtc101 : NULL;
}
void drmModeFreeCrtc(drmModeCrtcPtr p) { (void)p; }
int drmSetClientCap(int fd, uint64_t cap, uint64_t value)
{
    (void)fd;
    if (cap == DRM_CLIENT_CAP_ATOMIC && value && !F.atomic_ok) {
        errno = EOPNOTSUPP;
        return -1;
    }
    return 0;
}
static char *nodes0[DRM_NODE_MAX] = { "/dev/dri/card0" }, *nodes1[DRM_NODE_MAX] = { "/dev/dri/card1" };
static drmDevice dev0 = { .nodes = nodes0, .available_nodes = 1 << DRM_NODE_PRIMARY };
static drmDevice dev1 = { .nodes = nodes1, .available_nodes = 1 << DRM_NODE_PRIMARY };
int drmGetDevices2(uint32_t flags, drmDevicePtr devices[], int max)
{
    (void)flags;
    if (F.no_dev_dri)
        return 0;
    if (devices && max >= 2) {
        devices[0] = &dev0;
        devices[1] = &dev1;
    }
    return 2;
}
void drmFreeDevices(drmDevicePtr devices[], int count) { (void)devices; (void)count; }
int drmDropMaster(int fd) { (void)fd; return 0; }

/* Properties: ids 1000 + index into this table; objects own slices of it. */
static const char *prop_names[] = { "CRTC_ID", "MODE_ID", "ACTIVE", "type", "FB_ID", "CRTC_ID", "SRC_X", "SRC_Y",
                                    "SRC_W", "SRC_H", "CRTC_X", "CRTC_Y", "CRTC_W", "CRTC_H" };
static drmModePropertyRes prop_res[14];
static uint32_t conn_props[1] = { 1000 }, crtc_props[2] = { 1001, 1002 },
                plane_props[11] = { 1003, 1004, 1005, 1006, 1007, 1008, 1009, 1010, 1011, 1012, 1013 };
static uint64_t conn_vals[1], crtc_vals[2], plane_vals[11] = { DRM_PLANE_TYPE_PRIMARY };
static drmModeObjectProperties oprops;
drmModeObjectPropertiesPtr drmModeObjectGetProperties(int fd, uint32_t obj, uint32_t type)
{
    (void)fd;
    if (type == DRM_MODE_OBJECT_CONNECTOR && obj == 42)
        oprops = (drmModeObjectProperties){ 1, conn_props, conn_vals };
    else if (type == DRM_MODE_OBJECT_CRTC)
        oprops = (drmModeObjectProperties){ 2, crtc_props, crtc_vals };
    else if (type == DRM_MODE_OBJECT_PLANE && obj == 31)
        oprops = (drmModeObjectProperties){ 11, plane_props, plane_vals };
    else
        return NULL;
    return &oprops;
}
void drmModeFreeObjectProperties(drmModeObjectPropertiesPtr p) { (void)p; }
drmModePropertyPtr drmModeGetProperty(int fd, uint32_t id)
{
    (void)fd;
    if (id < 1000 || id >= 1014)
        return NULL;
    drmModePropertyRes *p = &prop_res[id - 1000];
    memset(p, 0, sizeof *p);
    p->prop_id = id;
    snprintf(p->name, sizeof p->name, "%s", prop_names[id - 1000]);
    return p;
}
void drmModeFreeProperty(drmModePropertyPtr p) { (void)p; }
static uint32_t planes[1] = { 31 };
static drmModePlaneRes plane_res = { 1, planes };
static drmModePlane plane31 = { .plane_id = 31, .possible_crtcs = 1 };
drmModePlaneResPtr drmModeGetPlaneResources(int fd) { (void)fd; return &plane_res; }
void drmModeFreePlaneResources(drmModePlaneResPtr p) { (void)p; }
drmModePlanePtr drmModeGetPlane(int fd, uint32_t id) { (void)fd; return id == 31 ? &plane31 : NULL; }
void drmModeFreePlane(drmModePlanePtr p) { (void)p; }
int drmModeCreatePropertyBlob(int fd, const void *data, size_t size, uint32_t *id)
{
    (void)fd; (void)data; (void)size;
    *id = 77;
    return 0;
}
int drmModeDestroyPropertyBlob(int fd, uint32_t id) { (void)fd; (void)id; return 0; }

struct _drmModeAtomicReq { uint32_t obj[32], prop[32]; uint64_t val[32]; int n; };
drmModeAtomicReqPtr drmModeAtomicAlloc(void) { return calloc(1, sizeof(struct _drmModeAtomicReq)); }
void drmModeAtomicFree(drmModeAtomicReqPtr r) { free(r); }
int drmModeAtomicAddProperty(drmModeAtomicReqPtr r, uint32_t obj, uint32_t prop, uint64_t val)
{
    if (r->n == 32)
        return -ENOSPC;
    r->obj[r->n] = obj;
    r->prop[r->n] = prop;
    r->val[r->n++] = val;
    return r->n;
}
static void queue_flip(int fd, void *user)
{
    F.flip_user = user;
    F.flips_queued++;
    assert_int_equal(write(F.wr[card_of_fd(fd)], "f", 1), 1);
}
int drmModeAtomicCommit(int fd, drmModeAtomicReqPtr r, uint32_t flags, void *user)
{
    if ((flags & DRM_MODE_ATOMIC_ALLOW_MODESET) && F.modeset_errno) {
        errno = F.modeset_errno;
        return -1;
    }
    int c = F.ncommit++;
    F.commit[c].flags = flags;
    for (int i = 0; i < r->n; i++) {
        if (r->prop[i] == 1004) F.commit[c].fb = (uint32_t)r->val[i];
        if (r->prop[i] == 1001) F.commit[c].mode_blob = (uint32_t)r->val[i];
        if (r->prop[i] == 1002) F.commit[c].active = (uint32_t)r->val[i];
    }
    if (flags & DRM_MODE_PAGE_FLIP_EVENT)
        queue_flip(fd, user);
    return 0;
}
int drmModeSetCrtc(int fd, uint32_t crtc, uint32_t fb, uint32_t x, uint32_t y, uint32_t *conn, int n,
                   drmModeModeInfoPtr mode)
{
    (void)fd; (void)x; (void)y;
    if (fb != CONSOLE_FB && fb != 0 && F.modeset_errno) {
        errno = F.modeset_errno;
        return -1;
    }
    int c = F.nsetcrtc++;
    F.setcrtc[c].crtc = crtc;
    F.setcrtc[c].fb = fb;
    F.setcrtc[c].nconn = n;
    F.setcrtc[c].conn = n ? conn[0] : 0;
    F.setcrtc[c].w = mode ? mode->hdisplay : 0;
    F.setcrtc[c].hz = mode ? mode->vrefresh : 0;
    return 0;
}
int drmModePageFlip(int fd, uint32_t crtc, uint32_t fb, uint32_t flags, void *user)
{
    (void)crtc; (void)fb;
    F.npageflip++;
    if (flags & DRM_MODE_PAGE_FLIP_EVENT)
        queue_flip(fd, user);
    return 0;
}
int drmHandleEvent(int fd, drmEventContextPtr ctx)
{
    char b;
    if (read(fd, &b, 1) != 1)
        return -1;
    F.flips_queued--;
    if (ctx->version >= 3 && ctx->page_flip_handler2)
        ctx->page_flip_handler2(fd, 1, 0, 0, 100, F.flip_user);
    else
        ctx->page_flip_handler(fd, 1, 0, 0, F.flip_user);
    return 0;
}
static uint32_t next_fb = 200;
int drmModeAddFB2WithModifiers(int fd, uint32_t w, uint32_t h, uint32_t fmt, const uint32_t hd[4],
                               const uint32_t st[4], const uint32_t off[4], const uint64_t mod[4], uint32_t *id,
                               uint32_t flags)
{
    (void)fd; (void)w; (void)h; (void)fmt; (void)hd; (void)st; (void)off; (void)mod; (void)flags;
    F.naddfb++;
    *id = next_fb++;
    return 0;
}
int drmModeAddFB2(int fd, uint32_t w, uint32_t h, uint32_t fmt, const uint32_t hd[4], const uint32_t st[4],
                  const uint32_t off[4], uint32_t *id, uint32_t flags)
{
    return drmModeAddFB2WithModifiers(fd, w, h, fmt, hd, st, off, NULL, id, flags);
}
int drmModeAddFB(int fd, uint32_t w, uint32_t h, uint8_t depth, uint8_t bpp, uint32_t pitch, uint32_t bo,
                 uint32_t *id)
{
    (void)fd; (void)w; (void)h; (void)depth; (void)bpp; (void)pitch; (void)bo; (void)id;
    return -1;
}
int drmModeRmFB(int fd, uint32_t id) { (void)fd; (void)id; F.nrmfb++; return 0; }

/* ---------------------------------------------------------------- GBM: three buffers in rotation */
struct gbm_device { int fd; };
struct gbm_surface { uint32_t w, h; };
struct gbm_bo { int locked, in_use; void *user; void (*destroy)(struct gbm_bo *, void *); };
static struct gbm_device the_gbm;
static struct gbm_surface the_surface;
static struct gbm_bo bos[3];
struct gbm_device *gbm_create_device(int fd) { the_gbm.fd = fd; return &the_gbm; }
void gbm_device_destroy(struct gbm_device *g) { (void)g; }
int gbm_device_get_fd(struct gbm_device *g) { return g->fd; }
struct gbm_surface *gbm_surface_create(struct gbm_device *g, uint32_t w, uint32_t h, uint32_t fmt, uint32_t flags)
{
    (void)g; (void)fmt; (void)flags;
    memset(bos, 0, sizeof bos);
    the_surface.w = w;
    the_surface.h = h;
    return &the_surface;
}
void gbm_surface_destroy(struct gbm_surface *s)
{
    (void)s;
    for (int i = 0; i < 3; i++)
        if (bos[i].destroy)
            bos[i].destroy(&bos[i], bos[i].user);
}
struct gbm_bo *gbm_surface_lock_front_buffer(struct gbm_surface *s)
{
    (void)s;
    for (int i = 0; i < 3; i++)
        if (!bos[i].locked) {
            bos[i].locked = 1;
            F.locked++;
            if (F.locked > F.max_locked)
                F.max_locked = F.locked;
            return &bos[i];
        }
    return NULL; /* the caller never gave buffers back */
}
void gbm_surface_release_buffer(struct gbm_surface *s, struct gbm_bo *bo) { (void)s; bo->locked = 0; F.locked--; }
void *gbm_bo_get_user_data(struct gbm_bo *bo) { return bo->user; }
void gbm_bo_set_user_data(struct gbm_bo *bo, void *data, void (*destroy)(struct gbm_bo *, void *))
{
    bo->user = data;
    bo->destroy = destroy;
}
struct gbm_device *gbm_bo_get_device(struct gbm_bo *bo) { (void)bo; return &the_gbm; }
uint32_t gbm_bo_get_width(struct gbm_bo *bo) { (void)bo; return the_surface.w; }
uint32_t gbm_bo_get_height(struct gbm_bo *bo) { (void)bo; return the_surface.h; }
uint32_t gbm_bo_get_format(struct gbm_bo *bo) { (void)bo; return GBM_FORMAT_XRGB8888; }
uint64_t gbm_bo_get_modifier(struct gbm_bo *bo) { (void)bo; return 0; /* linear */ }
int gbm_bo_get_plane_count(struct gbm_bo *bo) { (void)bo; return 1; }
union gbm_bo_handle gbm_bo_get_handle_for_plane(struct gbm_bo *bo, int p)
{
    (void)p;
    union gbm_bo_handle h;
    h.u32 = (uint32_t)(bo - bos) + 1;
    return h;
}
union gbm_bo_handle gbm_bo_get_handle(struct gbm_bo *bo) { return gbm_bo_get_handle_for_plane(bo, 0); }
uint32_t gbm_bo_get_stride_for_plane(struct gbm_bo *bo, int p) { (void)bo; (void)p; return the_surface.w * 4; }
uint32_t gbm_bo_get_stride(struct gbm_bo *bo) { return gbm_bo_get_stride_for_plane(bo, 0); }
uint32_t gbm_bo_get_offset(struct gbm_bo *bo, int p) { (void)bo; (void)p; return 0; }

/* ---------------------------------------------------------------- EGL (egl_common.h) */
static EGLint egl_visual;
int cu_egl_init(cu_egl *e, EGLenum platform, void *native, EGLint visual, const char *who, char *err, size_t len)
{
    (void)native; (void)who; (void)err; (void)len;
    assert_int_equal(platform, EGL_PLATFORM_GBM_KHR);
    egl_visual = visual;
    e->dpy = (EGLDisplay)&egl_visual;
    return 0;
}
int cu_egl_make_current(cu_egl *e, void *win, const char *who, char *err, size_t len)
{
    (void)e; (void)who; (void)err; (void)len;
    assert_ptr_equal(win, &the_surface);
    return 0;
}
void *cu_egl_proc(const char *name) { (void)name; return NULL; }
void cu_egl_describe(const cu_egl *e, char *buf, size_t len) { (void)e; snprintf(buf, len, "EGL fake"); }
void cu_egl_terminate(cu_egl *e) { e->dpy = EGL_NO_DISPLAY; }
const char *cu_egl_error(void) { return "EGL_SUCCESS"; }
EGLBoolean eglSwapBuffers(EGLDisplay dpy, EGLSurface s) { (void)dpy; (void)s; return EGL_TRUE; }

/* ---------------------------------------------------------------- tests */
static int setup(void **state)
{
    (void)state;
    memset(&F, 0, sizeof F);
    F.rd[0] = F.rd[1] = F.wr[0] = F.wr[1] = -1;
    F.hdmi2_connected = 1;
    F.atomic_ok = 1;
    modes[0] = mk_mode(1920, 1080, 60, 1);
    modes[1] = mk_mode(1280, 720, 60, 0);
    modes[2] = mk_mode(1280, 720, 50, 0);
    unsetenv("CUMULO_DRM_LEGACY");
    return 0;
}

static void close_pipes(void)
{
    for (int i = 0; i < 2; i++)
        if (F.wr[i] >= 0)
            close(F.wr[i]);
}

static void test_atomic_pi4(void **state)
{
    (void)state;
    cu_display *d;
    cu_display_opts o = {0};
    char err[512], desc[512];
    assert_int_equal(cu_display_drm.open(&d, &o, err, sizeof err), 0);
    assert_int_equal(egl_visual, GBM_FORMAT_XRGB8888);
    cu_display_drm.describe(d, desc, sizeof desc);
    assert_string_equal(desc, "EGL fake; 1920x1080@60.00 fullscreen on HDMI-A-2 via /dev/dri/by-path/platform-gpu-card "
                              "(atomic modesetting)");
    unsigned fbo;
    int w, h;
    cu_display_drm.frame(d, &fbo, &w, &h);
    assert_true(fbo == 0 && w == 1920 && h == 1080);
    for (int i = 0; i < 5; i++)
        assert_int_equal(cu_display_drm.present(d, err, sizeof err), 0);
    assert_int_equal(F.ncommit, 5);
    assert_true(F.commit[0].flags & DRM_MODE_ATOMIC_ALLOW_MODESET);    /* the first frame sets the mode */
    assert_int_equal(F.commit[0].mode_blob, 77);
    assert_int_equal(F.commit[0].active, 1);
    for (int i = 1; i < 5; i++) {
        assert_int_equal(F.commit[i].flags, DRM_MODE_ATOMIC_NONBLOCK | DRM_MODE_PAGE_FLIP_EVENT);
        assert_int_not_equal(F.commit[i].fb, F.commit[i - 1].fb);      /* a new buffer every frame */
    }
    assert_int_equal(F.flips_queued, 0);    /* each present waited for its flip: vsync */
    assert_true(F.max_locked <= 2);         /* the buffer off screen is given back to GBM */
    assert_int_equal(F.naddfb, 2);          /* one KMS framebuffer per GBM buffer, reused (two in rotation) */
    cu_display_drm.close(d);
    /* The console's framebuffer and mode are back on its CRTC. */
    assert_int_equal(F.nsetcrtc, 1);
    assert_int_equal(F.setcrtc[0].crtc, 100);
    assert_int_equal(F.setcrtc[0].fb, CONSOLE_FB);
    assert_int_equal(F.setcrtc[0].conn, 42);
    assert_int_equal(F.setcrtc[0].w, 1920);
    assert_int_equal(F.nrmfb, 2);
    close_pipes();
}

static void test_legacy_with_mode(void **state)
{
    (void)state;
    setenv("CUMULO_DRM_LEGACY", "1", 1);
    cu_display *d;
    cu_display_opts o = { .mode = "1280x720@50" };
    char err[512], desc[512];
    assert_int_equal(cu_display_drm.open(&d, &o, err, sizeof err), 0);
    cu_display_drm.describe(d, desc, sizeof desc);
    assert_non_null(strstr(desc, "1280x720@50.00 fullscreen on HDMI-A-2"));
    assert_non_null(strstr(desc, "(legacy modesetting)"));
    for (int i = 0; i < 3; i++)
        assert_int_equal(cu_display_drm.present(d, err, sizeof err), 0);
    assert_int_equal(F.ncommit, 0);
    assert_int_equal(F.setcrtc[0].w, 1280);     /* modeset on the first frame */
    assert_int_equal(F.setcrtc[0].hz, 50);
    assert_int_equal(F.npageflip, 2);
    cu_display_drm.close(d);
    assert_int_equal(F.setcrtc[F.nsetcrtc - 1].fb, CONSOLE_FB);
    close_pipes();
}

static void test_probe_without_by_path(void **state)
{
    (void)state;
    /* Without udev's by-path links: every primary node in turn; card0 (V3D, render only) is skipped. */
    F.no_by_path = 1;
    F.atomic_ok = 0;
    cu_display *d;
    cu_display_opts o = {0};
    char err[512], desc[512];
    assert_int_equal(cu_display_drm.open(&d, &o, err, sizeof err), 0);
    cu_display_drm.describe(d, desc, sizeof desc);
    assert_non_null(strstr(desc, "via /dev/dri/card1 (legacy modesetting)")); /* no atomic: legacy */
    cu_display_drm.close(d);
    assert_int_equal(F.nsetcrtc, 0); /* never set a mode, so nothing to restore */
    close_pipes();
}

static void expect_open_error(const cu_display_opts *o, const char *fragment)
{
    cu_display *d = NULL;
    char err[1024] = "";
    assert_int_not_equal(cu_display_drm.open(&d, o, err, sizeof err), 0);
    if (!strstr(err, fragment))
        fail_msg("message '%s' lacks '%s'", err, fragment);
    assert_non_null(strstr(err, "drm: "));
    close_pipes();
    F.rd[0] = F.rd[1] = F.wr[0] = F.wr[1] = -1;
}

static void test_errors(void **state)
{
    (void)state;
    cu_display_opts o = {0};
    F.no_dev_dri = 1;
    expect_open_error(&o, "no DRM device: /dev/dri does not exist");
    F.no_dev_dri = 0;
    F.hdmi2_connected = 0;
    expect_open_error(&o, "no DRM device with a connected display: plug in a monitor");
    F.hdmi2_connected = 1;
    F.card1_denied = 1;
    expect_open_error(&o, "permission denied: add the user to group 'video'");
    F.card1_denied = 0;
    cu_display_opts v3d = { .device = "/dev/dri/card0" };
    expect_open_error(&v3d, "/dev/dri/card0 has no display controller");
    cu_display_opts bypath = { .device = "platform-gpu-card", .mode = "1024x768" };
    expect_open_error(&bypath, "HDMI-A-2 on /dev/dri/by-path/platform-gpu-card has no mode 1024x768; it offers: "
                               "1920x1080@60.00 1280x720@60.00 1280x720@50.00");
    cu_display_opts refresh = { .mode = "1920x1080@75" };
    expect_open_error(&refresh, "has no mode 1920x1080@75");
}

static void test_display_in_use(void **state)
{
    (void)state;
    /* Another DRM master (X, a compositor) holds the screen: the first modeset is refused. */
    F.modeset_errno = EACCES;
    cu_display *d;
    cu_display_opts o = {0};
    char err[512];
    assert_int_equal(cu_display_drm.open(&d, &o, err, sizeof err), 0);
    assert_int_not_equal(cu_display_drm.present(d, err, sizeof err), 0);
    assert_non_null(strstr(err, "another display server (X, Wayland, a kiosk) owns the screen"));
    assert_int_equal(F.locked, 0); /* the buffer went back to GBM */
    cu_display_drm.close(d);
    assert_int_equal(F.nsetcrtc, 0); /* nothing of ours to undo */
    close_pipes();
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_atomic_pi4, setup),
        cmocka_unit_test_setup(test_legacy_with_mode, setup),
        cmocka_unit_test_setup(test_probe_without_by_path, setup),
        cmocka_unit_test_setup(test_errors, setup),
        cmocka_unit_test_setup(test_display_in_use, setup),
    };
    fake_dir_use(&by_path);
    return cmocka_run_group_tests(tests, NULL, NULL);
}
