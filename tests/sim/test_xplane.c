/* tests/sim/test_xplane.c: X-Plane RREF: the request's bytes against a hand-written one, a recorded take-off
 * (tests/sim/data/xplane_rref.hex), the UTC date from X-Plane's local one, and hostile datagrams. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "xplane.h"

#define STREAM "tests/sim/data/xplane_rref.hex"
#define DGRAM_MAX 2048

/* The recorded file: one datagram per line in hex, blanks between bytes allowed, '#' lines and blank lines skipped. */
typedef struct dgram {
    uint8_t b[DGRAM_MAX];
    size_t len;
} dgram;

static int load_stream(dgram *out, int cap)
{
    FILE *f = fopen(STREAM, "r");
    if (!f)
        fail_msg("cannot open %s (run from the top of the tree)", STREAM);
    char line[8192];
    int n = 0;
    while (fgets(line, sizeof line, f)) {
        if (line[0] == '#' || line[strspn(line, " \t\r\n")] == 0)
            continue;
        assert_true(n < cap);
        dgram *d = &out[n++];
        d->len = 0;
        for (const char *p = line; *p;) {
            if (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n') {
                p++;
                continue;
            }
            unsigned v;
            if (sscanf(p, "%2x", &v) != 1)
                fail_msg("datagram %d: '%.8s' is not hex", n, p);
            assert_true(d->len < DGRAM_MAX);
            d->b[d->len++] = (uint8_t)v;
            p += 2;
        }
    }
    fclose(f);
    return n;
}

/* Builders for hand-made datagrams: a header and (index, value) records, little-endian as X-Plane sends them. */
typedef struct rec { int32_t idx; float v; } rec;
static size_t build(uint8_t *out, const char *hdr, const rec *r, size_t n)
{
    memcpy(out, hdr, 5);
    for (size_t i = 0; i < n; i++) {
        uint32_t u = (uint32_t)r[i].idx, f;
        memcpy(&f, &r[i].v, 4);
        for (int k = 0; k < 4; k++) {
            out[5 + 8 * i + k] = (uint8_t)(u >> (8 * k));
            out[9 + 8 * i + k] = (uint8_t)(f >> (8 * k));
        }
    }
    return 5 + 8 * n;
}

static void assert_printable(const char *err)
{
    for (const char *p = err; *p; p++)
        if ((unsigned char)*p < 0x20 || (unsigned char)*p >= 0x7f)
            fail_msg("byte 0x%02x in message '%s'", (unsigned char)*p, err);
}

static void test_table(void **state)
{
    (void)state;
    static const char *want[CU_XPLANE_REFS] = {
        "sim/flightmodel/position/latitude", "sim/flightmodel/position/longitude",
        "sim/flightmodel/position/elevation", "sim/flightmodel/position/true_psi",
        "sim/flightmodel/position/true_theta", "sim/flightmodel/position/true_phi", "sim/time/zulu_time_sec",
        "sim/time/local_time_sec", "sim/time/local_date_days", "sim/graphics/view/field_of_view_deg",
    };
    for (int i = 0; i < CU_XPLANE_REFS; i++)
        assert_string_equal(cu_xplane_dataref(i), want[i]);
    assert_null(cu_xplane_dataref(-1));
    assert_null(cu_xplane_dataref(CU_XPLANE_REFS));
}

/* The request, byte by byte: "RREF" NUL at 0..4, freq at 5..8, index at 9..12 (little-endian), the path at 13,
 * NULs to byte 412. */
