/* src/core/solar.c: UTC time text and calendar arithmetic, and the sun's topocentric position by NREL's SPA. */
#include "solar.h"
#include "vecmath.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

/* Reda & Andreas 2004, "Solar position algorithm for solar radiation applications" (NREL/TP-560-34302): its Earth
 * periodic terms and 63 nutation terms, copied by a script, unchanged, from pvlib-python's pvlib/spa.py (BSD-3-Clause,
 * commit 6382338a), not from NREL's spa.c; the counts are the paper's (L0 64, L1 34, L2 20, L3 7, L4 3, L5 1, B0 5,
 * B1 2, R0 40, R1 10, R2 6, R3 2, R4 1). */
typedef struct { double a, b, c; } spa_term;
typedef struct { signed char y[5]; double a, b, c, d; } spa_nutation; /* Y0..Y4 multiply X0..X4 */

static const spa_term L0[64] = {
    {175347046.0, 0.0, 0.0}, {3341656.0, 4.6692568, 6283.07585}, {34894.0, 4.6261, 12566.1517},
    {3497.0, 2.7441, 5753.3849}, {3418.0, 2.8289, 3.5231}, {3136.0, 3.6277, 77713.7715}, {2676.0, 4.4181, 7860.4194},
    {2343.0, 6.1352, 3930.2097}, {1324.0, 0.7425, 11506.7698}, {1273.0, 2.0371, 529.691}, {1199.0, 1.1096, 1577.3435},
    {990.0, 5.233, 5884.927}, {902.0, 2.045, 26.298}, {857.0, 3.508, 398.149}, {780.0, 1.179, 5223.694},
    {753.0, 2.533, 5507.553}, {505.0, 4.583, 18849.228}, {492.0, 4.205, 775.523}, {357.0, 2.92, 0.067},
    {317.0, 5.849, 11790.629}, {284.0, 1.899, 796.298}, {271.0, 0.315, 10977.079}, {243.0, 0.345, 5486.778},
    {206.0, 4.806, 2544.314}, {205.0, 1.869, 5573.143}, {202.0, 2.458, 6069.777}, {156.0, 0.833, 213.299},
    {132.0, 3.411, 2942.463}, {126.0, 1.083, 20.775}, {115.0, 0.645, 0.98}, {103.0, 0.636, 4694.003},
    {102.0, 0.976, 15720.839}, {102.0, 4.267, 7.114}, {99.0, 6.21, 2146.17}, {98.0, 0.68, 155.42},
    {86.0, 5.98, 161000.69}, {85.0, 1.3, 6275.96}, {85.0, 3.67, 71430.7}, {80.0, 1.81, 17260.15},
    {79.0, 3.04, 12036.46}, {75.0, 1.76, 5088.63}, {74.0, 3.5, 3154.69}, {74.0, 4.68, 801.82}, {70.0, 0.83, 9437.76},
    {62.0, 3.98, 8827.39}, {61.0, 1.82, 7084.9}, {57.0, 2.78, 6286.6}, {56.0, 4.39, 14143.5}, {56.0, 3.47, 6279.55},
    {52.0, 0.19, 12139.55}, {52.0, 1.33, 1748.02}, {51.0, 0.28, 5856.48}, {49.0, 0.49, 1194.45}, {41.0, 5.37, 8429.24},
    {41.0, 2.4, 19651.05}, {39.0, 6.17, 10447.39}, {37.0, 6.04, 10213.29}, {37.0, 2.57, 1059.38}, {36.0, 1.71, 2352.87},
    {36.0, 1.78, 6812.77}, {33.0, 0.59, 17789.85}, {30.0, 0.44, 83996.85}, {30.0, 2.74, 1349.87}, {25.0, 3.16, 4690.48},
};
static const spa_term L1[34] = {
    {628331966747.0, 0.0, 0.0}, {206059.0, 2.678235, 6283.07585}, {4303.0, 2.6351, 12566.1517}, {425.0, 1.59, 3.523},
    {119.0, 5.796, 26.298}, {109.0, 2.966, 1577.344}, {93.0, 2.59, 18849.23}, {72.0, 1.14, 529.69},
    {68.0, 1.87, 398.15}, {67.0, 4.41, 5507.55}, {59.0, 2.89, 5223.69}, {56.0, 2.17, 155.42}, {45.0, 0.4, 796.3},
    {36.0, 0.47, 775.52}, {29.0, 2.65, 7.11}, {21.0, 5.34, 0.98}, {19.0, 1.85, 5486.78}, {19.0, 4.97, 213.3},
    {17.0, 2.99, 6275.96}, {16.0, 0.03, 2544.31}, {16.0, 1.43, 2146.17}, {15.0, 1.21, 10977.08}, {12.0, 2.83, 1748.02},
    {12.0, 3.26, 5088.63}, {12.0, 5.27, 1194.45}, {12.0, 2.08, 4694.0}, {11.0, 0.77, 553.57}, {10.0, 1.3, 6286.6},
    {10.0, 4.24, 1349.87}, {9.0, 2.7, 242.73}, {9.0, 5.64, 951.72}, {8.0, 5.3, 2352.87}, {6.0, 2.65, 9437.76},
    {6.0, 4.67, 4690.48},
};
static const spa_term L2[20] = {
    {52919.0, 0.0, 0.0}, {8720.0, 1.0721, 6283.0758}, {309.0, 0.867, 12566.152}, {27.0, 0.05, 3.52}, {16.0, 5.19, 26.3},
    {16.0, 3.68, 155.42}, {10.0, 0.76, 18849.23}, {9.0, 2.06, 77713.77}, {7.0, 0.83, 775.52}, {5.0, 4.66, 1577.34},
    {4.0, 1.03, 7.11}, {4.0, 3.44, 5573.14}, {3.0, 5.14, 796.3}, {3.0, 6.05, 5507.55}, {3.0, 1.19, 242.73},
    {3.0, 6.12, 529.69}, {3.0, 0.31, 398.15}, {3.0, 2.28, 553.57}, {2.0, 4.38, 5223.69}, {2.0, 3.75, 0.98},
};
static const spa_term L3[7] = {
    {289.0, 5.844, 6283.076}, {35.0, 0.0, 0.0}, {17.0, 5.49, 12566.15}, {3.0, 5.2, 155.42}, {1.0, 4.72, 3.52},
    {1.0, 5.3, 18849.23}, {1.0, 5.97, 242.73},
};
static const spa_term L4[3] = {
    {114.0, 3.142, 0.0}, {8.0, 4.13, 6283.08}, {1.0, 3.84, 12566.15},
};
static const spa_term L5[1] = {
    {1.0, 3.14, 0.0},
};
static const spa_term B0[5] = {
    {280.0, 3.199, 84334.662}, {102.0, 5.422, 5507.553}, {80.0, 3.88, 5223.69}, {44.0, 3.7, 2352.87},
    {32.0, 4.0, 1577.34},
};
static const spa_term B1[2] = {
    {9.0, 3.9, 5507.55}, {6.0, 1.73, 5223.69},
};
static const spa_term R0[40] = {
    {100013989.0, 0.0, 0.0}, {1670700.0, 3.0984635, 6283.07585}, {13956.0, 3.05525, 12566.1517},
    {3084.0, 5.1985, 77713.7715}, {1628.0, 1.1739, 5753.3849}, {1576.0, 2.8469, 7860.4194}, {925.0, 5.453, 11506.77},
    {542.0, 4.564, 3930.21}, {472.0, 3.661, 5884.927}, {346.0, 0.964, 5507.553}, {329.0, 5.9, 5223.694},
    {307.0, 0.299, 5573.143}, {243.0, 4.273, 11790.629}, {212.0, 5.847, 1577.344}, {186.0, 5.022, 10977.079},
    {175.0, 3.012, 18849.228}, {110.0, 5.055, 5486.778}, {98.0, 0.89, 6069.78}, {86.0, 5.69, 15720.84},
    {86.0, 1.27, 161000.69}, {65.0, 0.27, 17260.15}, {63.0, 0.92, 529.69}, {57.0, 2.01, 83996.85},
    {56.0, 5.24, 71430.7}, {49.0, 3.25, 2544.31}, {47.0, 2.58, 775.52}, {45.0, 5.54, 9437.76}, {43.0, 6.01, 6275.96},
    {39.0, 5.36, 4694.0}, {38.0, 2.39, 8827.39}, {37.0, 0.83, 19651.05}, {37.0, 4.9, 12139.55}, {36.0, 1.67, 12036.46},
    {35.0, 1.84, 2942.46}, {33.0, 0.24, 7084.9}, {32.0, 0.18, 5088.63}, {32.0, 1.78, 398.15}, {28.0, 1.21, 6286.6},
    {28.0, 1.9, 6279.55}, {26.0, 4.59, 10447.39},
};
static const spa_term R1[10] = {
    {103019.0, 1.10749, 6283.07585}, {1721.0, 1.0644, 12566.1517}, {702.0, 3.142, 0.0}, {32.0, 1.02, 18849.23},
    {31.0, 2.84, 5507.55}, {25.0, 1.32, 5223.69}, {18.0, 1.42, 1577.34}, {10.0, 5.91, 10977.08}, {9.0, 1.42, 6275.96},
    {9.0, 0.27, 5486.78},
};
static const spa_term R2[6] = {
    {4359.0, 5.7846, 6283.0758}, {124.0, 5.579, 12566.152}, {12.0, 3.14, 0.0}, {9.0, 3.63, 77713.77},
    {6.0, 1.87, 5573.14}, {3.0, 5.47, 18849.23},
};
static const spa_term R3[2] = {
    {145.0, 4.273, 6283.076}, {7.0, 3.92, 12566.15},
};
static const spa_term R4[1] = {
    {4.0, 2.56, 6283.08},
};
static const spa_nutation NUTATION[63] = {
    {{0, 0, 0, 0, 1}, -171996, -174.2, 92025, 8.9}, {{-2, 0, 0, 2, 2}, -13187, -1.6, 5736, -3.1},
    {{0, 0, 0, 2, 2}, -2274, -0.2, 977, -0.5}, {{0, 0, 0, 0, 2}, 2062, 0.2, -895, 0.5},
    {{0, 1, 0, 0, 0}, 1426, -3.4, 54, -0.1}, {{0, 0, 1, 0, 0}, 712, 0.1, -7, 0},
    {{-2, 1, 0, 2, 2}, -517, 1.2, 224, -0.6}, {{0, 0, 0, 2, 1}, -386, -0.4, 200, 0},
    {{0, 0, 1, 2, 2}, -301, 0, 129, -0.1}, {{-2, -1, 0, 2, 2}, 217, -0.5, -95, 0.3}, {{-2, 0, 1, 0, 0}, -158, 0, 0, 0},
    {{-2, 0, 0, 2, 1}, 129, 0.1, -70, 0}, {{0, 0, -1, 2, 2}, 123, 0, -53, 0}, {{2, 0, 0, 0, 0}, 63, 0, 0, 0},
    {{0, 0, 1, 0, 1}, 63, 0.1, -33, 0}, {{2, 0, -1, 2, 2}, -59, 0, 26, 0}, {{0, 0, -1, 0, 1}, -58, -0.1, 32, 0},
    {{0, 0, 1, 2, 1}, -51, 0, 27, 0}, {{-2, 0, 2, 0, 0}, 48, 0, 0, 0}, {{0, 0, -2, 2, 1}, 46, 0, -24, 0},
    {{2, 0, 0, 2, 2}, -38, 0, 16, 0}, {{0, 0, 2, 2, 2}, -31, 0, 13, 0}, {{0, 0, 2, 0, 0}, 29, 0, 0, 0},
    {{-2, 0, 1, 2, 2}, 29, 0, -12, 0}, {{0, 0, 0, 2, 0}, 26, 0, 0, 0}, {{-2, 0, 0, 2, 0}, -22, 0, 0, 0},
    {{0, 0, -1, 2, 1}, 21, 0, -10, 0}, {{0, 2, 0, 0, 0}, 17, -0.1, 0, 0}, {{2, 0, -1, 0, 1}, 16, 0, -8, 0},
    {{-2, 2, 0, 2, 2}, -16, 0.1, 7, 0}, {{0, 1, 0, 0, 1}, -15, 0, 9, 0}, {{-2, 0, 1, 0, 1}, -13, 0, 7, 0},
    {{0, -1, 0, 0, 1}, -12, 0, 6, 0}, {{0, 0, 2, -2, 0}, 11, 0, 0, 0}, {{2, 0, -1, 2, 1}, -10, 0, 5, 0},
    {{2, 0, 1, 2, 2}, -8, 0, 3, 0}, {{0, 1, 0, 2, 2}, 7, 0, -3, 0}, {{-2, 1, 1, 0, 0}, -7, 0, 0, 0},
    {{0, -1, 0, 2, 2}, -7, 0, 3, 0}, {{2, 0, 0, 2, 1}, -7, 0, 3, 0}, {{2, 0, 1, 0, 0}, 6, 0, 0, 0},
    {{-2, 0, 2, 2, 2}, 6, 0, -3, 0}, {{-2, 0, 1, 2, 1}, 6, 0, -3, 0}, {{2, 0, -2, 0, 1}, -6, 0, 3, 0},
    {{2, 0, 0, 0, 1}, -6, 0, 3, 0}, {{0, -1, 1, 0, 0}, 5, 0, 0, 0}, {{-2, -1, 0, 2, 1}, -5, 0, 3, 0},
    {{-2, 0, 0, 0, 1}, -5, 0, 3, 0}, {{0, 0, 2, 2, 1}, -5, 0, 3, 0}, {{-2, 0, 2, 0, 1}, 4, 0, 0, 0},
    {{-2, 1, 0, 2, 1}, 4, 0, 0, 0}, {{0, 0, 1, -2, 0}, 4, 0, 0, 0}, {{-1, 0, 1, 0, 0}, -4, 0, 0, 0},
    {{-2, 1, 0, 0, 0}, -4, 0, 0, 0}, {{1, 0, 0, 0, 0}, -4, 0, 0, 0}, {{0, 0, 1, 2, 0}, 3, 0, 0, 0},
    {{0, 0, -2, 2, 2}, -3, 0, 0, 0}, {{-1, -1, 1, 0, 0}, -3, 0, 0, 0}, {{0, 1, 1, 0, 0}, -3, 0, 0, 0},
    {{0, -1, 1, 2, 2}, -3, 0, 0, 0}, {{2, -1, -1, 2, 2}, -3, 0, 0, 0}, {{0, 0, 3, 2, 2}, -3, 0, 0, 0},
    {{2, -1, 0, 2, 2}, -3, 0, 0, 0},
};

