/* platform/display/drm_mode.h: choosing a display mode for the DRM back end (`--mode WxH[@Hz]` or the preferred
 * one); pure, so it is tested without a display. */
#ifndef CU_PLATFORM_DRM_MODE_H
#define CU_PLATFORM_DRM_MODE_H
#include <stddef.h>

typedef struct cu_mode_info {
    int w, h;
    double hz;        /* exact refresh from the pixel clock and totals, not the rounded vrefresh */
    int preferred;    /* DRM_MODE_TYPE_PREFERRED: the monitor's native mode */
    int interlaced;
} cu_mode_info;

/* "1920x1080" or "1280x720@60" or "1280x720@59.94". Returns 0, or non-zero with a message naming --mode. */
int cu_drm_parse_mode(const char *s, int *w, int *h, double *hz, char *err, size_t errlen);
/* w == 0: the preferred mode, else the largest progressive one (kmscube's rule). Else the mode of that size whose
 * refresh is nearest hz (hz == 0: highest refresh), within 0.5 Hz when hz is given; progressive before interlaced.
 * Returns the index or -1. */
int cu_drm_pick_mode(const cu_mode_info *m, int n, int w, int h, double hz);
/* "1920x1080@60.00 1280x720@60.00 ..." for error messages. */
void cu_drm_list_modes(const cu_mode_info *m, int n, char *buf, size_t len);

#endif
