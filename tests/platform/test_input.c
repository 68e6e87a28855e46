/* tests/platform/test_input.c: `--input` parsing (good and bad), the stdin command language and its line splitter, and
 * the sun mapping (axis toggle, acceleration, limits). The clock's offset: test_clock.c. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>
#include "input.h"
#include "input_backend.h"
#include "stdin_input.h"
#include "sun_control.h"

static void test_parse_gpio(void **state)
{
    (void)state;
    cu_input_spec s;
    char err[256];
    assert_int_equal(cu_input_parse("gpio:chip=gpiochip0,a=17,b=27,button=22", &s, err, sizeof err), 0);
    assert_int_equal(s.kind, CU_INPUT_GPIO);
    assert_string_equal(s.chip, "gpiochip0");
    assert_string_equal(s.a, "17");
    assert_string_equal(s.b, "27");
    assert_string_equal(s.button, "22");
    assert_int_equal(s.debounce_us, -1);
    assert_int_equal(cu_input_line_offset(s.a), 17);

    assert_int_equal(cu_input_parse("gpio:a=GPIO17,b=GPIO27,steps=2,debounce=500", &s, err, sizeof err), 0);
    assert_string_equal(s.chip, "gpiochip0"); /* default chip */
    assert_string_equal(s.a, "GPIO17");
    assert_int_equal(cu_input_line_offset(s.a), -1); /* a name */
    assert_int_equal(s.steps_per_detent, 2);
    assert_int_equal(s.debounce_us, 500);
    assert_string_equal(s.button, "");

    assert_int_equal(cu_input_parse("gpio:chip=/dev/gpiochip4,b=6,a=5", &s, err, sizeof err), 0);
    assert_string_equal(s.chip, "/dev/gpiochip4");

    char d[128];
    cu_input_parse("gpio:chip=gpiochip0,a=17,b=27,button=22", &s, err, sizeof err);
    cu_input_describe(&s, d, sizeof d);
    assert_string_equal(d, "gpio gpiochip0 a=17 b=27 button=22");
}

static void expect_bad(const char *spec, const char *fragment)
{
    cu_input_spec s;
    char err[256] = "";
    assert_int_not_equal(cu_input_parse(spec, &s, err, sizeof err), 0);
    if (!strstr(err, fragment))
        fail_msg("'%s': message '%s' lacks '%s'", spec, err, fragment);
    assert_non_null(strstr(err, "--input"));
}

static void test_parse_bad(void **state)
{
    (void)state;
    expect_bad("", "empty");
    expect_bad("gpio:", "needs both");
    expect_bad("gpio:a=17", "needs both");
    expect_bad("gpio:a=17,b=", "needs a value");
    expect_bad("gpio:a=17,b=27,", "trailing");
    expect_bad("gpio:a=17,b=27,c=3", "unknown key 'c'");
    expect_bad("gpio:a=17,b=27,button", "expected key=value");
    expect_bad("gpio:a=17,b=17", "different");
    expect_bad("gpio:a=17,b=27,button=27", "different");
    expect_bad("gpio:a=17,b=27,steps=3", "'steps'");
    expect_bad("gpio:a=17,b=27,steps=x", "'steps'");
    expect_bad("gpio:a=17,b=27,debounce=-5", "'debounce'");
    /* numbers are digits only: strtol would take a sign or leading blanks, and wrap nothing past its range */
    expect_bad("gpio:a=17,b=27,steps=+4", "'steps'");
    expect_bad("gpio:a=17,b=27,debounce= 5", "'debounce'");
    expect_bad("gpio:a=17,b=27,debounce=99999999999999999999", "'debounce'");
    expect_bad("gpio:a=17,b=27,chip=aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa"
               "aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa", "longer than");
    expect_bad("evdev:", "give a device path");
    expect_bad("evdev:event3", "give a device path");
    expect_bad("evdev:name=", "needs a value");
    expect_bad("joystick:0", "unknown input kind");
    expect_bad("gpio", "unknown input kind");
    assert_int_equal(cu_input_line_offset("-1"), -1);
    assert_int_equal(cu_input_line_offset("17x"), -1);
    assert_int_equal(cu_input_line_offset("\t17"), -1);
    assert_int_equal(cu_input_line_offset("18446744073709551633"), -1);
    assert_int_equal(cu_input_line_offset("65535"), 65535);
    assert_int_equal(cu_input_line_offset(""), -1);
}

