/* tests/platform/test_evdev.c: evdev decoding on recorded `struct input_event` streams (USB dial, keyboard with
 * auto-repeat, Pi rotary-encoder overlay, a mouse, SYN_DROPPED) and the one-line errors of opening devices. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>
#include "evdev.h"

#define EV(sec, usec, t, c, v) { .input_event_sec = (sec), .input_event_usec = (usec), .type = (t), .code = (c), \
                                 .value = (v) }
#ifndef input_event_sec
#undef EV
#define EV(sec, usec, t, c, v) { .time = { (sec), (usec) }, .type = (t), .code = (c), .value = (v) }
#endif

typedef struct decoded { cu_action a[64]; int n; } decoded;

static decoded decode_all(cu_evdev_decoder *d, const struct input_event *ev, size_t n)
{
    decoded out = {0};
    for (size_t i = 0; i < n; i++)
        if (cu_evdev_decode(d, &ev[i], &out.a[out.n]))
            out.n++;
    return out;
}

static void test_usb_dial(void **state)
{
    (void)state;
    /* Griffin PowerMate: REL_DIAL per detent, BTN_0 press/release (as recorded with evtest). */
    static const struct input_event s[] = {
        EV(100, 0, EV_REL, REL_DIAL, 1), EV(100, 0, EV_SYN, SYN_REPORT, 0),
        EV(100, 20000, EV_REL, REL_DIAL, 2), EV(100, 20000, EV_SYN, SYN_REPORT, 0),
        EV(100, 90000, EV_REL, REL_DIAL, -1), EV(100, 90000, EV_SYN, SYN_REPORT, 0),
        EV(101, 0, EV_KEY, BTN_0, 1), EV(101, 0, EV_SYN, SYN_REPORT, 0),
        EV(101, 150000, EV_KEY, BTN_0, 0), EV(101, 150000, EV_SYN, SYN_REPORT, 0),
    };
    cu_evdev_decoder d = {0};
    decoded r = decode_all(&d, s, sizeof s / sizeof s[0]);
    assert_int_equal(r.n, 4);
    assert_int_equal(r.a[0].kind, CU_ACT_TURN);
    assert_int_equal(r.a[0].detents, 1);
    assert_true(r.a[0].t_ns == 100000000000ull);
    assert_int_equal(r.a[1].detents, 2);
    assert_true(r.a[1].t_ns == 100020000000ull);
    assert_int_equal(r.a[2].detents, -1);
    assert_int_equal(r.a[3].kind, CU_ACT_TOGGLE);
}

static void test_consumer_control_knob(void **state)
{
    (void)state;
    /* Cheap USB volume knobs are HID consumer controls: volume up/down and mute. */
    static const struct input_event s[] = {
        EV(5, 0, EV_MSC, MSC_SCAN, 0xc00e9), EV(5, 0, EV_KEY, KEY_VOLUMEUP, 1), EV(5, 0, EV_SYN, SYN_REPORT, 0),
        EV(5, 10, EV_KEY, KEY_VOLUMEUP, 0), EV(5, 10, EV_SYN, SYN_REPORT, 0),
        EV(6, 0, EV_KEY, KEY_VOLUMEDOWN, 1), EV(6, 0, EV_SYN, SYN_REPORT, 0),
        EV(6, 10, EV_KEY, KEY_VOLUMEDOWN, 0), EV(6, 10, EV_SYN, SYN_REPORT, 0),
        EV(7, 0, EV_KEY, KEY_MUTE, 1), EV(7, 10, EV_KEY, KEY_MUTE, 0), EV(7, 10, EV_SYN, SYN_REPORT, 0),
    };
    cu_evdev_decoder d = {0};
    decoded r = decode_all(&d, s, sizeof s / sizeof s[0]);
    assert_int_equal(r.n, 3);
    assert_int_equal(r.a[0].detents, 1);
    assert_int_equal(r.a[1].detents, -1);
    assert_int_equal(r.a[2].kind, CU_ACT_TOGGLE);
}

static void test_keyboard_with_repeat(void **state)
{
    (void)state;
    static const struct input_event s[] = {
        EV(1, 0, EV_MSC, MSC_SCAN, 0x70050), EV(1, 0, EV_KEY, KEY_LEFT, 1), EV(1, 0, EV_SYN, SYN_REPORT, 0),
        EV(1, 250000, EV_KEY, KEY_LEFT, 2), EV(1, 250000, EV_SYN, SYN_REPORT, 0),
        EV(1, 283000, EV_KEY, KEY_LEFT, 2), EV(1, 283000, EV_SYN, SYN_REPORT, 0),
        EV(1, 300000, EV_KEY, KEY_LEFT, 0), EV(1, 300000, EV_SYN, SYN_REPORT, 0),
        EV(2, 0, EV_KEY, KEY_UP, 1), EV(2, 1, EV_KEY, KEY_UP, 0),
        EV(2, 2, EV_KEY, KEY_DOWN, 1), EV(2, 3, EV_KEY, KEY_RIGHT, 1),
        EV(3, 0, EV_KEY, KEY_LEFTSHIFT, 1), EV(3, 1, EV_KEY, KEY_EQUAL, 1), /* '+' on the main keyboard */
        EV(3, 2, EV_KEY, KEY_KPMINUS, 1), EV(3, 3, EV_KEY, KEY_MINUS, 1), EV(3, 4, EV_KEY, KEY_KPPLUS, 1),
        EV(4, 0, EV_KEY, KEY_ENTER, 1), EV(4, 1, EV_KEY, KEY_ENTER, 2), EV(4, 2, EV_KEY, KEY_ENTER, 0),
        EV(4, 3, EV_KEY, KEY_A, 1), EV(4, 4, EV_KEY, KEY_Q, 1),
    };
    cu_evdev_decoder d = {0};
    decoded r = decode_all(&d, s, sizeof s / sizeof s[0]);
    static const struct { cu_action_kind k; int det; } want[] = {
        { CU_ACT_TURN_AZ, -1 }, { CU_ACT_TURN_AZ, -1 }, { CU_ACT_TURN_AZ, -1 },
        { CU_ACT_TURN_EL, 1 }, { CU_ACT_TURN_EL, -1 }, { CU_ACT_TURN_AZ, 1 },
        { CU_ACT_TURN, 1 }, { CU_ACT_TURN, -1 }, { CU_ACT_TURN, -1 }, { CU_ACT_TURN, 1 },
        { CU_ACT_TOGGLE, 0 }, { CU_ACT_QUIT, 0 },
    };
    assert_int_equal(r.n, (int)(sizeof want / sizeof want[0]));
    for (int i = 0; i < r.n; i++) {
        assert_int_equal(r.a[i].kind, want[i].k);
        assert_int_equal(r.a[i].detents, want[i].det);
    }
}

