/* platform/input/clock_control.h: `cumulo run --clock`: maps input actions to an offset of the time of day, and gives
 * the time the sky shows from the wall clock, the time scale and the offsets. Pure: the caller reads the clocks. */
#ifndef CU_PLATFORM_CLOCK_CONTROL_H
#define CU_PLATFORM_CLOCK_CONTROL_H
#include "input.h"
#include "knob_speed.h"

typedef struct cu_clock_ctl {
    double offset_s;        /* the knob's offset, whole seconds within +-CU_OFFSET_MAX_MIN minutes; the button zeroes it */
    double step_s;          /* seconds per detent at slow speed (--step, in minutes) */
    double shift_s;         /* --clock-offset: a fixed shift of the wall clock, seconds */
    double scale;           /* --time-scale: the shown clock runs this many times faster than the wall clock */
    cu_knob_speed speed;    /* the acceleration of fast turns, as for the angles */
} cu_clock_ctl;

/* Defaults: 10 minutes a detent, no shift, scale 1, the knob's default acceleration, offset 0. */
void cu_clock_ctl_init(cu_clock_ctl *c);
/* Applies one action: the knob, +/- and left/right move the offset by the step (accelerated like the angles), up/down by
 * an hour, the button (toggle) puts it back to 0, `offset MINUTES` sets it. Returns 1 when the offset changed, 0
 * otherwise; actions on the sun's angles are not the clock's and change nothing (the caller says so). */
int  cu_clock_ctl_apply(cu_clock_ctl *c, const cu_action *a);
/* The POSIX time (seconds since 1970 UTC) the sky shows when the wall clock reads wall_s, elapsed_s (monotonic) after
 * the start: wall_s + (scale - 1) elapsed_s + shift + offset. */
double cu_clock_ctl_shown(const cu_clock_ctl *c, double wall_s, double elapsed_s);
/* t (POSIX seconds, rounded down to a whole second) as ISO 8601 UTC, "2026-06-21T12:00:00Z". Returns non-zero when t
 * is not a time of the years 0..9999 this machine can represent. */
int  cu_clock_format_utc(double t, char *buf, size_t len);
/* An offset in seconds as signed minutes for the log lines: "+30min", "-90min", "+0min", "+7.5min". */
void cu_clock_format_offset(double offset_s, char *buf, size_t len);

#endif
