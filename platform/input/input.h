/* platform/input/input.h: what the inputs of `cumulo run` say (actions) and the `--input` option's grammar; pure, no
 * I/O. */
#ifndef CU_PLATFORM_INPUT_H
#define CU_PLATFORM_INPUT_H
#include <stddef.h>
#include <stdint.h>

/* Every input back end (GPIO knob, evdev keyboard or dial, stdin commands) turns its events into these. */
typedef enum cu_action_kind {
    CU_ACT_NONE = 0,
    CU_ACT_TURN,      /* knob: detents on the axis the knob currently drives (+ clockwise) */
    CU_ACT_TURN_AZ,   /* detents on azimuth whatever the knob drives (left/right arrows) */
    CU_ACT_TURN_EL,   /* detents on elevation (up/down arrows) */
    CU_ACT_TOGGLE,    /* knob button: switch the knob between azimuth and elevation */
    CU_ACT_SET_SUN,   /* absolute elevation and azimuth, degrees */
    CU_ACT_SET_EL,
    CU_ACT_SET_AZ,
    CU_ACT_SET_OFFSET,/* --clock: the offset of the time of day, minutes */
    CU_ACT_STATUS,    /* print the current sun */
    CU_ACT_QUIT
} cu_action_kind;

typedef struct cu_action {
    cu_action_kind kind;
    int detents;
    double el, az;
    double minutes;   /* CU_ACT_SET_OFFSET, within +-CU_OFFSET_MAX_MIN */
    uint64_t t_ns;    /* when it happened (CLOCK_MONOTONIC for devices, 0 = now) */
} cu_action;

#define CU_OFFSET_MAX_MIN 1440 /* the clock's offset, minutes: a day either way reaches every time of day */

typedef enum cu_input_kind { CU_INPUT_GPIO = 1, CU_INPUT_EVDEV, CU_INPUT_STDIN } cu_input_kind;

#define CU_INPUT_NAME_MAX 128
typedef struct cu_input_spec {
    cu_input_kind kind;
    /* gpio: chip (name "gpiochip0", number "0", path "/dev/gpiochip0" or label), lines by offset or name */
    char chip[CU_INPUT_NAME_MAX];
    char a[CU_INPUT_NAME_MAX], b[CU_INPUT_NAME_MAX], button[CU_INPUT_NAME_MAX];
    int steps_per_detent;   /* 0 = decoder default (4) */
    int debounce_us;        /* kernel debounce where libgpiod v2 offers it; -1 = default (1000 us), 0 = off */
    /* evdev: by path or by device name (EVIOCGNAME, exact match first, then substring) */
    char path[256];
    char name[CU_INPUT_NAME_MAX];
} cu_input_spec;

/* Parses one --input value:
 *   gpio:chip=gpiochip0,a=17,b=27[,button=22][,steps=4][,debounce=1000]
 *   evdev:/dev/input/event3 | evdev:path=/dev/input/by-id/... | evdev:name=Griffin PowerMate
 *   stdin
 * Returns 0, or non-zero with a one-line message naming the option and the field. */
int cu_input_parse(const char *s, cu_input_spec *out, char *err, size_t errlen);

/* A GPIO line given as a number is an offset; anything else is a line name (e.g. "GPIO17" on a Pi). Returns the
 * offset, or -1 when it is a name. */
int cu_input_line_offset(const char *s);
/* Copies src into dst (n bytes, always terminated), every control byte but keep[]'s written as \xHH: text from a
 * line or a device that is echoed into a log must not drive the terminal that shows it (ESC sequences, BEL). */
void cu_input_escape(char *dst, size_t n, const char *src, const char *keep);

/* A human-readable description for log lines, e.g. "gpio gpiochip0 a=17 b=27 button=22". */
void cu_input_describe(const cu_input_spec *s, char *buf, size_t len);

#endif