static void test_rotary_encoder_overlay_and_mouse(void **state)
{
    (void)state;
    /* dtoverlay=rotary-encoder,relative_axis=1 reports REL_X per step; a mouse also moves REL_X but has BTN_LEFT. */
    unsigned char keys[KEY_MAX / 8 + 1] = {0}, rels[REL_MAX / 8 + 1] = {0};
    rels[REL_X / 8] |= 1 << (REL_X % 8);
    assert_int_equal(cu_evdev_rel_x_is_knob(keys, sizeof keys, rels, sizeof rels), 1);
    cu_evdev_decoder enc = { .rel_x_is_knob = 1 };
    static const struct input_event s[] = {
        EV(9, 0, EV_REL, REL_X, 1), EV(9, 0, EV_SYN, SYN_REPORT, 0),
        EV(9, 5000, EV_REL, REL_X, 1), EV(9, 5000, EV_SYN, SYN_REPORT, 0),
        EV(9, 9000, EV_REL, REL_X, -1), EV(9, 9000, EV_SYN, SYN_REPORT, 0),
    };
    decoded r = decode_all(&enc, s, sizeof s / sizeof s[0]);
    assert_int_equal(r.n, 3);
    assert_int_equal(r.a[0].detents + r.a[1].detents + r.a[2].detents, 1);

    keys[BTN_LEFT / 8] |= 1 << (BTN_LEFT % 8);
    rels[REL_Y / 8] |= 1 << (REL_Y % 8);
    assert_int_equal(cu_evdev_rel_x_is_knob(keys, sizeof keys, rels, sizeof rels), 0);
    cu_evdev_decoder mouse = { .rel_x_is_knob = 0 };
    static const struct input_event m[] = {
        EV(9, 0, EV_REL, REL_X, 7), EV(9, 0, EV_REL, REL_Y, -3), EV(9, 0, EV_SYN, SYN_REPORT, 0),
        EV(9, 8000, EV_REL, REL_WHEEL, -1), EV(9, 8000, EV_SYN, SYN_REPORT, 0),
        EV(9, 9000, EV_KEY, BTN_LEFT, 1), EV(9, 9000, EV_SYN, SYN_REPORT, 0),
    };
    r = decode_all(&mouse, m, sizeof m / sizeof m[0]);
    assert_int_equal(r.n, 1); /* only the wheel */
    assert_int_equal(r.a[0].detents, -1);
}

static void test_syn_dropped(void **state)
{
    (void)state;
    static const struct input_event s[] = {
        EV(1, 0, EV_REL, REL_DIAL, 1), EV(1, 0, EV_SYN, SYN_REPORT, 0),
        EV(1, 10, EV_SYN, SYN_DROPPED, 0),
        EV(1, 20, EV_REL, REL_DIAL, 5),   /* the tail of a report whose start was lost */
        EV(1, 20, EV_SYN, SYN_REPORT, 0),
        EV(1, 30, EV_REL, REL_DIAL, -1), EV(1, 30, EV_SYN, SYN_REPORT, 0),
    };
    cu_evdev_decoder d = {0};
    decoded r = decode_all(&d, s, sizeof s / sizeof s[0]);
    assert_int_equal(r.n, 2);
    assert_int_equal(r.a[0].detents, 1);
    assert_int_equal(r.a[1].detents, -1);
}

static void test_open_errors(void **state)
{
    (void)state;
    cu_evdev *e;
    cu_input_spec s = { .kind = CU_INPUT_EVDEV };
    char err[512];
    snprintf(s.path, sizeof s.path, "/nonexistent/event42");
    assert_int_not_equal(cu_evdev_open(&e, &s, 0, err, sizeof err), 0);
    assert_non_null(strstr(err, "/nonexistent/event42"));
    assert_non_null(strstr(err, "plugged in"));
    snprintf(s.path, sizeof s.path, "/dev/null");
    assert_int_not_equal(cu_evdev_open(&e, &s, 0, err, sizeof err), 0);
    assert_non_null(strstr(err, "not an input event device"));
    s.path[0] = '\0';
    snprintf(s.name, sizeof s.name, "No Such Knob 1234");
    assert_int_not_equal(cu_evdev_open(&e, &s, 0, err, sizeof err), 0);
    assert_non_null(strstr(err, "No Such Knob 1234"));
    assert_null(e);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_usb_dial),
        cmocka_unit_test(test_consumer_control_knob),
        cmocka_unit_test(test_keyboard_with_repeat),
        cmocka_unit_test(test_rotary_encoder_overlay_and_mouse),
        cmocka_unit_test(test_syn_dropped),
        cmocka_unit_test(test_open_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
