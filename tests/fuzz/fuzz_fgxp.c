/* tests/fuzz/fuzz_fgxp.c: libFuzzer target for the FlightGear line and X-Plane RREF decoders (platform/sim/). */
#include "fuzz.h"
#include "fgfs.h"
#include "xplane.h"
#include <math.h>

static void check_printable(const char *err)
{
    for (const char *p = err; *p; p++)
        FUZZ_CHECK((unsigned char)*p >= 0x20 && (unsigned char)*p < 0x7f, "byte 0x%02x in '%s'", (unsigned char)*p,
                   err);
}

static int leap(int y)
{
    return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
}

/* Every number of the state finite, and what a decoder set within the ranges the headers promise. */
static void check_state(const cu_sim_state *st, double max_second)
{
    const double *d[] = {&st->lat_deg, &st->lon_deg, &st->alt_m, &st->yaw_deg, &st->pitch_deg, &st->roll_deg,
                         &st->view_xyz[0], &st->view_xyz[1], &st->view_xyz[2], &st->view_yaw_deg,
                         &st->view_pitch_deg, &st->view_roll_deg, &st->fov_left_deg, &st->fov_right_deg,
                         &st->fov_top_deg, &st->fov_bottom_deg, &st->near_m, &st->far_m, &st->second,
                         &st->wind_speed, &st->wind_from_deg};
    for (size_t i = 0; i < sizeof d / sizeof *d; i++)
        FUZZ_CHECK(isfinite(*d[i]), "state number %zu is %g", i, *d[i]);
    FUZZ_CHECK((st->changed & ~(unsigned)(CU_SIM_POSE | CU_SIM_TIME)) == 0, "changed bits 0x%x", st->changed);
    FUZZ_CHECK(!st->frustum_valid && !st->wind_valid, "a decoder set the frustum or the wind");
    if (st->pose_valid) {
        FUZZ_CHECK(fabs(st->lat_deg) <= 90 && fabs(st->lon_deg) <= 180, "position %.17g %.17g", st->lat_deg,
                   st->lon_deg);
        FUZZ_CHECK(st->alt_m >= -1e4 && st->alt_m <= 1e6, "altitude %.17g", st->alt_m);
        FUZZ_CHECK(fabs(st->yaw_deg) <= 1e4 && fabs(st->pitch_deg) <= 1e4 && fabs(st->roll_deg) <= 1e4,
                   "attitude %g %g %g", st->yaw_deg, st->pitch_deg, st->roll_deg);
    }
    if (st->time_valid) {
        static const int mdays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
        FUZZ_CHECK(st->year >= 1 && st->year <= 9999 && st->month >= 1 && st->month <= 12, "date %d-%d", st->year,
                   st->month);
        int dim = mdays[st->month - 1] + (st->month == 2 && leap(st->year));
        FUZZ_CHECK(st->day >= 1 && st->day <= dim, "date %d-%02d-%02d", st->year, st->month, st->day);
        FUZZ_CHECK(st->hour >= 0 && st->hour <= 23 && st->minute >= 0 && st->minute <= 59, "time %d:%d", st->hour,
                   st->minute);
        FUZZ_CHECK(st->second >= 0 && st->second < max_second, "second %.17g", st->second);
    }
}

/* The first byte: bit 0 picks the protocol (0 FlightGear, 1 X-Plane); for X-Plane, bit 1 first feeds a datagram
 * holding every dataref (so that the rest merges with a full set), bits 2-3 pick the year (2024, 0, 1, 9999: no
 * year, and the ends where New Year moves out of range). The rest is the datagram. */
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    uint8_t mode = data[0];
    data++, size--;
    cu_sim_state st, before;
    memset(&st, 0, sizeof st);
    char err[256];
    double fov = -1, fov_before;

    if (!(mode & 1)) {
        memset(err, 0, sizeof err);
        memcpy(&before, &st, sizeof st);
        if (cu_fgfs_parse((const char *)data, size, &st, &fov, err, sizeof err)) {
            FUZZ_CHECK_MESSAGE(err, "fgfs: ");
            check_printable(err);
            FUZZ_CHECK(!memcmp(&st, &before, sizeof st), "a refused line changed the state");
            FUZZ_CHECK(fov == -1, "a refused line set the field of view");
            return 0;
        }
        FUZZ_CHECK(st.changed == (CU_SIM_POSE | CU_SIM_TIME) && st.pose_valid && st.time_valid, "changed 0x%x",
                   st.changed);
        FUZZ_CHECK(fov >= 1 && fov <= 179, "field of view %.17g", fov);
        check_state(&st, 61);
        return 0;
    }

    static const int years[4] = {2024, 0, 1, 9999};
    cu_xplane_rx rx;
    cu_xplane_rx_init(&rx, years[(mode >> 2) & 3]);
    unsigned long calls = 0;
    if (mode & 2) {
        static const float v[CU_XPLANE_REFS] = {47.5f, -122.25f, 100, 90, 1, 2, 1800, 45000, 0, 70};
        uint8_t b[5 + 8 * CU_XPLANE_REFS];
        memcpy(b, "RREF,", 5);
        for (int i = 0; i < CU_XPLANE_REFS; i++) {
            uint32_t f;
            memcpy(&f, &v[i], 4);
            for (int k = 0; k < 4; k++)
                b[5 + 8 * i + k] = (uint8_t)((uint32_t)i >> (8 * k)), b[9 + 8 * i + k] = (uint8_t)(f >> (8 * k));
        }
        FUZZ_CHECK(cu_xplane_parse(&rx, b, sizeof b, &st, &fov, err, sizeof err) == 0, "the full set: %s", err);
        calls++;
        check_state(&st, 60);
    }
    memcpy(&before, &st, sizeof st);
    fov_before = fov;
    cu_xplane_rx rx_before = rx;
    memset(err, 0, sizeof err);
    st.changed = 0;
    before.changed = 0;
    int rc = cu_xplane_parse(&rx, data, size, &st, &fov, err, sizeof err);
    calls++;
    FUZZ_CHECK(rx.datagrams + rx.rejected == calls, "%lu accepted + %lu refused of %lu", rx.datagrams, rx.rejected,
               calls);
    if (rc) {
        FUZZ_CHECK(rc == -1, "returned %d", rc);
        FUZZ_CHECK_MESSAGE(err, "xplane: ");
        check_printable(err);
        FUZZ_CHECK(!memcmp(&st, &before, sizeof st), "a refused datagram changed the state");
        FUZZ_CHECK(!memcmp(rx.val, rx_before.val, sizeof rx.val) && rx.have == rx_before.have,
                   "a refused datagram changed the values");
        FUZZ_CHECK(fov == fov_before, "a refused datagram set the field of view");
        return 0;
    }
    FUZZ_CHECK(size >= 5 && (size - 5) % 8 == 0, "accepted %zu bytes", size);
    FUZZ_CHECK(rx.unknown - rx_before.unknown <= (size - 5) / 8, "unknown count");
    FUZZ_CHECK(fov == -1 || (fov >= 1 && fov <= 179), "field of view %.17g", fov);
    check_state(&st, 60);
    return 0;
}
