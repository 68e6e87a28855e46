/* platform/sim/fgfs.c: FlightGear generic-protocol lines (data/flightgear/cumulo.xml) into the simulation state. */
#include "fgfs.h"
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* One row per <chunk> of cumulo.xml, in its order: the name the XML gives the chunk, the range a value must lie in
 * (max_open: the maximum itself excluded), and whether it must be whole (the calendar fields, sent with %d). */
static const struct fgfs_field {
    const char *name;
    double min, max;
    int max_open, whole;
} fields[CU_FGFS_FIELDS] = {
    [CU_FGFS_LAT] = {"latitude-deg", -90, 90, 0, 0},
    [CU_FGFS_LON] = {"longitude-deg", -180, 180, 0, 0},
    [CU_FGFS_ALT] = {"altitude-m", -1e4, 1e6, 0, 0},
    [CU_FGFS_HEADING] = {"heading-deg", -1e4, 1e4, 0, 0},
    [CU_FGFS_PITCH] = {"pitch-deg", -1e4, 1e4, 0, 0},
    [CU_FGFS_ROLL] = {"roll-deg", -1e4, 1e4, 0, 0},
    [CU_FGFS_YEAR] = {"year", 1, 9999, 0, 1},
    [CU_FGFS_MONTH] = {"month", 1, 12, 0, 1},
    [CU_FGFS_DAY] = {"day", 1, 31, 0, 1},
    [CU_FGFS_HOUR] = {"hour", 0, 23, 0, 1},
    [CU_FGFS_MINUTE] = {"minute", 0, 59, 0, 1},
    [CU_FGFS_SECOND] = {"second", 0, 61, 1, 0},   /* 60.x: a leap second */
    [CU_FGFS_FOV] = {"field-of-view-deg", 1, 179, 0, 0},
};

/* The longest field read as a number: 1e6 with %.8f is 17 characters; more is not a number FlightGear printed. */
#define FIELD_MAX 48

const char *cu_fgfs_field_name(int field)
{
    return field >= 0 && field < CU_FGFS_FIELDS ? fields[field].name : NULL;
}

static int fail(char *err, size_t errlen, const char *fmt, ...)
{
    if (err && errlen) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err, errlen, fmt, ap);
        va_end(ap);
    }
    return -1;
}

/* The datagram's bytes as a message may quote them: printable ASCII as is, anything else (and the quote and the
 * backslash) as \xHH, at most 24 bytes and then "...", so that a hostile packet cannot write escape sequences into a
 * terminal or a log line. out needs 24 * 4 + 4 bytes. */
#define QUOTE_BYTES 24
#define QUOTE_CAP (QUOTE_BYTES * 4 + 4)
static const char *quote(char *out, const char *s, size_t n)
{
    size_t o = 0;
    for (size_t i = 0; i < n && i < QUOTE_BYTES; i++) {
        unsigned char c = (unsigned char)s[i];
        if (c >= 0x20 && c < 0x7f && c != '\\' && c != '\'')
            out[o++] = (char)c;
        else
            o += (size_t)snprintf(out + o, 5, "\\x%02x", c);
    }
    if (n > QUOTE_BYTES) {
        memcpy(out + o, "...", 3);
        o += 3;
    }
    out[o] = 0;
    return out;
}

static int is_blank(char c)
{
    return c == ' ' || c == '\t';
}

/* A decimal number as printf's %f, %e, %g and %d write one: [+-]digits[.digits][(e|E)[+-]digits], a digit before or
 * after the point. strtod alone would also take "nan", "inf", hexadecimal and leading newlines. */
static int is_decimal(const char *s, size_t n)
{
    size_t i = 0, digits = 0;
    if (i < n && (s[i] == '+' || s[i] == '-'))
        i++;
    for (; i < n && s[i] >= '0' && s[i] <= '9'; i++)
        digits++;
    if (i < n && s[i] == '.')
        for (i++; i < n && s[i] >= '0' && s[i] <= '9'; i++)
            digits++;
    if (!digits)
        return 0;
    if (i < n && (s[i] == 'e' || s[i] == 'E')) {
        size_t e = 0;
        if (++i < n && (s[i] == '+' || s[i] == '-'))
            i++;
        for (; i < n && s[i] >= '0' && s[i] <= '9'; i++)
            e++;
        if (!e)
            return 0;
    }
    return i == n;
}

