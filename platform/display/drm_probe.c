/* platform/display/drm_probe.c: the DRM back end's choice of device (by path, by-path name, or the first card with a
 * connected output) and of connector, CRTC, primary plane and mode. */
#include "drm_priv.h"
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static const char *conn_type_name(uint32_t t)
{
    switch (t) {
    case DRM_MODE_CONNECTOR_VGA: return "VGA";
    case DRM_MODE_CONNECTOR_DVII: return "DVI-I";
    case DRM_MODE_CONNECTOR_DVID: return "DVI-D";
    case DRM_MODE_CONNECTOR_Composite: return "Composite";
    case DRM_MODE_CONNECTOR_LVDS: return "LVDS";
    case DRM_MODE_CONNECTOR_DisplayPort: return "DP";
    case DRM_MODE_CONNECTOR_HDMIA: return "HDMI-A";
    case DRM_MODE_CONNECTOR_HDMIB: return "HDMI-B";
    case DRM_MODE_CONNECTOR_TV: return "TV";
    case DRM_MODE_CONNECTOR_eDP: return "eDP";
    case DRM_MODE_CONNECTOR_VIRTUAL: return "Virtual";
    case DRM_MODE_CONNECTOR_DSI: return "DSI";
    case DRM_MODE_CONNECTOR_DPI: return "DPI";
    default: return "Unknown";
    }
}

static double mode_hz(const drmModeModeInfo *m)
{
    if (!m->htotal || !m->vtotal)
        return m->vrefresh;
    double hz = m->clock * 1000.0 / ((double)m->htotal * m->vtotal);
    if (m->flags & DRM_MODE_FLAG_INTERLACE)
        hz *= 2.0;
    if (m->flags & DRM_MODE_FLAG_DBLSCAN)
        hz /= 2.0;
    return hz;
}

/* ---------------------------------------------------------------- device probing */

/* 1 if fd is a KMS device with a connected connector (not a render-only GPU such as the Pi's V3D node). */
static int has_display(int fd)
{
    drmModeRes *res = drmModeGetResources(fd);
    if (!res)
        return 0;
    int ok = 0;
    for (int i = 0; i < res->count_connectors && !ok; i++) {
        drmModeConnector *c = drmModeGetConnector(fd, res->connectors[i]);
        if (c) {
            ok = c->connection == DRM_MODE_CONNECTED && c->count_modes > 0;
            drmModeFreeConnector(c);
        }
    }
    drmModeFreeResources(res);
    return ok;
}

static int try_open(const char *path, char *chosen, size_t clen, int *denied)
{
    int fd = open(path, O_RDWR | O_CLOEXEC);
    if (fd < 0) {
        if (errno == EACCES || errno == EPERM)
            *denied = 1;
        return -1;
    }
    if (!has_display(fd)) {
        close(fd);
        return -1;
    }
    snprintf(chosen, clen, "%s", path);
    return fd;
}

int cu_drm_probe(const char *want, char *chosen, size_t clen, char *err, size_t errlen)
{
    int denied = 0, fd;
    struct stat st;
    if (want) {
        char path[300];
        /* A by-path name on its own ("platform-gpu-card") is looked up where udev puts it. */
        if (want[0] == '/')
            snprintf(path, sizeof path, "%s", want);
        else
            snprintf(path, sizeof path, "/dev/dri/by-path/%s", want);
        if (want[0] != '/' && stat(path, &st) != 0)
            snprintf(path, sizeof path, "/dev/dri/%s", want);
        fd = open(path, O_RDWR | O_CLOEXEC);
        if (fd < 0) {
            if (errno == EACCES || errno == EPERM)
                snprintf(err, errlen, "drm: %s: permission denied: add the user to group 'video' (sudo usermod "
                         "-aG video $USER) or run as root", path);
            else
                snprintf(err, errlen, "drm: cannot open %s (%s): list the devices with ls -l /dev/dri/by-path",
                         path, strerror(errno));
            return -1;
        }
        drmModeRes *res = drmModeGetResources(fd);
        if (!res) {
            close(fd);
            snprintf(err, errlen, "drm: %s has no display controller (a render-only GPU?): give the card that "
                     "drives the screen, e.g. /dev/dri/by-path/platform-gpu-card on a Raspberry Pi", path);
            return -1;
        }
        drmModeFreeResources(res);
        snprintf(chosen, clen, "%s", path);
        return fd;
    }
    if (stat("/dev/dri", &st) != 0) {
        snprintf(err, errlen, "drm: no DRM device: /dev/dri does not exist (no KMS display driver loaded; on a "
                 "Raspberry Pi set dtoverlay=vc4-kms-v3d in config.txt), or use --platform x11|wayland|headless");
        return -1;
    }
    /* Raspberry Pi: the display controller (vc4) is not always card0 (V3D, render-only, may probe first); udev
     * gives it a stable by-path name ending in "gpu-card" (Pi 4: platform-gpu-card, Pi 5: platform-axi:gpu-card). */
    DIR *dir = opendir("/dev/dri/by-path");
    if (dir) {
        struct dirent *de;
        while ((de = readdir(dir))) {
            size_t n = strlen(de->d_name);
            if (n >= 8 && !strcmp(de->d_name + n - 8, "gpu-card")) {
                char p[300];
                snprintf(p, sizeof p, "/dev/dri/by-path/%s", de->d_name);
                if ((fd = try_open(p, chosen, clen, &denied)) >= 0) {
                    closedir(dir);
                    return fd;
                }
            }
        }
        closedir(dir);
    }
    /* Then every primary node libdrm knows, as kmscube does. */
    drmDevicePtr devs[32];
    int n = drmGetDevices2(0, devs, 32);
    for (int i = 0; i < n; i++) {
        fd = -1;
        if (devs[i]->available_nodes & (1 << DRM_NODE_PRIMARY))
            fd = try_open(devs[i]->nodes[DRM_NODE_PRIMARY], chosen, clen, &denied);
        if (fd >= 0) {
            drmFreeDevices(devs, n);
            return fd;
        }
    }
    if (n > 0)
        drmFreeDevices(devs, n);
    if (denied)
        snprintf(err, errlen, "drm: /dev/dri/card*: permission denied: add the user to group "
                 "'video' (sudo usermod -aG video $USER) or run as root");
    else
        snprintf(err, errlen, "drm: no DRM device with a connected display: plug in a monitor (and check "
                 "/sys/class/drm/*/status), or give --device /dev/dri/cardN");
    return -1;
}

