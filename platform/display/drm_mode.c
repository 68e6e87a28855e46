/* platform/display/drm_mode.c: --mode parsing and mode choice for DRM/KMS. */
#include "drm_mode.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int cu_drm_parse_mode(const char *s, int *w, int *h, double *hz, char *err, size_t errlen)
{
    char *end;
    long a, b;
    double r = 0.0;
    a = strtol(s, &end, 10);
    if (end == s || *end != 'x' || a < 1 || a > 16384)
        goto bad;
    const char *q = end + 1;
    b = strtol(q, &end, 10);
    if (end == q || b < 1 || b > 16384)
        goto bad;
    if (*end == '@') {
        q = end + 1;
        r = strtod(q, &end);
        if (end == q || !(r > 0.0) || r > 1000.0)
            goto bad;
    }
    if (*end)
        goto bad;
    *w = (int)a;
    *h = (int)b;
    *hz = r;
    return 0;
bad:
    snprintf(err, errlen, "--mode '%s': expected WxH or WxH@Hz, e.g. 1920x1080 or 1280x720@60", s);
    return 1;
}

int cu_drm_pick_mode(const cu_mode_info *m, int n, int w, int h, double hz)
{
    int best = -1;
    if (w == 0) {
        for (int i = 0; i < n; i++)
            if (m[i].preferred)
                return i;
        long area = -1;
        for (int i = 0; i < n; i++) {
            long a = (long)m[i].w * m[i].h;
            if (!m[i].interlaced && (a > area || (a == area && m[i].hz > m[best].hz))) {
                area = a;
                best = i;
            }
        }
        return best >= 0 ? best : (n > 0 ? 0 : -1);
    }
    double best_d = 1e9;
    int best_il = 1;
    for (int i = 0; i < n; i++) {
        if (m[i].w != w || m[i].h != h)
            continue;
        double d = hz > 0.0 ? fabs(m[i].hz - hz) : -m[i].hz;
        if (hz > 0.0 && d > 0.5)
            continue;
        if (best < 0 || m[i].interlaced < best_il || (m[i].interlaced == best_il && d < best_d)) {
            best = i;
            best_d = d;
            best_il = m[i].interlaced;
        }
    }
    return best;
}

void cu_drm_list_modes(const cu_mode_info *m, int n, char *buf, size_t len)
{
    size_t used = 0;
    buf[0] = '\0';
    for (int i = 0; i < n && used + 1 < len; i++) {
        int k = snprintf(buf + used, len - used, "%s%dx%d@%.2f%s", i ? " " : "", m[i].w, m[i].h, m[i].hz,
                         m[i].interlaced ? "i" : "");
        if (k < 0)
            break;
        used += (size_t)k;
    }
}