/* ---- calendar ---- */

static const char *const MONTH_NAME[12] = {"January", "February", "March",     "April",   "May",      "June",
                                           "July",    "August",   "September", "October", "November", "December"};

static int days_in_month(int y, int m)
{
    static const signed char n[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    return n[m - 1] + (m == 2 && ((y % 4 == 0 && y % 100 != 0) || y % 400 == 0));
}

/* Days from 1970-01-01 in the proleptic Gregorian calendar and back (Hinnant's days_from_civil / civil_from_days,
 * with March as the first month so that the leap day ends the year); y >= 0 here. */
static long long days_from_civil(long long y, int m, int d)
{
    y -= m <= 2;
    long long era = y / 400, yoe = y - era * 400;
    long long doy = (153 * (m > 2 ? m - 3 : m + 9) + 2) / 5 + d - 1;
    return era * 146097 + yoe * 365 + yoe / 4 - yoe / 100 + doy - 719468;
}

static void civil_from_days(long long z, int *y, int *m, int *d)
{
    z += 719468;
    long long era = z / 146097, doe = z - era * 146097;
    long long yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
    long long doy = doe - (365 * yoe + yoe / 4 - yoe / 100), mp = (5 * doy + 2) / 153;
    *d = (int)(doy - (153 * mp + 2) / 5 + 1);
    *m = (int)(mp < 10 ? mp + 3 : mp - 9);
    *y = (int)(yoe + era * 400 + (*m <= 2));
}

/* The years the ΔT model covers (and the tests check). */
#define YEAR_MIN 1900
#define YEAR_MAX 2100
#define SECONDS_MIN (-2208988800LL) /* 1900-01-01T00:00:00Z */
#define SECONDS_END 4133980800LL    /* 2101-01-01T00:00:00Z */

/* *out = `total` whole seconds after 1970-01-01T00:00:00Z plus frac in [0, 1); 1 when that is outside the years. */
static int split_seconds(long long total, double frac, cu_utc *out)
{
    long long days = total / 86400 - (total % 86400 < 0), sod = total - days * 86400;
    civil_from_days(days, &out->year, &out->month, &out->day);
    out->hour = (int)(sod / 3600);
    out->minute = (int)(sod / 60 % 60);
    out->second = (double)(sod % 60) + frac;
    return total < SECONDS_MIN || total >= SECONDS_END;
}

static long long seconds_of(const cu_utc *t)
{
    return days_from_civil(t->year, t->month, t->day) * 86400 + t->hour * 3600LL + t->minute * 60LL;
}

static int check_year(int y, char *why, size_t n)
{
    if (y >= YEAR_MIN && y <= YEAR_MAX)
        return 0;
    snprintf(why, n, "year %d (UTC) is outside %d..%d, the years of the Delta T model (Espenak & Meeus 2006)", y,
             YEAR_MIN, YEAR_MAX);
    return 1;
}

static int check_month_day(int y, int m, int d, char *why, size_t n)
{
    if (m < 1 || m > 12)
        snprintf(why, n, "month %d is not in 1..12", m);
    else if (d < 1 || d > days_in_month(y, m))
        snprintf(why, n, "day %d is not in %s %d", d, MONTH_NAME[m - 1], y);
    else
        return 0;
    return 1;
}

static int check_clock(int h, int mi, double s, char *why, size_t n)
{
    if (h < 0 || h > 23)
        snprintf(why, n, "hour %d is not in 0..23", h);
    else if (mi < 0 || mi > 59)
        snprintf(why, n, "minute %d is not in 0..59", mi);
    else if (!(s >= 0 && s < 61))
        snprintf(why, n, "second %g is not in 0..60 (60 only for a leap second)", s);
    else
        return 0;
    return 1;
}

/* UTC inserts a leap second only as the last second of a day. */
static int check_leap_second(const cu_utc *t, char *why, size_t n)
{
    if (t->second < 60 || (t->hour == 23 && t->minute == 59))
        return 0;
    snprintf(why, n, "second 60 (a leap second) is only at 23:59:60 UTC, not at %02d:%02d UTC", t->hour, t->minute);
    return 1;
}

static int utc_invalid(const cu_utc *t, char *why, size_t n)
{
    return check_year(t->year, why, n) || check_month_day(t->year, t->month, t->day, why, n) ||
           check_clock(t->hour, t->minute, t->second, why, n) || check_leap_second(t, why, n);
}

double cu_utc_julian_day(const cu_utc *t)
{
    int y = t->month > 2 ? t->year : t->year - 1, m = t->month > 2 ? t->month : t->month + 12;
    int a = y / 100, b = 2 - a + a / 4; /* Gregorian calendar: every date here is after 1582-10-15 */
    double day = t->day + (t->hour * 3600.0 + t->minute * 60.0 + t->second) / 86400.0;
    return floor(365.25 * (y + 4716)) + floor(30.6001 * (m + 1)) + day + b - 1524.5;
}

int cu_utc_add_seconds(cu_utc *t, double seconds)
{
    char why[160];
    if (!t || !isfinite(seconds) || fabs(seconds) > 1e12 || utc_invalid(t, why, sizeof why))
        return 1;
    double s = t->second + seconds, whole = floor(s);
    cu_utc r;
    if (split_seconds(seconds_of(t) + (long long)whole, s - whole, &r))
        return 1;
    *t = r;
    return 0;
}

int cu_utc_from_unix(double unix_seconds, cu_utc *out)
{
    cu_utc t = {1970, 1, 1, 0, 0, 0};
    if (!out || cu_utc_add_seconds(&t, unix_seconds))
        return 1;
    *out = t;
    return 0;
}

/* ---- ISO 8601 / RFC 3339 text ---- */

#define QUOTE_MAX 64 /* bytes of the text an error quotes */

/* "time_utc '<text>': why", quoting the first QUOTE_MAX bytes with control bytes escaped, "..." when cut. */
static int parse_fail(cu_error *err, const char *text, const char *why)
{
    char head[QUOTE_MAX + 1], q[4 * QUOTE_MAX + 1];
    size_t len = strlen(text), k = len < QUOTE_MAX ? len : QUOTE_MAX;
    memcpy(head, text, k);
    head[k] = 0;
    return cu_fail(err, "time_utc '%s%s': %s", cu_escape(q, sizeof q, head), len > QUOTE_MAX ? "..." : "", why);
}

/* What stands at text[i] where `want` should: the message names the character (1-based) and what it holds. */
static int syntax_fail(cu_error *err, const char *text, int i, const char *want)
{
    char why[200], c[2] = {text[i], 0}, ce[8];
    snprintf(why, sizeof why, "expected %s at character %d, found %s%s%s (layout YYYY-MM-DDTHH:MM:SS[.s]Z or +HH:MM)",
             want, i + 1, text[i] ? "'" : "the end", cu_escape(ce, sizeof ce, c), text[i] ? "'" : "");
    return parse_fail(err, text, why);
}

/* n decimal digits at text[*i] (advancing *i), or -1 with *i at the first that is not one. */
static int digits(const char *text, int *i, int n)
{
    int v = 0;
    for (int k = 0; k < n; k++, (*i)++) {
        if (text[*i] < '0' || text[*i] > '9')
            return -1;
        v = v * 10 + (text[*i] - '0');
    }
    return v;
}

int cu_utc_parse(const char *text, cu_utc *out, cu_error *err)
{
    if (!text || !*text)
        return cu_fail(err, "time_utc is empty: expected a UTC time such as 2026-06-21T12:00:00Z");
    static const int width[6] = {4, 2, 2, 2, 2, 2};
    static const char sep[5] = {'-', '-', 'T', ':', ':'};
    static const char *const sep_name[5] = {"'-'", "'-'", "'T' or a space", "':'", "':'"};
    int f[6], i = 0;
    for (int k = 0; k < 6; k++) {
        if ((f[k] = digits(text, &i, width[k])) < 0)
            return syntax_fail(err, text, i, "a digit");
        if (k < 5 && text[i] != sep[k] && !(k == 2 && text[i] == ' '))
            return syntax_fail(err, text, i, sep_name[k]);
        i += k < 5;
    }
    double frac = 0, scale = 1;
    if (text[i] == '.') {
        int n = 0;
        for (i++; n < 9 && text[i] >= '0' && text[i] <= '9'; i++, n++)
            frac += (text[i] - '0') / (scale *= 10);
        if (n == 0)
            return syntax_fail(err, text, i, "a digit after '.'");
        if (text[i] >= '0' && text[i] <= '9')
            return parse_fail(err, text, "more than 9 digits of fractional seconds");
    }
    int offset_min = 0;
    if (!text[i])
        return parse_fail(err, text, "no time zone: end with Z (UTC) or an offset such as +02:00");
    if (text[i] == '+' || text[i] == '-') {
        int sign = text[i++] == '+' ? 1 : -1, oh, om;
        if ((oh = digits(text, &i, 2)) < 0)
            return syntax_fail(err, text, i, "two digits of offset hours");
        i += text[i] == ':';
        if ((om = digits(text, &i, 2)) < 0)
            return syntax_fail(err, text, i, "two digits of offset minutes");
        if (oh > 23)
            return parse_fail(err, text, "offset hours are not in 00..23");
        if (om > 59)
            return parse_fail(err, text, "offset minutes are not in 00..59");
        offset_min = sign * (oh * 60 + om);
    } else if (text[i] == 'Z') {
        i++;
    } else {
        return syntax_fail(err, text, i, "the time zone: Z or an offset such as +02:00");
    }
    if (text[i])
        return syntax_fail(err, text, i, "the end of the text after the time zone");

    char why[200];
    /* A written year one off the range may still be in it in UTC (2101-01-01T00:30:00+01:00). */
    if ((f[0] < YEAR_MIN - 1 || f[0] > YEAR_MAX + 1) && check_year(f[0], why, sizeof why))
        return parse_fail(err, text, why);
    if (check_month_day(f[0], f[1], f[2], why, sizeof why) || check_clock(f[3], f[4], f[5], why, sizeof why))
        return parse_fail(err, text, why);
    /* Local time minus the offset is UTC; the seconds (a leap second's 60 too) stay as written. */
    cu_utc local = {f[0], f[1], f[2], f[3], f[4], 0}, utc;
    split_seconds(seconds_of(&local) - offset_min * 60LL, 0, &utc);
    utc.second = f[5] + frac;
    if (check_year(utc.year, why, sizeof why) || check_leap_second(&utc, why, sizeof why))
        return parse_fail(err, text, why);
    if (out)
        *out = utc;
    return 0;
}

/* ---- ΔT and SPA ---- */

double cu_solar_delta_t(int year, int month)
{
    double y = year + (month - 0.5) / 12, t;
    if (year < 1920)
        return t = y - 1900, -2.79 + t * (1.494119 + t * (-0.0598939 + t * (0.0061966 - 0.000197 * t)));
    if (year < 1941)
        return t = y - 1920, 21.20 + t * (0.84493 + t * (-0.076100 + t * 0.0020936));
    if (year < 1961)
        return t = y - 1950, 29.07 + t * (0.407 + t * (-1.0 / 233 + t / 2547));
    if (year < 1986)
        return t = y - 1975, 45.45 + t * (1.067 + t * (-1.0 / 260 - t / 718));
    if (year < 2005)
        return t = y - 2000,
               63.86 + t * (0.3345 + t * (-0.060374 + t * (0.0017275 + t * (0.000651814 + t * 0.00002373599))));
    if (year < 2050)
        return t = y - 2000, 62.92 + t * (0.32217 + t * 0.005589);
    t = (y - 1820) / 100;
    return -20 + 32 * t * t - 0.5628 * (2150 - y);
}

#define DEG (CU_PI / 180)
#define COUNT(a) ((int)(sizeof(a) / sizeof(a)[0]))

static double wrap360(double x)
{
    x = fmod(x, 360.0);
    x = x < 0 ? x + 360.0 : x;
    return x >= 360.0 ? 0.0 : x; /* -1e-17 + 360 rounds to 360 */
}

static double clamp1(double x) { return x > 1 ? 1 : x < -1 ? -1 : x; }

typedef struct { const spa_term *t; int n; } spa_series;
#define SERIES(a) {a, COUNT(a)}

/* The sum of A cos(B + C JME) of each table, as a polynomial in JME (L = (L0 + L1 JME + ...) / 1e8); radians. */
static double earth_series(const spa_series *tab, int k, double jme)
{
    double v = 0;
    for (int p = k - 1; p >= 0; p--) {
        double s = 0;
        for (int i = 0; i < tab[p].n; i++)
            s += tab[p].t[i].a * cos(tab[p].t[i].b + tab[p].t[i].c * jme);
        v = v * jme + s;
    }
    return v / 1e8;
}

int cu_solar_position_spa(const cu_utc *t, double latitude_deg, double longitude_deg, double height_m,
                          double pressure_hpa, double temperature_c, double delta_t_s, int refraction,
                          cu_solar_angles *out, cu_error *err)
{
    char why[200];
    if (!t || !out)
        return cu_fail(err, "solar position: no time or no result given");
    if (utc_invalid(t, why, sizeof why))
        return cu_fail(err, "solar position: %s", why);
    if (!(latitude_deg >= -90 && latitude_deg <= 90))
        return cu_fail(err, "latitude %g is not in [-90, 90] degrees (north positive)", latitude_deg);
    if (!(longitude_deg >= -180 && longitude_deg <= 180))
        return cu_fail(err, "longitude %g is not in [-180, 180] degrees (east positive)", longitude_deg);
    if (!(height_m >= -1000 && height_m <= 100000))
        return cu_fail(err, "height %g is not in [-1000, 100000] m above sea level", height_m);
    /* generous physical bounds: the test point passes 820 hPa, 11 C, 67 s */
    if (!(pressure_hpa > 0 && pressure_hpa <= 5000) || !(temperature_c > -273 && temperature_c <= 6000) ||
        !(delta_t_s >= -8000 && delta_t_s <= 8000))
        return cu_fail(err, "solar position: pressure %g hPa, temperature %g C or Delta T %g s out of range",
                       pressure_hpa, temperature_c, delta_t_s);

    /* Julian day (UT), ephemeris day (TT = UT + ΔT), their centuries and the ephemeris millennium from J2000 */
    double jd = cu_utc_julian_day(t), jde = jd + delta_t_s / 86400;
    double jc = (jd - 2451545) / 36525, jce = (jde - 2451545) / 36525, jme = jce / 10;
    /* the Earth's heliocentric longitude, latitude and radius (AU); the sun's geocentric longitude and latitude */
    static const spa_series L[6] = {SERIES(L0), SERIES(L1), SERIES(L2), SERIES(L3), SERIES(L4), SERIES(L5)},
                            B[2] = {SERIES(B0), SERIES(B1)},
                            R[5] = {SERIES(R0), SERIES(R1), SERIES(R2), SERIES(R3), SERIES(R4)};
    double helio_l = earth_series(L, 6, jme) / DEG, helio_b = earth_series(B, 2, jme) / DEG;
    double radius = earth_series(R, 5, jme);
    double theta = wrap360(helio_l + 180), beta = -helio_b;
    /* nutation in longitude and obliquity: X0..X4 (degrees) for the moon and sun, 63 terms in 0.0001 arc seconds */
    double x[5] = {297.85036 + jce * (445267.111480 + jce * (-0.0019142 + jce / 189474)),
                   357.52772 + jce * (35999.050340 + jce * (-0.0001603 - jce / 300000)),
                   134.96298 + jce * (477198.867398 + jce * (0.0086972 + jce / 56250)),
                   93.27191 + jce * (483202.017538 + jce * (-0.0036825 + jce / 327270)),
                   125.04452 + jce * (-1934.136261 + jce * (0.0020708 + jce / 450000))};
    double dpsi = 0, deps = 0;
    for (int i = 0; i < COUNT(NUTATION); i++) {
        const spa_nutation *n = &NUTATION[i];
        double arg = 0;
        for (int j = 0; j < 5; j++)
            arg += n->y[j] * x[j];
        dpsi += (n->a + n->b * jce) * sin(arg * DEG);
        deps += (n->c + n->d * jce) * cos(arg * DEG);
    }
    dpsi /= 36000000;
    deps /= 36000000;
    /* the true obliquity of the ecliptic (mean obliquity in arc seconds, a polynomial in U = JME / 10) */
    double u = jme / 10;
    double eps0 = 84381.448 + u * (-4680.93 + u * (-1.55 + u * (1999.25 + u * (-51.38 + u * (-249.67 + u * (-39.05 +
                  u * (7.12 + u * (27.87 + u * (5.79 + u * 2.45)))))))));
    double eps = (eps0 / 3600 + deps) * DEG;
    /* aberration, the apparent longitude, apparent sidereal time at Greenwich, geocentric right ascension and
     * declination, the observer's hour angle (measured westward from south) */
    double lambda = (theta + dpsi - 20.4898 / (3600 * radius)) * DEG;
    double nu0 = wrap360(280.46061837 + 360.98564736629 * (jd - 2451545) + jc * jc * (0.000387933 - jc / 38710000));
    double nu = nu0 + dpsi * cos(eps);
    double alpha = wrap360(atan2(sin(lambda) * cos(eps) - tan(beta * DEG) * sin(eps), cos(lambda)) / DEG);
    double delta = asin(clamp1(sin(beta * DEG) * cos(eps) + cos(beta * DEG) * sin(eps) * sin(lambda)));
    double h = wrap360(nu + longitude_deg - alpha) * DEG;
    /* parallax: xi the equatorial horizontal one; 0.99664719 = 1 - flattening, 6378140 m the equatorial radius */
    double xi = 8.794 / (3600 * radius) * DEG, lat = latitude_deg * DEG;
    double uu = atan(0.99664719 * tan(lat));
    double xx = cos(uu) + height_m / 6378140 * cos(lat), yy = 0.99664719 * sin(uu) + height_m / 6378140 * sin(lat);
    double den = cos(delta) - xx * sin(xi) * cos(h);
    double dalpha = atan2(-xx * sin(xi) * sin(h), den);
    double delta_p = atan2((sin(delta) - yy * sin(xi)) * cos(dalpha), den);
    double h_p = h - dalpha;
    /* topocentric elevation; refraction only while the sun is not wholly below the horizon (SPA's horizon
     * refraction 0.5667 plus the sun's radius 0.26667); the azimuth, from north */
    double e0 = asin(clamp1(sin(lat) * sin(delta_p) + cos(lat) * cos(delta_p) * cos(h_p))) / DEG, de = 0;
    if (refraction && e0 >= -(0.26667 + 0.5667))
        de = pressure_hpa / 1010 * 283 / (273 + temperature_c) * 1.02 / (60 * tan((e0 + 10.3 / (e0 + 5.11)) * DEG));
    double gamma = atan2(sin(h_p), cos(h_p) * sin(lat) - tan(delta_p) * cos(lat)) / DEG;
    out->elevation = e0 + de;
    out->zenith = 90 - out->elevation;
    out->azimuth = wrap360(gamma + 180);
    return 0;
}

int cu_solar_position(const cu_utc *t, double latitude_deg, double longitude_deg, double height_m, int refraction,
                      cu_solar_angles *out, cu_error *err)
{
    return cu_solar_position_spa(t, latitude_deg, longitude_deg, height_m, 1010, 10,
                                 t ? cu_solar_delta_t(t->year, t->month) : 0, refraction, out, err);
}

int cu_solar_position_at(const char *time_utc, double latitude_deg, double longitude_deg, double height_m,
                         int refraction, double *elevation_deg, double *azimuth_deg, cu_error *err)
{
    cu_utc t;
    cu_solar_angles a;
    if (cu_utc_parse(time_utc, &t, err) ||
        cu_solar_position(&t, latitude_deg, longitude_deg, height_m, refraction, &a, err))
        return 1;
    *elevation_deg = a.elevation;
    *azimuth_deg = a.azimuth;
    return 0;
}