static void test_parse_evdev_and_stdin(void **state)
{
    (void)state;
    cu_input_spec s;
    char err[256];
    assert_int_equal(cu_input_parse("evdev:/dev/input/event3", &s, err, sizeof err), 0);
    assert_int_equal(s.kind, CU_INPUT_EVDEV);
    assert_string_equal(s.path, "/dev/input/event3");
    assert_int_equal(cu_input_parse("evdev:path=/dev/input/by-id/usb-knob-event-if00", &s, err, sizeof err), 0);
    assert_string_equal(s.path, "/dev/input/by-id/usb-knob-event-if00");
    assert_int_equal(cu_input_parse("evdev:name=Griffin PowerMate", &s, err, sizeof err), 0);
    assert_string_equal(s.name, "Griffin PowerMate");
    assert_string_equal(s.path, "");
    assert_int_equal(cu_input_parse("stdin", &s, err, sizeof err), 0);
    assert_int_equal(s.kind, CU_INPUT_STDIN);
}

static void test_stdin_commands(void **state)
{
    (void)state;
    cu_action a;
    char err[256];
    assert_int_equal(cu_stdin_parse("sun 35 120", &a, err, sizeof err), 0);
    assert_int_equal(a.kind, CU_ACT_SET_SUN);
    assert_true(a.el == 35.0 && a.az == 120.0);
    assert_int_equal(cu_stdin_parse("  sun\t-4.5 300.25  # dusk", &a, err, sizeof err), 0);
    assert_true(a.el == -4.5 && a.az == 300.25);
    assert_int_equal(cu_stdin_parse("el 10", &a, err, sizeof err), 0);
    assert_int_equal(a.kind, CU_ACT_SET_EL);
    assert_int_equal(cu_stdin_parse("azimuth 270", &a, err, sizeof err), 0);
    assert_int_equal(a.kind, CU_ACT_SET_AZ);
    assert_true(a.az == 270.0);
    assert_int_equal(cu_stdin_parse("turn -3", &a, err, sizeof err), 0);
    assert_int_equal(a.kind, CU_ACT_TURN);
    assert_int_equal(a.detents, -3);
    assert_int_equal(cu_stdin_parse("toggle", &a, err, sizeof err), 0);
    assert_int_equal(a.kind, CU_ACT_TOGGLE);
    assert_int_equal(cu_stdin_parse("quit", &a, err, sizeof err), 0);
    assert_int_equal(a.kind, CU_ACT_QUIT);
    assert_int_equal(cu_stdin_parse("offset -90.5", &a, err, sizeof err), 0);
    assert_int_equal(a.kind, CU_ACT_SET_OFFSET);
    assert_true(a.minutes == -90.5);
    assert_int_equal(cu_stdin_parse("offset 1440", &a, err, sizeof err), 0);
    assert_true(a.minutes == 1440.0);
    assert_int_equal(cu_stdin_parse("status\r", &a, err, sizeof err), 0);
    assert_int_equal(a.kind, CU_ACT_STATUS);
    assert_int_equal(cu_stdin_parse("", &a, err, sizeof err), 0);
    assert_int_equal(a.kind, CU_ACT_NONE);
    assert_int_equal(cu_stdin_parse("# just a comment", &a, err, sizeof err), 0);
    assert_int_equal(a.kind, CU_ACT_NONE);

    static const char *bad[] = { "sun 35", "sun 95 10", "sun x 10", "sun 10 nan", "sun 1 2 3", "el", "az 1e9",
                                 "turn 1.5", "turn", "quit now", "dance", "sun 10 20 30 40 50", "offset",
                                 "offset 1441", "offset -2000", "offset 1 2", "offset inf", "offset 30min" };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        err[0] = '\0';
        if (cu_stdin_parse(bad[i], &a, err, sizeof err) == 0)
            fail_msg("'%s' was accepted", bad[i]);
        assert_non_null(strstr(err, "stdin:"));
    }
    /* what a line echoes back is escaped: an ESC or BEL from stdin must not reach the terminal that shows the log */
    static const char *const hostile[][2] = {
        { "dance\x1b[2J", "'dance\\x1b[2J'" }, { "sun \x1b]0;x\x07 10", "'\\x1b]0;x\\x07'" },
        { "el\x1b", "'el\\x1b'" }, { "quit \x7f", "'quit'" },
    };
    for (size_t i = 0; i < sizeof hostile / sizeof hostile[0]; i++) {
        err[0] = '\0';
        assert_int_not_equal(cu_stdin_parse(hostile[i][0], &a, err, sizeof err), 0);
        for (const char *p = err; *p; p++)
            if ((unsigned char)*p < 32 || *p == 127)
                fail_msg("case %zu: raw byte 0x%02x in '%s'", i, (unsigned char)*p, err);
        if (!strstr(err, hostile[i][1]))
            fail_msg("case %zu: '%s' lacks %s", i, err, hostile[i][1]);
    }
}

typedef struct lines { char got[8][64]; int n; } lines;
static void collect(void *user, const char *line)
{
    lines *l = user;
    if (l->n < 8)
        strncpy(l->got[l->n++], line, 63);
}

