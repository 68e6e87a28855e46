/* tests/sim/test_fgfs.c: FlightGear generic-protocol lines: the XML against the decoder's table, a recorded climb
 * out of KSFO (tests/sim/data/fgfs_stream.txt, one datagram per line, as cumulo.xml makes fgfs print them), line
 * endings, and hostile datagrams, each refused with the field named and the state left as it was. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "fgfs.h"

#define STREAM "tests/sim/data/fgfs_stream.txt"
#define XML "data/flightgear/cumulo.xml"
#define LIT(s) s, sizeof(s) - 1   /* a literal with a NUL inside, and its length */
#define LINE1 "37.61890000,-122.37500000,3.962,297.500,0.000,0.000,2024,6,21,19,30,0,55.000"

static char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        fail_msg("cannot open %s (run from the top of the tree)", path);
    static char buf[65536];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = 0;
    *len = n;
    return buf;
}

/* A state with every field set to something a decoder would not write, so that a stray write shows. */
static void sentinel(cu_sim_state *st)
{
    memset(st, 0, sizeof *st);
    st->view_xyz[0] = 1.5, st->view_yaw_deg = 7;
    st->frustum_valid = 1, st->fov_left_deg = -30, st->fov_right_deg = 30, st->fov_top_deg = 20;
    st->fov_bottom_deg = -20, st->near_m = 0.5, st->far_m = 9000;
    st->wind_valid = 1, st->wind_speed = 4, st->wind_from_deg = 270;
    st->layers[1].enabled = 1, st->layers[1].base_m = 1500;
}

static int parse_str(const char *s, cu_sim_state *st, double *fov, char *err, size_t errlen)
{
    return cu_fgfs_parse(s, strlen(s), st, fov, err, errlen);
}

static void assert_printable(const char *err)
{
    for (const char *p = err; *p; p++)
        if ((unsigned char)*p < 0x20 || (unsigned char)*p >= 0x7f)
            fail_msg("byte 0x%02x in message '%s'", (unsigned char)*p, err);
}

/* The XML's chunk names, in order, are the decoder's fields; the altitude goes out in metres through <factor>. */
static void test_xml_matches_table(void **state)
{
    (void)state;
    size_t len;
    const char *x = slurp(XML, &len);
    const char *p = strstr(x, "<output>");
    assert_non_null(p);
    int n = 0;
    while ((p = strstr(p, "<chunk>")) != NULL) {
        const char *end = strstr(p, "</chunk>"), *name = strstr(p, "<name>");
        assert_non_null(end);
        assert_true(name && name < end);
        name += strlen("<name>");
        const char *stop = strstr(name, "</name>");
        char got[64];
        snprintf(got, sizeof got, "%.*s", (int)(stop - name), name);
        assert_true(n < CU_FGFS_FIELDS);
        assert_string_equal(got, cu_fgfs_field_name(n));
        char chunk[1024];
        snprintf(chunk, sizeof chunk, "%.*s", (int)(end - p), p);
        if (n == CU_FGFS_ALT) {
            assert_non_null(strstr(chunk, "<node>/position/altitude-ft</node>"));
            assert_non_null(strstr(chunk, "<factor>0.3048</factor>"));
        }
        if (n <= CU_FGFS_ROLL || n == CU_FGFS_FOV) /* a float chunk would print latitude through a C float */
            assert_non_null(strstr(chunk, "<type>double</type>"));
        n++;
        p = end;
    }
    assert_int_equal(n, CU_FGFS_FIELDS);
    assert_non_null(strstr(x, "<line_separator>newline</line_separator>"));
    assert_non_null(strstr(x, "<var_separator>,</var_separator>"));
    assert_null(cu_fgfs_field_name(-1));
    assert_null(cu_fgfs_field_name(CU_FGFS_FIELDS));
    assert_string_equal(cu_fgfs_field_name(2), "altitude-m");
}

static void check_time(const cu_sim_state *st, int y, int mo, int d, int h, int mi, double s)
{
    assert_int_equal(st->time_valid, 1);
    assert_int_equal(st->year, y);
    assert_int_equal(st->month, mo);
    assert_int_equal(st->day, d);
    assert_int_equal(st->hour, h);
    assert_int_equal(st->minute, mi);
    assert_true(st->second == s);
}

