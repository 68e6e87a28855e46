/* tests/platform/test_clock.c: `cumulo run --clock`'s arithmetic: the knob's offset of the time of day (steps,
 * acceleration, reset, limits), the time shown from the clocks, and the ISO 8601 and offset texts of the log lines. */
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <string.h>
#include <time.h>
#include <cmocka.h>
#include "clock_control.h"

static void test_offset_by_knob_keys_and_commands(void **state)
{
    (void)state;
    cu_clock_ctl c;
    cu_clock_ctl_init(&c);
    assert_true(c.step_s == 600.0 && c.scale == 1.0 && c.shift_s == 0.0 && c.offset_s == 0.0);
    c.speed.accel = 0;
    cu_action t = { .kind = CU_ACT_TURN, .detents = 3 };
    assert_int_equal(cu_clock_ctl_apply(&c, &t), 1);
    assert_true(c.offset_s == 1800.0);                      /* 10 minutes a detent */
    cu_action left = { .kind = CU_ACT_TURN_AZ, .detents = -1 };
    cu_clock_ctl_apply(&c, &left);
    assert_true(c.offset_s == 1200.0);
    cu_action up = { .kind = CU_ACT_TURN_EL, .detents = 1 };
    cu_clock_ctl_apply(&c, &up);
    assert_true(c.offset_s == 4800.0);                      /* up/down: an hour */
    cu_action zero = { .kind = CU_ACT_TURN, .detents = 0 };
    assert_int_equal(cu_clock_ctl_apply(&c, &zero), 0);
    cu_action button = { .kind = CU_ACT_TOGGLE };
    assert_int_equal(cu_clock_ctl_apply(&c, &button), 1);
    assert_true(c.offset_s == 0.0);                         /* the button: back to the clock itself */
    assert_int_equal(cu_clock_ctl_apply(&c, &button), 0);   /* already there: nothing to redo */
    cu_action set = { .kind = CU_ACT_SET_OFFSET, .minutes = 90 };
    assert_int_equal(cu_clock_ctl_apply(&c, &set), 1);
    assert_true(c.offset_s == 5400.0);
    assert_int_equal(cu_clock_ctl_apply(&c, &set), 0);
    /* the angles are not the clock's: nothing changes */
    cu_action sun = { .kind = CU_ACT_SET_SUN, .el = 10, .az = 20 };
    assert_int_equal(cu_clock_ctl_apply(&c, &sun), 0);
    assert_true(c.offset_s == 5400.0);
    /* a day either way, then the knob stops */
    cu_action spin = { .kind = CU_ACT_TURN, .detents = 10000 };
    cu_clock_ctl_apply(&c, &spin);
    assert_true(c.offset_s == CU_OFFSET_MAX_MIN * 60.0);
    assert_int_equal(cu_clock_ctl_apply(&c, &spin), 0);
    spin.detents = -100000;
    cu_clock_ctl_apply(&c, &spin);
    assert_true(c.offset_s == -CU_OFFSET_MAX_MIN * 60.0);
    /* whole seconds, and never -0 (it would print as "-0min") */
    set.minutes = 0.5 / 60.0 + 1e-9;
    cu_clock_ctl_apply(&c, &set);
    assert_true(c.offset_s == 1.0);
    set.minutes = -0.4 / 60.0;
    cu_clock_ctl_apply(&c, &set);
    assert_true(c.offset_s == 0.0 && !signbit(c.offset_s));
    /* --step 2.5 (minutes) */
    c.step_s = 150;
    t.detents = -2;
    cu_clock_ctl_apply(&c, &t);
    assert_true(c.offset_s == -300.0);
}

static void test_offset_acceleration(void **state)
{
    (void)state;
    cu_clock_ctl c;
    cu_clock_ctl_init(&c);
    /* The knob's curve, as for the angles: the first turn is exact, one 50 ms later (20 detents/s) five times the
     * step, one after a pause of seconds exact again. */
    cu_action a = { .kind = CU_ACT_TURN, .detents = 1, .t_ns = 1000000000u };
    cu_clock_ctl_apply(&c, &a);
    assert_true(c.offset_s == 600.0);
    a.t_ns += 50000000u;
    cu_clock_ctl_apply(&c, &a);
    assert_true(c.offset_s == 600.0 + 3000.0);
    a.t_ns += 3000000000u;
    cu_clock_ctl_apply(&c, &a);
    assert_true(c.offset_s == 4200.0);
}

static void test_time_shown(void **state)
{
    (void)state;
    cu_clock_ctl c;
    cu_clock_ctl_init(&c);
    double wall = 1782043200.0; /* 2026-06-21T12:00:00Z */
    /* scale 1: the wall clock itself, whatever the monotonic time says */
    assert_true(cu_clock_ctl_shown(&c, wall, 0.0) == wall);
    assert_true(cu_clock_ctl_shown(&c, wall + 10.0, 10.0) == wall + 10.0);
    /* NTP steps the wall clock: the time shown follows the step */
    assert_true(cu_clock_ctl_shown(&c, wall + 310.0, 10.0) == wall + 310.0);
    /* --time-scale 3600: an hour a second of the monotonic clock */
    c.scale = 3600;
    assert_true(cu_clock_ctl_shown(&c, wall + 2.0, 2.0) == wall + 7200.0);
    /* --clock-offset and the knob's offset add */
    c.scale = 1;
    c.shift_s = -21600;
    c.offset_s = 5400;
    assert_true(cu_clock_ctl_shown(&c, wall, 123.0) == wall - 16200.0);
}

static void utc_is(double t, const char *want)
{
    char buf[32];
    assert_int_equal(cu_clock_format_utc(t, buf, sizeof buf), 0);
    assert_string_equal(buf, want);
}

static void test_formats(void **state)
{
    (void)state;
    utc_is(0.0, "1970-01-01T00:00:00Z");
    utc_is(1782043200.0, "2026-06-21T12:00:00Z");
    utc_is(1782043200.999, "2026-06-21T12:00:00Z");       /* rounded down: the second it is */
    utc_is(1709251199.0, "2024-02-29T23:59:59Z");
    utc_is(-1.5, "1969-12-31T23:59:58Z");
    if (sizeof(time_t) >= 8) {
        utc_is(-2208988800.0, "1900-01-01T00:00:00Z");
        utc_is(4133980799.0, "2100-12-31T23:59:59Z");
    }
    char buf[32];
    assert_int_not_equal(cu_clock_format_utc(1e13, buf, sizeof buf), 0);
    assert_int_not_equal(cu_clock_format_utc(-1e13, buf, sizeof buf), 0);
    assert_int_not_equal(cu_clock_format_utc(NAN, buf, sizeof buf), 0);
    assert_int_not_equal(cu_clock_format_utc(INFINITY, buf, sizeof buf), 0);
    assert_int_not_equal(cu_clock_format_utc(0.0, buf, 8), 0); /* too small a buffer */

    static const struct { double s; const char *text; } offs[] = {
        { 1800, "+30min" }, { -5400, "-90min" }, { 0, "+0min" }, { 450, "+7.5min" }, { 86400, "+1440min" },
    };
    for (size_t i = 0; i < sizeof offs / sizeof offs[0]; i++) {
        cu_clock_format_offset(offs[i].s, buf, sizeof buf);
        assert_string_equal(buf, offs[i].text);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_offset_by_knob_keys_and_commands),
        cmocka_unit_test(test_offset_acceleration),
        cmocka_unit_test(test_time_shown),
        cmocka_unit_test(test_formats),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
