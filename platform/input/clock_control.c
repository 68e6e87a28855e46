/* platform/input/clock_control.c: knob/keyboard/command actions -> the offset of the time of day, and the time the sky
 * shows under --clock (see clock_control.h). */
#include "clock_control.h"
#include <math.h>
#include <stdio.h>
#include <time.h>

#define OFFSET_MAX_S (CU_OFFSET_MAX_MIN * 60.0)

void cu_clock_ctl_init(cu_clock_ctl *c)
{
    /* 10 minutes a detent, not 1: the Earth turns 15 degrees an hour, so a minute moves the sun about a quarter of a
     * degree, too little for a detent to show. With ten a day is 144 detents: seven turns of a 20-detent knob turned
     * slowly, about one spun fast (the gain tops out at x8). */
    c->offset_s = 0.0;
    c->step_s = 600.0;
    c->shift_s = 0.0;
    c->scale = 1.0;
    cu_knob_speed_init(&c->speed);
}

static int set_offset(cu_clock_ctl *c, double s)
{
    /* Whole seconds: the shown time is one (cu_clock_format_utc), and +0.0 so that a turn back to 0 is never -0. */
    s = round(s) + 0.0;
    if (s > OFFSET_MAX_S) s = OFFSET_MAX_S;
    if (s < -OFFSET_MAX_S) s = -OFFSET_MAX_S;
    if (s == c->offset_s)
        return 0;
    c->offset_s = s;
    return 1;
}

int cu_clock_ctl_apply(cu_clock_ctl *c, const cu_action *a)
{
    switch (a->kind) {
    case CU_ACT_TURN:
    case CU_ACT_TURN_AZ:
    case CU_ACT_TURN_EL: {
        if (a->detents == 0)
            return 0;
        double g = cu_knob_speed_turn(&c->speed, a);
        double step = a->kind == CU_ACT_TURN_EL ? 3600.0 : g * c->step_s;
        return set_offset(c, c->offset_s + step * a->detents);
    }
    case CU_ACT_TOGGLE:
        return set_offset(c, 0.0);
    case CU_ACT_SET_OFFSET:
        return set_offset(c, a->minutes * 60.0);
    default:
        return 0;
    }
}

double cu_clock_ctl_shown(const cu_clock_ctl *c, double wall_s, double elapsed_s)
{
    /* The wall clock read now, not its reading at the start plus the monotonic time: a Pi has no battery clock and
     * steps its clock when NTP first answers, maybe minutes after the kiosk started; the sky must follow that step.
     * Only the speed-up beyond real time rides on the monotonic clock, which never steps. */
    return wall_s + (c->scale - 1.0) * elapsed_s + c->shift_s + c->offset_s;
}

int cu_clock_format_utc(double t, char *buf, size_t len)
{
    double s = floor(t);
    /* Years 0..9999 (four digits); a 32-bit time_t (older armhf systems) ends in 2038: past it is refused, not
     * wrapped, and checked before the conversion, which would be undefined. */
    double lo = sizeof(time_t) < 8 ? -2147483648.0 : -62167219200.0;
    double hi = sizeof(time_t) < 8 ? 2147483647.0 : 253402300799.0;
    if (!(s >= lo && s <= hi)) {
        snprintf(buf, len, "(out of range)");
        return 1;
    }
    time_t tt = (time_t)s;
    struct tm tm;
    if (!gmtime_r(&tt, &tm) || !strftime(buf, len, "%Y-%m-%dT%H:%M:%SZ", &tm)) {
        snprintf(buf, len, "(out of range)");
        return 1;
    }
    return 0;
}

void cu_clock_format_offset(double offset_s, char *buf, size_t len)
{
    snprintf(buf, len, "%+gmin", offset_s / 60.0 + 0.0);
}