/* ---------------------------------------------------------------- connector, mode, CRTC */

int cu_drm_pick_output(cu_display *d, const cu_display_opts *o, char *err, size_t errlen)
{
    drmModeRes *res = drmModeGetResources(d->fd);
    if (!res) {
        snprintf(err, errlen, "drm: drmModeGetResources on %s failed: %s", d->path, strerror(errno));
        return 1;
    }
    drmModeConnector *conn = NULL;
    for (int i = 0; i < res->count_connectors && !conn; i++) {
        drmModeConnector *c = drmModeGetConnector(d->fd, res->connectors[i]);
        if (c && c->connection == DRM_MODE_CONNECTED && c->count_modes > 0)
            conn = c;
        else if (c)
            drmModeFreeConnector(c);
    }
    if (!conn) {
        drmModeFreeResources(res);
        snprintf(err, errlen, "drm: %s has no connected display: plug in a monitor and restart", d->path);
        return 1;
    }
    d->conn_id = conn->connector_id;
    snprintf(d->conn_name, sizeof d->conn_name, "%s-%u", conn_type_name(conn->connector_type),
             conn->connector_type_id);

    cu_mode_info modes[MAX_MODES];
    int nm = conn->count_modes < MAX_MODES ? conn->count_modes : MAX_MODES;
    for (int i = 0; i < nm; i++) {
        modes[i].w = conn->modes[i].hdisplay;
        modes[i].h = conn->modes[i].vdisplay;
        modes[i].hz = mode_hz(&conn->modes[i]);
        modes[i].preferred = (conn->modes[i].type & DRM_MODE_TYPE_PREFERRED) != 0;
        modes[i].interlaced = (conn->modes[i].flags & DRM_MODE_FLAG_INTERLACE) != 0;
    }
    int w = 0, h = 0;
    double hz = 0.0;
    if (o->mode && cu_drm_parse_mode(o->mode, &w, &h, &hz, err, errlen)) {
        drmModeFreeConnector(conn);
        drmModeFreeResources(res);
        return 1;
    }
    int mi = cu_drm_pick_mode(modes, nm, w, h, hz);
    if (mi < 0) {
        char list[1024];
        cu_drm_list_modes(modes, nm, list, sizeof list);
        snprintf(err, errlen, "drm: %s on %s has no mode %s; it offers: %s", d->conn_name, d->path, o->mode, list);
        drmModeFreeConnector(conn);
        drmModeFreeResources(res);
        return 1;
    }
    d->mode = conn->modes[mi];
    d->hz = modes[mi].hz;

    /* The CRTC already driving this connector (keeps the console's pipe), else the first one an encoder allows. */
    uint32_t crtc = 0;
    if (conn->encoder_id) {
        drmModeEncoder *enc = drmModeGetEncoder(d->fd, conn->encoder_id);
        if (enc) {
            crtc = enc->crtc_id;
            drmModeFreeEncoder(enc);
        }
    }
    for (int e = 0; e < conn->count_encoders && !crtc; e++) {
        drmModeEncoder *enc = drmModeGetEncoder(d->fd, conn->encoders[e]);
        if (!enc)
            continue;
        for (int c = 0; c < res->count_crtcs && !crtc; c++)
            if (enc->possible_crtcs & (1u << c))
                crtc = res->crtcs[c];
        drmModeFreeEncoder(enc);
    }
    drmModeFreeConnector(conn);
    if (!crtc) {
        drmModeFreeResources(res);
        snprintf(err, errlen, "drm: no CRTC can drive %s on %s", d->conn_name, d->path);
        return 1;
    }
    d->crtc_id = crtc;
    for (int c = 0; c < res->count_crtcs; c++)
        if (res->crtcs[c] == crtc)
            d->crtc_index = c;
    drmModeFreeResources(res);
    d->saved = drmModeGetCrtc(d->fd, d->crtc_id);
    return 0;
}

/* ---------------------------------------------------------------- atomic modesetting */

