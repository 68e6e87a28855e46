/* platform/display/drm_priv.h: what the DRM back end's two files share: the display's state, and the probe of the
 * device and output (drm_probe.c) that drm.c's open calls. */
#ifndef CU_PLATFORM_DRM_PRIV_H
#define CU_PLATFORM_DRM_PRIV_H
#include "display.h"
#include "drm_mode.h"
#include "egl_common.h"
#include <gbm.h>
#include <stdint.h>
#include <xf86drm.h>
#include <xf86drmMode.h>

#define MAX_MODES 128

struct cu_display {
    int fd;
    char path[300];
    char conn_name[48];
    uint32_t conn_id, crtc_id, plane_id;
    int crtc_index;
    drmModeModeInfo mode;
    double hz;
    drmModeCrtc *saved;         /* what the CRTC showed before us (the console), put back on close */
    int atomic;
    uint32_t mode_blob;
    int modeset_done, flip_pending;
    struct gbm_device *gbm;
    struct gbm_surface *gs;
    struct gbm_bo *bo;          /* buffer on screen */
    cu_egl egl;
    /* atomic property ids */
    uint32_t p_conn_crtc, p_crtc_mode, p_crtc_active;
    uint32_t p_fb, p_crtc, p_sx, p_sy, p_sw, p_sh, p_cx, p_cy, p_cw, p_ch;
};

/* Opens the display device: `want` (a path or by-path name) or the first card with a connected output, Raspberry Pi
 * by-path names first. Returns the fd, or -1 with a message that says what to do. */
int cu_drm_probe(const char *want, char *chosen, size_t clen, char *err, size_t errlen);
/* Picks the connector, CRTC, plane and mode (--mode, else the preferred one) into d. */
int cu_drm_pick_output(cu_display *d, const cu_display_opts *o, char *err, size_t errlen);
#endif