static void test_stdin_line_splitter(void **state)
{
    (void)state;
    cu_stdin s;
    lines l = {0};
    cu_stdin_init(&s, -1);
    cu_stdin_feed(&s, "sun 1", 5, collect, &l);
    assert_int_equal(l.n, 0);
    cu_stdin_feed(&s, "0 20\nquit\n\nst", 13, collect, &l);
    assert_int_equal(l.n, 3);
    assert_string_equal(l.got[0], "sun 10 20");
    assert_string_equal(l.got[1], "quit");
    assert_string_equal(l.got[2], "");
    char big[600];
    memset(big, 'x', sizeof big);
    cu_stdin_feed(&s, big, sizeof big, collect, &l);
    cu_stdin_feed(&s, "\nturn 1\n", 8, collect, &l);
    assert_int_equal(l.n, 5);
    assert_string_equal(l.got[3], CU_STDIN_OVERLONG);
    assert_string_equal(l.got[4], "turn 1");
}

static void test_sun_knob_and_toggle(void **state)
{
    (void)state;
    cu_sun_ctl c;
    cu_sun_ctl_init(&c, 30, 350);
    c.speed.accel = 0;
    cu_action a = { .kind = CU_ACT_TURN, .detents = 15 };
    assert_int_equal(cu_sun_ctl_apply(&c, &a), 1);
    assert_true(c.az == 5.0 && c.el == 30.0);          /* wraps past north */
    a.detents = -10;
    cu_sun_ctl_apply(&c, &a);
    assert_true(c.az == 355.0);
    cu_action t = { .kind = CU_ACT_TOGGLE };
    assert_int_equal(cu_sun_ctl_apply(&c, &t), 0);
    assert_int_equal(c.axis, CU_SUN_ELEVATION);
    a.detents = 4;
    cu_sun_ctl_apply(&c, &a);
    assert_true(c.el == 32.0 && c.az == 355.0);         /* 0.5 deg per detent */
    a.detents = 1000;
    cu_sun_ctl_apply(&c, &a);
    assert_true(c.el == 90.0);                          /* clamped */
    assert_int_equal(cu_sun_ctl_apply(&c, &a), 0);      /* already at the limit: no change, no sun pass */
    cu_action az = { .kind = CU_ACT_TURN_AZ, .detents = 2 };
    cu_sun_ctl_apply(&c, &az);
    assert_true(c.az == 357.0);
    cu_action el = { .kind = CU_ACT_TURN_EL, .detents = -400 };
    cu_sun_ctl_apply(&c, &el);
    assert_true(c.el == -10.0);
}

static void test_sun_set_and_limits(void **state)
{
    (void)state;
    cu_sun_ctl c;
    char err[256];
    cu_sun_ctl_init(&c, 30, 120);
    assert_int_equal(cu_sun_parse_range("--sun-azimuth-range", "90:270", -720, 720, &c.lim.az_min, &c.lim.az_max,
                                        err, sizeof err), 0);
    assert_int_equal(cu_sun_parse_range("--sun-elevation-range", "5:60", -90, 90, &c.lim.el_min, &c.lim.el_max,
                                        err, sizeof err), 0);
    cu_action s = { .kind = CU_ACT_SET_SUN, .el = 80, .az = 300 };
    assert_int_equal(cu_sun_ctl_apply(&c, &s), 1);
    assert_true(c.el == 60.0 && c.az == 270.0);          /* partial azimuth range clamps instead of wrapping */
    s.el = 60; s.az = 270;
    assert_int_equal(cu_sun_ctl_apply(&c, &s), 0);
    cu_action e = { .kind = CU_ACT_SET_EL, .el = 0 };
    cu_sun_ctl_apply(&c, &e);
    assert_true(c.el == 5.0);
    cu_action z = { .kind = CU_ACT_SET_AZ, .az = 100 };
    cu_sun_ctl_apply(&c, &z);
    assert_true(c.az == 100.0);

    static const char *bad[] = { "10", "10:", ":10", "20:10", "10:10", "-100:10", "a:b", "1:2x" };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        double lo, hi;
        err[0] = '\0';
        assert_int_not_equal(cu_sun_parse_range("--sun-elevation-range", bad[i], -90, 90, &lo, &hi, err, sizeof err),
                             0);
        assert_non_null(strstr(err, "--sun-elevation-range"));
    }
    /* Negative azimuths and whole turns wrap into [0, 360). */
    cu_sun_ctl_init(&c, 10, -30);
    assert_true(c.az == 330.0);
    s.el = 10; s.az = 720;
    cu_sun_ctl_apply(&c, &s);
    assert_true(c.az == 0.0);
}