static void test_request(void **state)
{
    (void)state;
    uint8_t out[500], want[413];
    memset(out, 0xaa, sizeof out);
    memset(want, 0, sizeof want);
    const char *path = "sim/flightmodel/position/elevation";
    memcpy(want, "RREF\0", 5);
    want[5] = 30;                                    /* freq 30 = 0x0000001e */
    want[9] = 2;                                     /* index 2 */
    memcpy(want + 13, path, strlen(path));
    assert_int_equal(cu_xplane_rref_request(out, sizeof out, 30, 2, path), 413);
    assert_memory_equal(out, want, 413);
    assert_int_equal(out[413], 0xaa);                /* nothing past the request */

    /* 1000 = 0x3e8, index -2 = 0xfffffffe, a path of 399 bytes (its NUL is byte 412) */
    char long_path[400];
    memset(long_path, 'a', 399);
    long_path[399] = 0;
    assert_int_equal(cu_xplane_rref_request(out, 413, 1000, -2, long_path), 413);
    const uint8_t head[13] = {'R', 'R', 'E', 'F', 0, 0xe8, 0x03, 0, 0, 0xfe, 0xff, 0xff, 0xff};
    assert_memory_equal(out, head, 13);
    assert_int_equal(out[13], 'a');
    assert_int_equal(out[411], 'a');
    assert_int_equal(out[412], 0);
    /* an unsubscribe: frequency 0 */
    assert_int_equal(cu_xplane_rref_request(out, 413, 0, 7, "sim/time/zulu_time_sec"), 413);
    assert_int_equal(out[5] | out[6] | out[7] | out[8], 0);
    assert_int_equal(out[9], 7);

    /* refused, out untouched */
    char too_long[401];
    memset(too_long, 'a', 400);
    too_long[400] = 0;
    const char *bad_paths[] = {too_long, "", "sim/time\n", "sim/time zulu", "sim/\x7f", "sim/\xc3\xa9", NULL};
    for (size_t i = 0; i < sizeof bad_paths / sizeof *bad_paths; i++) {
        memset(out, 0x55, sizeof out);
        assert_int_equal(cu_xplane_rref_request(out, sizeof out, 10, 1, bad_paths[i]), 0);
        assert_int_equal(out[0], 0x55);
    }
    assert_int_equal(cu_xplane_rref_request(out, 412, 10, 1, path), 0);
    assert_int_equal(cu_xplane_rref_request(out, sizeof out, -1, 1, path), 0);
    assert_int_equal(cu_xplane_rref_request(out, sizeof out, 1001, 1, path), 0);
    assert_int_equal(cu_xplane_rref_request(NULL, 413, 10, 1, path), 0);
    assert_int_equal(out[0], 0x55);
}

static void check_time(const cu_sim_state *st, int y, int mo, int d, int h, int mi, double s)
{
    assert_int_equal(st->time_valid, 1);
    assert_int_equal(st->year, y);
    assert_int_equal(st->month, mo);
    assert_int_equal(st->day, d);
    assert_int_equal(st->hour, h);
    assert_int_equal(st->minute, mi);
    if (st->second != s)
        fail_msg("second %.9g, expected %.9g", st->second, s);
}

/* The recorded take-off; the expected values are the file's comments, as float32 (what the wire holds). */
static void test_stream(void **state)
{
    (void)state;
    static dgram d[16];
    int n = load_stream(d, 16);
    assert_int_equal(n, 7);
    cu_xplane_rx rx;
    cu_xplane_rx_init(&rx, 2024);
    cu_sim_state st;
    memset(&st, 0, sizeof st);
    char err[256];
    double fov = -1;
    for (int i = 0; i < n; i++) {
        st.changed = 0;
        if (cu_xplane_parse(&rx, d[i].b, d[i].len, &st, &fov, err, sizeof err))
            fail_msg("datagram %d: %s", i + 1, err);
        switch (i) {
        case 0: /* the view and the date: neither pose nor time */
            assert_int_equal(st.changed, 0);
            assert_int_equal(st.pose_valid, 0);
            assert_int_equal(st.time_valid, 0);
            assert_true(fov == 60);
            break;
        case 1: /* all ten at t = 0: KSEA, heading 160, 2024-06-21 19:30:00 UTC */
            assert_int_equal(st.changed, CU_SIM_POSE | CU_SIM_TIME);
            assert_int_equal(st.pose_valid, 1);
            assert_true(st.lat_deg == (double)47.4502f);
            assert_true(st.lon_deg == (double)-122.3088f);
            assert_true(st.alt_m == 131.0);
            assert_true(st.yaw_deg == 160.0);
            assert_true(st.pitch_deg == 0 && st.roll_deg == 0);
            check_time(&st, 2024, 6, 21, 19, 30, 0);
            break;
        case 2:
            check_time(&st, 2024, 6, 21, 19, 30, 2);
            assert_true(st.lat_deg < (double)47.4502f);   /* rolling south-south-east */
            break;
        case 3: /* two records of subscriptions not ours, skipped */
            assert_int_equal(rx.unknown, 2);
            assert_int_equal(st.changed, CU_SIM_POSE | CU_SIM_TIME);
            check_time(&st, 2024, 6, 21, 19, 30, 4);
            break;
        case 4: /* X-Plane 10's header */
            assert_true(st.pitch_deg == 2.5);
            check_time(&st, 2024, 6, 21, 19, 30, 6);
            break;
        case 5: /* time only */
            assert_int_equal(st.changed, CU_SIM_TIME);
            assert_true(st.pitch_deg == 2.5);
            check_time(&st, 2024, 6, 21, 19, 30, 7);
            break;
        case 6: /* pose only, a new field of view */
            assert_int_equal(st.changed, CU_SIM_POSE);
            assert_true(st.lat_deg == (double)47.4497f);
            assert_true(st.lon_deg == (double)-122.3085f);
            assert_true(st.alt_m == 133.5);
            assert_true(st.yaw_deg == 160.5 && st.pitch_deg == 6.5 && st.roll_deg == -1.5);
            assert_true(fov == 55);
            check_time(&st, 2024, 6, 21, 19, 30, 7);
            break;
        }
    }
    assert_int_equal(rx.datagrams, 7);
    assert_int_equal(rx.rejected, 0);
    assert_int_equal(rx.bad_values, 0);
    assert_int_equal(st.frustum_valid, 0);   /* the fov went out through its parameter */
}