/* The recorded stream, one datagram per line with its newline; values checked against the numbers of the lines. */
static void test_stream(void **state)
{
    (void)state;
    size_t len;
    char *s = slurp(STREAM, &len);
    cu_sim_state st, untouched;
    sentinel(&st);
    sentinel(&untouched);
    int n = 0;
    for (char *line = s; *line; n++) {
        char *nl = strchr(line, '\n');
        assert_non_null(nl);
        char err[256] = "";
        double fov = -1;
        st.changed = 0;
        if (cu_fgfs_parse(line, (size_t)(nl + 1 - line), &st, &fov, err, sizeof err))
            fail_msg("line %d: %s", n + 1, err);
        assert_int_equal(st.changed, CU_SIM_POSE | CU_SIM_TIME);
        assert_int_equal(st.pose_valid, 1);
        assert_true(fov == 55.0);
        if (n == 0) { /* 37.61890000,-122.37500000,3.962,297.500,0.000,0.000,2024,6,21,19,30,0,55.000 */
            assert_true(st.lat_deg == 37.6189);
            assert_true(st.lon_deg == -122.375);
            assert_true(st.alt_m == 3.962);
            assert_true(st.yaw_deg == 297.5);
            assert_true(st.pitch_deg == 0 && st.roll_deg == 0);
            check_time(&st, 2024, 6, 21, 19, 30, 0);
        } else if (n == 7) { /* the line printed with %f: six decimals everywhere */
            assert_true(st.lat_deg == 37.6259);
            assert_true(st.lon_deg == -122.391976);
            assert_true(st.alt_m == 78.962);
            assert_true(st.pitch_deg == 8.0);
            check_time(&st, 2024, 6, 21, 19, 30, 35);
        } else if (n == 12) { /* the last: a minute later, climbing and banking left */
            assert_true(st.lat_deg == 37.63367703);
            assert_true(st.lon_deg == -122.41083744);
            assert_true(st.alt_m == 266.462);
            assert_true(st.roll_deg == -5.0);
            check_time(&st, 2024, 6, 21, 19, 31, 0);
        }
        line = nl + 1;
    }
    assert_int_equal(n, 13);
    /* nothing but pose, time and their flags changed */
    untouched.changed = st.changed;
    untouched.pose_valid = 1, untouched.time_valid = 1;
    untouched.lat_deg = st.lat_deg, untouched.lon_deg = st.lon_deg, untouched.alt_m = st.alt_m;
    untouched.yaw_deg = st.yaw_deg, untouched.pitch_deg = st.pitch_deg, untouched.roll_deg = st.roll_deg;
    untouched.year = st.year, untouched.month = st.month, untouched.day = st.day;
    untouched.hour = st.hour, untouched.minute = st.minute, untouched.second = st.second;
    assert_memory_equal(&st, &untouched, sizeof st);
}

/* CRLF, no newline at all, blank lines after, several lines in one datagram (the last counts), blanks around. */
static void test_line_endings(void **state)
{
    (void)state;
    cu_sim_state st;
    char err[256];
    const char *ok[] = {LINE1 "\r\n", LINE1, LINE1 "\n\n\r\n",
                        "1,2,3,4,5,6,2020,1,1,0,0,0,60\n" LINE1 "\n",
                        "garbage\n" LINE1,
                        " 37.6189, -122.375 ,\t3.962,297.5,0,0,2024,6,21,19,30,0,55",
                        "+37.6189,-122.375,3.962e0,297.5,.0,0.,2024,6,21,19,30,0.0,55.000"};
    for (size_t i = 0; i < sizeof ok / sizeof *ok; i++) {
        sentinel(&st);
        double fov = 0;
        if (parse_str(ok[i], &st, &fov, err, sizeof err))
            fail_msg("case %zu: %s", i, err);
        assert_true(st.lat_deg == 37.6189);
        assert_true(st.alt_m == 3.962);
        assert_true(fov == 55);
        check_time(&st, 2024, 6, 21, 19, 30, 0);
    }
    /* the last line is the one decoded even when an earlier one is bad, and a bad last line is not rescued */
    sentinel(&st);
    assert_int_equal(parse_str(LINE1 "\nabc\n", &st, NULL, err, sizeof err), -1);
    assert_int_equal(st.pose_valid, 0);
}

/* Boundaries that are valid: the edges of each range, leap days, a leap second. */
static void test_boundaries(void **state)
{
    (void)state;
    const char *ok[] = {
        "90,180,-10000,10000,-10000,10000,2024,2,29,23,59,60.999,179",
        "-90,-180,1000000,0,0,0,2000,2,29,0,0,0,1",
        "0,0,0,0,0,0,1,1,1,0,0,0,90",
        "0,0,0,0,0,0,9999,12,31,0,0,0,90",
    };
    for (size_t i = 0; i < sizeof ok / sizeof *ok; i++) {
        cu_sim_state st;
        char err[256];
        sentinel(&st);
        if (parse_str(ok[i], &st, NULL, err, sizeof err))
            fail_msg("'%s': %s", ok[i], err);
    }
}