/* Field f (0-based) from the n bytes at s into *v, checked against its row of the table. */
static int parse_field(int f, const char *s, size_t n, double *v, char *err, size_t errlen)
{
    const struct fgfs_field *d = &fields[f];
    char q[QUOTE_CAP];
    while (n && is_blank(*s))
        s++, n--;
    while (n && is_blank(s[n - 1]))
        n--;
    if (!n)
        return fail(err, errlen, "fgfs: field %d (%s) is empty", f + 1, d->name);
    if (n > FIELD_MAX || !is_decimal(s, n))
        return fail(err, errlen, "fgfs: field %d (%s): '%s' is not a number", f + 1, d->name, quote(q, s, n));
    char tmp[FIELD_MAX + 1];
    memcpy(tmp, s, n);
    tmp[n] = 0;
    double x = strtod(tmp, NULL);   /* finite or +-HUGE_VAL: the grammar above has no nan or inf */
    if (!isfinite(x) || x < d->min || x > d->max || (d->max_open && x >= d->max))
        return fail(err, errlen, "fgfs: field %d (%s): '%s' is out of range %g..%g%s", f + 1, d->name, quote(q, s, n),
                    d->min, d->max, d->max_open ? " (excluded)" : "");
    if (d->whole && x != floor(x))
        return fail(err, errlen, "fgfs: field %d (%s): '%s' is not a whole number", f + 1, d->name, quote(q, s, n));
    *v = x;
    return 0;
}

static int days_in_month(int year, int month)
{
    static const int days[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    int leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
    return month == 2 && leap ? 29 : days[month - 1];
}

int cu_fgfs_parse(const char *buf, size_t len, cu_sim_state *st, double *hfov_deg, char *err, size_t errlen)
{
    if (!buf || !st)
        return fail(err, errlen, "fgfs: no datagram");
    /* The last line: drop the line separators at the end, then start after the newline before them. */
    size_t end = len;
    while (end && (buf[end - 1] == '\n' || buf[end - 1] == '\r'))
        end--;
    if (!end)
        return fail(err, errlen, "fgfs: an empty datagram (%zu bytes)", len);
    size_t start = end;
    while (start && buf[start - 1] != '\n')
        start--;
    const char *line = buf + start;
    size_t n = end - start;
    if (n > CU_FGFS_LINE_MAX)
        return fail(err, errlen, "fgfs: a line of %zu bytes, longer than %d", n, CU_FGFS_LINE_MAX);

    int count = 1;
    for (size_t i = 0; i < n; i++)
        count += line[i] == ',';
    if (count < CU_FGFS_FIELDS)
        return fail(err, errlen, "fgfs: field %d (%s) is missing: %d fields, cumulo.xml sends %d", count + 1,
                    fields[count].name, count, CU_FGFS_FIELDS);
    if (count > CU_FGFS_FIELDS)
        return fail(err, errlen, "fgfs: field %d is extra: %d fields, cumulo.xml sends %d", CU_FGFS_FIELDS + 1, count,
                    CU_FGFS_FIELDS);

    double v[CU_FGFS_FIELDS];
    size_t a = 0;
    for (int f = 0; f < CU_FGFS_FIELDS; f++) {
        size_t b = a;
        while (b < n && line[b] != ',')
            b++;
        if (parse_field(f, line + a, b - a, &v[f], err, errlen))
            return -1;
        a = b + 1;
    }
    int year = (int)v[CU_FGFS_YEAR], month = (int)v[CU_FGFS_MONTH], day = (int)v[CU_FGFS_DAY];
    if (day > days_in_month(year, month))
        return fail(err, errlen, "fgfs: field %d (day): %d is not a day of %04d-%02d (it has %d)", CU_FGFS_DAY + 1, day,
                    year, month, days_in_month(year, month));

    st->pose_valid = 1;
    st->lat_deg = v[CU_FGFS_LAT];
    st->lon_deg = v[CU_FGFS_LON];
    st->alt_m = v[CU_FGFS_ALT];
    st->yaw_deg = v[CU_FGFS_HEADING];
    st->pitch_deg = v[CU_FGFS_PITCH];
    st->roll_deg = v[CU_FGFS_ROLL];
    st->time_valid = 1;
    st->year = year;
    st->month = month;
    st->day = day;
    st->hour = (int)v[CU_FGFS_HOUR];
    st->minute = (int)v[CU_FGFS_MINUTE];
    st->second = v[CU_FGFS_SECOND];
    st->changed |= CU_SIM_POSE | CU_SIM_TIME;
    if (hfov_deg)
        *hfov_deg = v[CU_FGFS_FOV];
    return 0;
}