/* Position and attitude take all six; time takes zulu seconds and the day of year. */
static void test_partial(void **state)
{
    (void)state;
    cu_xplane_rx rx;
    cu_xplane_rx_init(&rx, 2024);
    cu_sim_state st;
    memset(&st, 0, sizeof st);
    uint8_t b[256];
    char err[256];
    rec a[] = {{CU_XPLANE_LAT, 10}, {CU_XPLANE_LON, 20}, {CU_XPLANE_ELEV, 30}, {CU_XPLANE_ZULU_SEC, 3600}};
    assert_int_equal(cu_xplane_parse(&rx, b, build(b, "RREF,", a, 4), &st, NULL, err, sizeof err), 0);
    assert_int_equal(st.changed, 0);
    rec c[] = {{CU_XPLANE_HEADING, 1}, {CU_XPLANE_PITCH, 2}, {CU_XPLANE_ROLL, 3}, {CU_XPLANE_DATE_DAYS, 0}};
    assert_int_equal(cu_xplane_parse(&rx, b, build(b, "RREF,", c, 4), &st, NULL, err, sizeof err), 0);
    assert_int_equal(st.changed, CU_SIM_POSE | CU_SIM_TIME);
    assert_true(st.lat_deg == 10 && st.lon_deg == 20 && st.alt_m == 30);
    assert_true(st.yaw_deg == 1 && st.pitch_deg == 2 && st.roll_deg == 3);
    check_time(&st, 2024, 1, 1, 1, 0, 0);
    /* an empty reply is valid and changes nothing */
    st.changed = 0;
    assert_int_equal(cu_xplane_parse(&rx, b, build(b, "RREF,", NULL, 0), &st, NULL, err, sizeof err), 0);
    assert_int_equal(st.changed, 0);
    /* indices just past ours and at the ends of int32: unknown, counted, skipped */
    rec u[] = {{CU_XPLANE_REFS, 1}, {INT32_MAX, 2}, {INT32_MIN, 3}, {CU_XPLANE_LAT, 11}};
    st.changed = 0;
    assert_int_equal(cu_xplane_parse(&rx, b, build(b, "RREF,", u, 4), &st, NULL, err, sizeof err), 0);
    assert_int_equal(rx.unknown, 3);
    assert_int_equal(rx.datagrams, 4);
    assert_int_equal(st.changed, CU_SIM_POSE);
    assert_true(st.lat_deg == 11);
    /* no year: no time */
    cu_xplane_rx_init(&rx, 0);
    memset(&st, 0, sizeof st);
    rec t[] = {{CU_XPLANE_ZULU_SEC, 3600}, {CU_XPLANE_DATE_DAYS, 3}};
    assert_int_equal(cu_xplane_parse(&rx, b, build(b, "RREF,", t, 2), &st, NULL, err, sizeof err), 0);
    assert_int_equal(st.time_valid, 0);
}

