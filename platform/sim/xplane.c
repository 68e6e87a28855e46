/* platform/sim/xplane.c: X-Plane RREF requests out and RREF replies into the simulation state, bytes only. */
#include "xplane.h"
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* The packet layout (xplane.h) agrees in three independent sources:
 * - charlylima/XPlaneUDP, XPlaneUdp.py: requests packed as struct "<5sii400s" from b"RREF\x00", asserted 413 bytes;
 *   replies checked for the header b"RREF," ("was b'RREFO' for XPlane10") and read as "<if" per 8 bytes from byte 5.
 * - Avacee/XPlane-Wireshark-Dissector-C, packet-xplane.c: an RREF of exactly 413 bytes is a request (frequency
 *   int32 at 5, "0 to stop", id int32 at 9, dataref at 13 "padded with '\0'", 400 bytes, all little-endian); any
 *   other length is a reply of (length - 5) / 8 records of int32 id and float value.
 * - xdevsoft/advancexplanedatarefs, README.md: the same request as "<4sxii400s" (the x: the NUL X-Plane looks for).
 * The dataref names and units are those of X-Plane's DataRefs.txt (der-On/X-Plane-Dataref-Search, dist/DataRefs.txt):
 * latitude, longitude "degrees", elevation "meters" "above MSL", true_psi "true degrees north, always",
 * zulu_time_sec and local_time_sec "seconds", local_date_days "Date in days since January 1st",
 * field_of_view_deg "horizontal field of view in degrees". */

/* RREF values are IEEE-754 binary32: the build fails where a float is not 4 bytes (C99 has no _Static_assert). */
typedef char cu_xplane_float_is_binary32[sizeof(float) == 4 ? 1 : -1];

static const struct xplane_ref {
    const char *path;
    double min, max;
    int whole;
} refs[CU_XPLANE_REFS] = {
    [CU_XPLANE_LAT] = {"sim/flightmodel/position/latitude", -90, 90, 0},
    [CU_XPLANE_LON] = {"sim/flightmodel/position/longitude", -180, 180, 0},
    [CU_XPLANE_ELEV] = {"sim/flightmodel/position/elevation", -1e4, 1e6, 0},
    [CU_XPLANE_HEADING] = {"sim/flightmodel/position/true_psi", -1e4, 1e4, 0},
    [CU_XPLANE_PITCH] = {"sim/flightmodel/position/true_theta", -1e4, 1e4, 0},
    [CU_XPLANE_ROLL] = {"sim/flightmodel/position/true_phi", -1e4, 1e4, 0},
    [CU_XPLANE_ZULU_SEC] = {"sim/time/zulu_time_sec", 0, 86400, 0},
    [CU_XPLANE_LOCAL_SEC] = {"sim/time/local_time_sec", 0, 86400, 0},
    [CU_XPLANE_DATE_DAYS] = {"sim/time/local_date_days", 0, 365, 1},
    [CU_XPLANE_FOV] = {"sim/graphics/view/field_of_view_deg", 1, 179, 0},
};

#define BIT(i) (1u << (i))
#define POSE_BITS (BIT(CU_XPLANE_LAT) | BIT(CU_XPLANE_LON) | BIT(CU_XPLANE_ELEV) | BIT(CU_XPLANE_HEADING) | \
                   BIT(CU_XPLANE_PITCH) | BIT(CU_XPLANE_ROLL))
#define TIME_BITS (BIT(CU_XPLANE_ZULU_SEC) | BIT(CU_XPLANE_DATE_DAYS))
#define DAY_S 86400.0

const char *cu_xplane_dataref(int index)
{
    return index >= 0 && index < CU_XPLANE_REFS ? refs[index].path : NULL;
}

static void put32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v, p[1] = (uint8_t)(v >> 8), p[2] = (uint8_t)(v >> 16), p[3] = (uint8_t)(v >> 24);
}

static uint32_t get32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* The index as X-Plane's int32 (two's complement on the wire), without the implementation-defined conversion. */
static long as_int32(uint32_t u)
{
    return u <= 0x7fffffffu ? (long)u : -(long)(~u) - 1;
}

size_t cu_xplane_rref_request(uint8_t *out, size_t cap, int freq, int index, const char *dataref)
{
    if (!out || cap < CU_XPLANE_REQUEST_SIZE || !dataref || freq < 0 || freq > 1000)
        return 0;
    size_t n = 0;
    while (n < CU_XPLANE_PATH_MAX && dataref[n])
        n++;
    if (n == 0 || n >= CU_XPLANE_PATH_MAX)
        return 0;
    for (size_t i = 0; i < n; i++)
        if ((unsigned char)dataref[i] < 0x21 || (unsigned char)dataref[i] > 0x7e)
            return 0;
    memset(out, 0, CU_XPLANE_REQUEST_SIZE);
    memcpy(out, "RREF", 4);                /* out[4] = 0 */
    put32(out + 5, (uint32_t)freq);
    put32(out + 9, (uint32_t)index);       /* modulo 2^32: two's complement for a negative index */
    memcpy(out + 13, dataref, n);          /* the rest of the 400 bytes stays NUL */
    return CU_XPLANE_REQUEST_SIZE;
}

void cu_xplane_rx_init(cu_xplane_rx *rx, int year)
{
    memset(rx, 0, sizeof *rx);
    rx->year = year;
}

static int fail(cu_xplane_rx *rx, char *err, size_t errlen, const char *fmt, ...)
{
    rx->rejected++;
    if (err && errlen) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err, errlen, fmt, ap);
        va_end(ap);
    }
    return -1;
}