/* Each bad datagram: refused, the message naming the field, no control byte in it, nothing changed; then a good
 * line still applies. */
static void test_hostile(void **state)
{
    (void)state;
    static char overlong[700];
    memset(overlong, '1', sizeof overlong - 1);
    static const struct { const char *dgram; size_t len; const char *frag; } bad[] = {
        {"", 0, "empty datagram"},
        {"\r\n", 2, "empty datagram"},
        {"37.61890000,-122.37500000,3.96", 30, "field 4 (heading-deg) is missing"},
        {"37.6189,-122.375,3.962,297.5,0,0,2024,6,21,19,30,0\n", 0, "field 13 (field-of-view-deg) is missing"},
        {LINE1 ",1\n", 0, "field 14 is extra"},
        {"37.6189,-122.375,abc,297.5,0,0,2024,6,21,19,30,0,55", 0, "field 3 (altitude-m): 'abc' is not a number"},
        {"37.6189,,3.962,297.5,0,0,2024,6,21,19,30,0,55", 0, "field 2 (longitude-deg) is empty"},
        {"nan,-122.375,3.962,297.5,0,0,2024,6,21,19,30,0,55", 0, "field 1 (latitude-deg): 'nan' is not a number"},
        {"37.6,-122.375,inf,297.5,0,0,2024,6,21,19,30,0,55", 0, "field 3 (altitude-m): 'inf' is not a number"},
        {"37.6,-122.375,3,-INF,0,0,2024,6,21,19,30,0,55", 0, "field 4 (heading-deg): '-INF' is not a number"},
        {"37.6,-122.375,3,0x1p3,0,0,2024,6,21,19,30,0,55", 0, "field 4 (heading-deg): '0x1p3' is not a number"},
        {"37.6,-122.375,3,1.2.3,0,0,2024,6,21,19,30,0,55", 0, "field 4 (heading-deg): '1.2.3' is not a number"},
        {"37.6,-122.375,3,1e,0,0,2024,6,21,19,30,0,55", 0, "field 4 (heading-deg): '1e' is not a number"},
        {"37.6,-122.375,3,.,0,0,2024,6,21,19,30,0,55", 0, "field 4 (heading-deg): '.' is not a number"},
        {"37.6,-122.375,1e400,0,0,0,2024,6,21,19,30,0,55", 0, "field 3 (altitude-m): '1e400' is out of range"},
        {"90.000001,-122.375,3,0,0,0,2024,6,21,19,30,0,55", 0, "field 1 (latitude-deg): '90.000001' is out of range"},
        {"37.6,-180.5,3,0,0,0,2024,6,21,19,30,0,55", 0, "field 2 (longitude-deg): '-180.5' is out of range"},
        {"37.6,-122.375,-10001,0,0,0,2024,6,21,19,30,0,55", 0, "field 3 (altitude-m)"},
        {"37.6,-122.375,3,0,1e5,0,2024,6,21,19,30,0,55", 0, "field 5 (pitch-deg): '1e5' is out of range"},
        {"37.6,-122.375,3,0,0,-10000.5,2024,6,21,19,30,0,55", 0, "field 6 (roll-deg)"},
        {"37.6,-122.375,3,0,0,0,2024.5,6,21,19,30,0,55", 0, "field 7 (year): '2024.5' is not a whole number"},
        {"37.6,-122.375,3,0,0,0,0,6,21,19,30,0,55", 0, "field 7 (year): '0' is out of range"},
        {"37.6,-122.375,3,0,0,0,2024,13,21,19,30,0,55", 0, "field 8 (month): '13' is out of range"},
        {"37.6,-122.375,3,0,0,0,2024,0,21,19,30,0,55", 0, "field 8 (month)"},
        {"37.6,-122.375,3,0,0,0,2024,4,31,19,30,0,55", 0, "field 9 (day): 31 is not a day of 2024-04"},
        {"37.6,-122.375,3,0,0,0,2023,2,29,19,30,0,55", 0, "field 9 (day): 29 is not a day of 2023-02"},
        {"37.6,-122.375,3,0,0,0,1900,2,29,19,30,0,55", 0, "field 9 (day): 29 is not a day of 1900-02"},
        {"37.6,-122.375,3,0,0,0,2024,6,0,19,30,0,55", 0, "field 9 (day): '0' is out of range"},
        {"37.6,-122.375,3,0,0,0,2024,6,21,24,30,0,55", 0, "field 10 (hour): '24' is out of range"},
        {"37.6,-122.375,3,0,0,0,2024,6,21,19,60,0,55", 0, "field 11 (minute): '60' is out of range"},
        {"37.6,-122.375,3,0,0,0,2024,6,21,19,30,61,55", 0, "field 12 (second): '61' is out of range"},
        {"37.6,-122.375,3,0,0,0,2024,6,21,19,30,-0.5,55", 0, "field 12 (second)"},
        {"37.6,-122.375,3,0,0,0,2024,6,21,19,30,0,0.5", 0, "field 13 (field-of-view-deg): '0.5' is out of range"},
        {"37.6,-122.375,3,0,0,0,2024,6,21,19,30,0,180", 0, "field 13 (field-of-view-deg): '180' is out of range"},
        {"37.6\x1b[31m,-122.375,3,0,0,0,2024,6,21,19,30,0,55", 0, "field 1 (latitude-deg): '37.6\\x1b[31m'"},
        {"37.6,-122.375,3,0\r,0,0,2024,6,21,19,30,0,55", 0, "field 4 (heading-deg): '0\\x0d'"},
        {"37.6,-12'2\\,3,0,0,0,2024,6,21,19,30,0,55", 0, "field 2 (longitude-deg): '-12\\x272\\x5c'"},
        {"37.6,-122.375,3,0,0,0,2024,6,21,19,30,0,\xff\xfe", 0, "field 13 (field-of-view-deg): '\\xff\\xfe'"},
        {LIT("37.6,-122.375,3,0,0,0,2024,6\0,21,19,30,0,55"), "field 8 (month): '6\\x00'"},
        {"37.6,-122.375,00000000000000000000000000000000000000000000000000003,0,0,0,2024,6,21,19,30,0,55", 0,
         "field 3 (altitude-m): '000000000000000000000000...' is not a number"},
        {overlong, 0, "a line of 699 bytes, longer than 512"},
    };
    cu_sim_state st, before;
    sentinel(&st);
    char err[256];
    assert_int_equal(parse_str(LINE1, &st, NULL, err, sizeof err), 0);
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        size_t len = bad[i].len ? bad[i].len : strlen(bad[i].dgram);
        st.changed = 0;
        memcpy(&before, &st, sizeof st);   /* not `before = st`: padding bytes too */
        double fov = -7;
        memset(err, 0, sizeof err);
        if (cu_fgfs_parse(bad[i].dgram, len, &st, &fov, err, sizeof err) != -1)
            fail_msg("case %zu accepted", i);
        if (!strstr(err, bad[i].frag))
            fail_msg("case %zu: message '%s' lacks '%s'", i, err, bad[i].frag);
        assert_true(strncmp(err, "fgfs: ", 6) == 0);
        assert_printable(err);
        assert_memory_equal(&st, &before, sizeof st);
        assert_true(fov == -7);
        /* and the next valid datagram applies */
        char good[128];
        snprintf(good, sizeof good, "%d,-122.375,3.962,297.5,0,0,2024,6,21,19,30,%zu,55\n", (int)(i % 80), i % 60);
        assert_int_equal(parse_str(good, &st, &fov, err, sizeof err), 0);
        assert_true(st.lat_deg == (double)(i % 80));
        assert_true(st.second == (double)(i % 60));
        assert_true(fov == 55);
    }
}

/* A small message buffer is filled and terminated, never overrun; no buffer at all is fine too. */
static void test_err_buffer(void **state)
{
    (void)state;
    cu_sim_state st;
    sentinel(&st);
    char err[12];
    memset(err, 'x', sizeof err);
    assert_int_equal(cu_fgfs_parse("abc", 3, &st, NULL, err, 8), -1);
    assert_int_equal(strlen(err), 7);
    assert_int_equal(err[8], 'x');
    assert_int_equal(cu_fgfs_parse("abc", 3, &st, NULL, NULL, 0), -1);
    assert_int_equal(cu_fgfs_parse(NULL, 0, &st, NULL, err, sizeof err), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_xml_matches_table), cmocka_unit_test(test_stream), cmocka_unit_test(test_line_endings),
        cmocka_unit_test(test_boundaries), cmocka_unit_test(test_hostile), cmocka_unit_test(test_err_buffer),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