/* Day of year with year, leap years, and the UTC date where X-Plane's local date differs from it. */
static void test_dates(void **state)
{
    (void)state;
    static const struct {
        int year; float doy, zulu, local; int has_local; int y, mo, d, h, mi; double s;
    } c[] = {
        {2024, 59, 0, 0, 0, 2024, 2, 29, 0, 0, 0},            /* day 59 of a leap year: February 29th */
        {2023, 59, 0, 0, 0, 2023, 3, 1, 0, 0, 0},
        {2024, 365, 0, 0, 0, 2024, 12, 31, 0, 0, 0},
        {2023, 365, 0, 0, 0, 2024, 1, 1, 0, 0, 0},            /* past the end of a 365-day year: the next */
        {2024, 172, 45296.5f, 0, 0, 2024, 6, 21, 12, 34, 56.5},
        {2024, 172, 86400, 0, 0, 2024, 6, 21, 23, 59, 86400 - 1e-3 - 23 * 3600 - 59 * 60},
        /* 01:00 UTC is 17:00 of the day before at UTC-8: the local date is a day behind */
        {2024, 172, 3600, 61200, 1, 2024, 6, 22, 1, 0, 0},
        /* 23:00 UTC is 08:00 of the next day at UTC+9: the local date is a day ahead */
        {2024, 173, 82800, 28800, 1, 2024, 6, 21, 23, 0, 0},
        {2024, 172, 70200, 45000, 1, 2024, 6, 21, 19, 30, 0},  /* UTC-7, the same day */
        {2023, 364, 3600, 61200, 1, 2024, 1, 1, 1, 0, 0},      /* New Year in UTC, New Year's Eve in Seattle */
        {2024, 0, 82800, 28800, 1, 2023, 12, 31, 23, 0, 0},    /* New Year in Tokyo, not yet in UTC */
    };
    for (size_t i = 0; i < sizeof c / sizeof *c; i++) {
        cu_xplane_rx rx;
        cu_xplane_rx_init(&rx, c[i].year);
        cu_sim_state st;
        memset(&st, 0, sizeof st);
        uint8_t b[64];
        char err[256];
        rec r[] = {{CU_XPLANE_DATE_DAYS, c[i].doy}, {CU_XPLANE_ZULU_SEC, c[i].zulu}, {CU_XPLANE_LOCAL_SEC, c[i].local}};
        if (cu_xplane_parse(&rx, b, build(b, "RREF,", r, c[i].has_local ? 3 : 2), &st, NULL, err, sizeof err))
            fail_msg("case %zu: %s", i, err);
        check_time(&st, c[i].y, c[i].mo, c[i].d, c[i].h, c[i].mi, c[i].s);
    }
}

/* Each bad datagram: refused and counted, the message naming the record and dataref, nothing of st or rx's values
 * changed; the next good one applies. */