static void test_sun_acceleration(void **state)
{
    (void)state;
    cu_sun_ctl c;
    cu_sun_ctl_init(&c, 30, 0);
    /* Slow: 2 detents/s -> exactly one degree per detent. */
    assert_true(cu_knob_speed_gain(&c.speed, 1, 500000000u) == 1.0);
    /* 20 detents/s -> 1 + 0.25 * 16 = 5. */
    double g = cu_knob_speed_gain(&c.speed, 1, 50000000u);
    assert_true(g > 4.999 && g < 5.001);
    /* Very fast: capped. */
    assert_true(cu_knob_speed_gain(&c.speed, 4, 1000000u) == 8.0);
    /* A sequence of turns: the first is exact (no previous time), a fast follow-up is amplified, one after a
     * long pause is exact again. */
    cu_action a = { .kind = CU_ACT_TURN, .detents = 1, .t_ns = 1000000000u };
    cu_sun_ctl_apply(&c, &a);
    assert_true(c.az == 1.0);
    a.t_ns += 50000000u;
    cu_sun_ctl_apply(&c, &a);
    assert_true(c.az > 5.999 && c.az < 6.001);
    a.t_ns += 3000000000u;
    cu_sun_ctl_apply(&c, &a);
    assert_true(c.az > 6.999 && c.az < 7.001);
}

extern const cu_input_backend cu_input_stdin; /* input_backend.c's table is not linked here: it needs them all */

static char logged[512];
static void log_line(void *user, const char *msg)
{
    (*(int *)user)++;
    snprintf(logged, sizeof logged, "%s", msg);
}

/* The "stdin" back end over a pipe standing in for fd 0: commands become actions, a bad one is logged and skipped,
 * the end of the stream is an ending, not a failure. */
static void test_stdin_backend(void **state)
{
    (void)state;
    int p[2], saved = dup(0), nlog = 0;
    assert_int_equal(pipe(p), 0);
    assert_int_equal(dup2(p[0], 0), 0);
    close(p[0]);
    cu_input_spec spec = { .kind = CU_INPUT_STDIN };
    cu_input_opts opts = { .log = log_line, .log_user = &nlog };
    cu_input *in;
    char msg[256], err[256];
    assert_int_equal(cu_input_stdin.open(&in, &spec, &opts, msg, sizeof msg), 0);
    assert_string_equal(msg, "");
    int fd;
    assert_int_equal(cu_input_stdin.fds(in, &fd, 1), 1);
    assert_int_equal(fd, 0);
    const char *cmds = "sun 10 20\nbogus\nturn -3";
    assert_int_equal(write(p[1], cmds, strlen(cmds)), (int)strlen(cmds));
    cu_action acts[4];
    int n;
    assert_int_equal(cu_input_stdin.read(in, acts, 4, &n, err, sizeof err), CU_INPUT_READ_OK);
    assert_int_equal(n, 1);
    assert_int_equal(acts[0].kind, CU_ACT_SET_SUN);
    assert_int_equal(nlog, 1);
    assert_non_null(strstr(logged, "stdin: unknown command 'bogus'"));
    close(p[1]);
    assert_int_equal(cu_input_stdin.read(in, acts, 4, &n, err, sizeof err), CU_INPUT_READ_ENDED);
    assert_int_equal(n, 1); /* the last line had no newline */
    assert_int_equal(acts[0].kind, CU_ACT_TURN);
    assert_int_equal(acts[0].detents, -3);
    cu_input_stdin.close(in);
    dup2(saved, 0);
    close(saved);
}

/* The knob starts from the scene's sun put inside the default limits, then inside the command line's. */
static void test_sun_ctl_start(void **state)
{
    (void)state;
    cu_sun_ctl set, c;
    cu_sun_ctl_init(&set, 0, 0);
    set.lim.el_min = 40;
    set.lim.el_max = 60;
    set.axis = CU_SUN_ELEVATION;
    set.step_az = 3;
    cu_sun_ctl_start(&c, &set, 75, 400);
    assert_true(c.el == 60 && c.az == 40);
    assert_int_equal(c.axis, CU_SUN_ELEVATION);
    assert_true(c.step_az == 3);
    cu_sun_ctl_init(&set, 0, 0);
    set.lim.el_min = -30;
    cu_sun_ctl_start(&c, &set, -20, 10);
    assert_true(c.el == -10); /* the default limit came first */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_parse_gpio),
        cmocka_unit_test(test_parse_bad),
        cmocka_unit_test(test_parse_evdev_and_stdin),
        cmocka_unit_test(test_stdin_commands),
        cmocka_unit_test(test_stdin_line_splitter),
        cmocka_unit_test(test_sun_knob_and_toggle),
        cmocka_unit_test(test_sun_set_and_limits),
        cmocka_unit_test(test_sun_acceleration),
        cmocka_unit_test(test_stdin_backend),
        cmocka_unit_test(test_sun_ctl_start),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