static int days_in_year(int y)
{
    return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0 ? 366 : 365;
}

/* rx's zulu seconds and day of year as st's UTC date and time; 0 when the year is not one st can hold. X-Plane's
 * date is local: where local and zulu clocks are more than 12 h apart, the local date is the day before (local clock
 * ahead of zulu by over 12 h means it is behind by the rest of a day) or after the UTC date. */
static int set_time(const cu_xplane_rx *rx, cu_sim_state *st)
{
    double z = rx->val[CU_XPLANE_ZULU_SEC];
    if (z >= DAY_S)   /* 86400 itself: a float rounded up in the last 1/256 s of the day */
        z = DAY_S - 1e-3;
    int year = rx->year, doy = (int)rx->val[CU_XPLANE_DATE_DAYS];
    if (rx->have & BIT(CU_XPLANE_LOCAL_SEC)) {
        double d = rx->val[CU_XPLANE_LOCAL_SEC] - z;
        doy += d > DAY_S / 2 ? 1 : d < -DAY_S / 2 ? -1 : 0;
    }
    if (year < 1 || year > 9999)
        return 0;
    if (doy < 0)
        doy += days_in_year(--year);
    else if (doy >= days_in_year(year))
        doy -= days_in_year(year++);
    if (year < 1 || year > 9999)
        return 0;
    static const int mdays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    int month = 0;
    for (;;) {
        int n = mdays[month] + (month == 1 && days_in_year(year) == 366);
        if (doy < n)
            break;
        doy -= n;
        month++;
    }
    int hour = (int)(z / 3600), minute = (int)((z - hour * 3600.0) / 60);
    st->time_valid = 1;
    st->year = year;
    st->month = month + 1;
    st->day = doy + 1;
    st->hour = hour;
    st->minute = minute;
    st->second = z - hour * 3600.0 - minute * 60.0;
    st->changed |= CU_SIM_TIME;
    return 1;
}

int cu_xplane_parse(cu_xplane_rx *rx, const uint8_t *buf, size_t len, cu_sim_state *st, double *hfov_deg, char *err,
                    size_t errlen)
{
    if (!rx) {
        if (err && errlen)
            snprintf(err, errlen, "xplane: no receiver state");
        return -1;
    }
    if (!st || (!buf && len))
        return fail(rx, err, errlen, "xplane: no datagram");
    if (len < 5)
        return fail(rx, err, errlen, "xplane: a datagram of %zu bytes, shorter than the 5-byte header", len);
    if (memcmp(buf, "RREF", 4) != 0 || (buf[4] != ',' && buf[4] != 'O'))
        return fail(rx, err, errlen, "xplane: header %02x %02x %02x %02x %02x is not \"RREF,\" (or X-Plane 10's "
                    "\"RREFO\")", buf[0], buf[1], buf[2], buf[3], buf[4]);
    if ((len - 5) % 8)
        return fail(rx, err, errlen, "xplane: %zu bytes after the header: record %zu is cut short (%zu of 8 bytes)",
                    len - 5, (len - 5) / 8 + 1, (len - 5) % 8);
    size_t n = (len - 5) / 8;

    /* First every record checked, so that a refused datagram leaves everything as it was. */
    unsigned long unknown = 0;
    for (size_t r = 0; r < n; r++) {
        const uint8_t *p = buf + 5 + 8 * r;
        uint32_t idx = get32(p), bits = get32(p + 4);
        if (idx >= CU_XPLANE_REFS) {
            unknown++;
            continue;
        }
        float f;
        memcpy(&f, &bits, sizeof f);
        const struct xplane_ref *d = &refs[idx];
        const char *why = NULL;
        if (!isfinite(f))
            why = "is not a finite number";
        else if (f < d->min || f > d->max)
            why = "is out of range";
        else if (d->whole && f != floorf(f))
            why = "is not a whole number";
        if (why) {
            rx->bad_values++;
            return fail(rx, err, errlen, "xplane: record %zu (index %ld, %s): %.9g %s (%g..%g)", r + 1, as_int32(idx),
                        d->path, (double)f, why, d->min, d->max);
        }
    }

    unsigned brought = 0;
    for (size_t r = 0; r < n; r++) {
        const uint8_t *p = buf + 5 + 8 * r;
        uint32_t idx = get32(p), bits = get32(p + 4);
        if (idx >= CU_XPLANE_REFS)
            continue;
        float f;
        memcpy(&f, &bits, sizeof f);
        rx->val[idx] = f;
        brought |= BIT(idx);
    }
    rx->have |= brought;
    rx->unknown += unknown;
    rx->datagrams++;

    if ((rx->have & POSE_BITS) == POSE_BITS && (brought & POSE_BITS)) {
        st->pose_valid = 1;
        st->lat_deg = rx->val[CU_XPLANE_LAT];
        st->lon_deg = rx->val[CU_XPLANE_LON];
        st->alt_m = rx->val[CU_XPLANE_ELEV];
        st->yaw_deg = rx->val[CU_XPLANE_HEADING];
        st->pitch_deg = rx->val[CU_XPLANE_PITCH];
        st->roll_deg = rx->val[CU_XPLANE_ROLL];
        st->changed |= CU_SIM_POSE;
    }
    if ((rx->have & TIME_BITS) == TIME_BITS && (brought & (TIME_BITS | BIT(CU_XPLANE_LOCAL_SEC))))
        set_time(rx, st);
    if (hfov_deg && (brought & BIT(CU_XPLANE_FOV)))
        *hfov_deg = rx->val[CU_XPLANE_FOV];
    return 0;
}