static void test_hostile(void **state)
{
    (void)state;
    const rec good[] = {{0, 47.5f}, {1, -122.25f}, {2, 100}, {3, 90}, {4, 1}, {5, 2}, {6, 3600}, {8, 10}, {9, 70}};
    static const struct { const char *hdr; rec r[4]; size_t n; size_t cut; const char *frag; } bad[] = {
        {"RREX,", {{0, 1}}, 1, 0, "header 52 52 45 58 2c is not \"RREF,\""},
        {"rref,", {{0, 1}}, 1, 0, "header 72 72 65 66 2c"},
        {"RREF\0", {{0, 1}}, 1, 0, "header 52 52 45 46 00"},
        {"RREF\x1b", {{0, 1}}, 1, 0, "header 52 52 45 46 1b"},
        {"RREF,", {{0, 1}}, 1, 1, "record 1 is cut short (7 of 8 bytes)"},
        {"RREF,", {{0, 1}, {1, 2}}, 2, 5, "record 2 is cut short (3 of 8 bytes)"},
        {"RREF,", {{0, 1}}, 1, 4, "record 1 is cut short (4 of 8 bytes)"},
        {"RREF,", {{0, 0}}, 1, 12, "shorter than the 5-byte header"},
        {"RREF,", {{0, 0}}, 1, 13, "a datagram of 0 bytes"},
        {"RREF,", {{1, 5}, {0, 0}}, 2, 0, "record 2 (index 0, sim/flightmodel/position/latitude): nan is not a finite"},
        {"RREF,", {{2, 0}}, 1, 0, "record 1 (index 2, sim/flightmodel/position/elevation): inf is not a finite"},
        {"RREF,", {{2, 0}}, 1, 0, "record 1 (index 2, sim/flightmodel/position/elevation): -inf is not a finite"},
        {"RREF,", {{1, 1e30f}}, 1, 0, "record 1 (index 1, sim/flightmodel/position/longitude): 1.00000002e+30 is out"},
        {"RREF,", {{0, 90.5f}}, 1, 0, "(index 0, sim/flightmodel/position/latitude): 90.5 is out of range (-90..90)"},
        {"RREF,", {{3, 1e4f}, {4, -10001}}, 2, 0, "record 2 (index 4, sim/flightmodel/position/true_theta)"},
        {"RREF,", {{6, -1}}, 1, 0, "(index 6, sim/time/zulu_time_sec): -1 is out of range (0..86400)"},
        {"RREF,", {{8, 100.5f}}, 1, 0, "(index 8, sim/time/local_date_days): 100.5 is not a whole number"},
        {"RREF,", {{8, 366}}, 1, 0, "(index 8, sim/time/local_date_days): 366 is out of range"},
        {"RREF,", {{9, 0.5f}}, 1, 0, "(index 9, sim/graphics/view/field_of_view_deg): 0.5 is out of range"},
        {"RREF,", {{57, 1}, {-1, 2}, {0, 0}, {1, 1}}, 4, 0, "record 3 (index 0"},
    };
    cu_xplane_rx rx;
    cu_xplane_rx_init(&rx, 2024);
    cu_sim_state st, before;
    memset(&st, 0, sizeof st);
    uint8_t b[512];
    char err[256];
    assert_int_equal(cu_xplane_parse(&rx, b, build(b, "RREF,", good, 9), &st, NULL, err, sizeof err), 0);
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        rec r[4];
        memcpy(r, bad[i].r, sizeof r);
        if (i == 9)    /* the table cannot hold these as constants */
            r[1].v = NAN;
        if (i == 10)
            r[0].v = INFINITY;
        if (i == 11)
            r[0].v = -INFINITY;
        if (i == 19)
            r[2].v = NAN;
        size_t len = build(b, bad[i].hdr, r, bad[i].n) - bad[i].cut;
        st.changed = 0;
        memcpy(&before, &st, sizeof st);
        double vals[CU_XPLANE_REFS];
        memcpy(vals, rx.val, sizeof vals);
        unsigned have = rx.have;
        unsigned long rejected = rx.rejected, accepted = rx.datagrams;
        double fov = -7;
        memset(err, 0, sizeof err);
        if (cu_xplane_parse(&rx, b, len, &st, &fov, err, sizeof err) != -1)
            fail_msg("case %zu accepted", i);
        if (!strstr(err, bad[i].frag))
            fail_msg("case %zu: message '%s' lacks '%s'", i, err, bad[i].frag);
        assert_true(strncmp(err, "xplane: ", 8) == 0);
        assert_printable(err);
        assert_memory_equal(&st, &before, sizeof st);
        assert_memory_equal(vals, rx.val, sizeof vals);
        assert_int_equal(rx.have, have);
        assert_int_equal(rx.rejected, rejected + 1);
        assert_int_equal(rx.datagrams, accepted);
        assert_true(fov == -7);
        /* the next good datagram applies */
        rec next[] = {{0, (float)i}, {9, 60}};
        assert_int_equal(cu_xplane_parse(&rx, b, build(b, "RREF,", next, 2), &st, &fov, err, sizeof err), 0);
        assert_true(st.lat_deg == (double)i);
        assert_int_equal(st.changed, CU_SIM_POSE);
        assert_true(fov == 60);
    }
    assert_int_equal(rx.bad_values, 11);
    assert_int_equal(rx.unknown, 0);   /* case 19's unknown records were in a refused datagram */
    /* no buffer, a tiny message buffer, no receiver */
    assert_int_equal(cu_xplane_parse(&rx, NULL, 0, &st, NULL, err, sizeof err), -1);
    memset(err, 'x', sizeof err);
    assert_int_equal(cu_xplane_parse(&rx, b, 3, &st, NULL, err, 6), -1);
    assert_int_equal(strlen(err), 5);
    assert_int_equal(err[6], 'x');
    assert_int_equal(cu_xplane_parse(&rx, b, 3, &st, NULL, NULL, 0), -1);
    assert_int_equal(cu_xplane_parse(NULL, b, 3, &st, NULL, err, sizeof err), -1);
    /* a request fed back to the parser (X-Plane echoes nothing, but a loop-back might) is refused by its NUL */
    assert_int_equal(cu_xplane_rref_request(b, sizeof b, 5, 0, "sim/time/zulu_time_sec"), 413);
    assert_int_equal(cu_xplane_parse(&rx, b, 413, &st, NULL, err, sizeof err), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_table), cmocka_unit_test(test_request), cmocka_unit_test(test_stream),
        cmocka_unit_test(test_partial), cmocka_unit_test(test_dates), cmocka_unit_test(test_hostile),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
