/* platform/input/sun_control.c: knob/keyboard/command actions -> sun elevation and azimuth (axis toggle, acceleration,
 * limits). */
#include "sun_control.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void cu_sun_ctl_init(cu_sun_ctl *c, double el, double az)
{
    cu_sun_ctl z = {0};
    *c = z;
    c->lim.el_min = -10.0; /* a little below the horizon: twilight colours, not a black screen */
    c->lim.el_max = 90.0;
    c->lim.az_min = 0.0;
    c->lim.az_max = 360.0;
    c->step_az = 1.0;
    c->step_el = 0.5;
    cu_knob_speed_init(&c->speed);
    c->el = el;
    c->az = az;
    cu_sun_ctl_clamp(&c->lim, &c->el, &c->az);
}

void cu_sun_ctl_start(cu_sun_ctl *c, const cu_sun_ctl *settings, double el, double az)
{
    cu_sun_ctl_init(c, el, az);
    el = c->el;
    az = c->az;
    *c = *settings;
    c->el = el;
    c->az = az;
    cu_sun_ctl_clamp(&c->lim, &c->el, &c->az);
}

int cu_sun_parse_range(const char *opt, const char *s, double lo, double hi, double *min, double *max,
                       char *err, size_t errlen)
{
    char *end;
    double a = strtod(s, &end);
    if (end == s || *end != ':')
        goto bad;
    const char *q = end + 1;
    double b = strtod(q, &end);
    if (end == q || *end || !(a < b) || a < lo || b > hi || !isfinite(a) || !isfinite(b))
        goto bad;
    *min = a;
    *max = b;
    return 0;
bad:
    snprintf(err, errlen, "%s '%s': expected MIN:MAX in degrees with %g <= MIN < MAX <= %g", opt, s, lo, hi);
    return 1;
}

void cu_sun_ctl_clamp(const cu_sun_limits *l, double *el, double *az)
{
    if (*el < l->el_min) *el = l->el_min;
    if (*el > l->el_max) *el = l->el_max;
    if (l->az_max - l->az_min >= 360.0) {
        *az = fmod(*az, 360.0);
        if (*az < 0.0) *az += 360.0;
        if (*az >= 360.0) *az = 0.0; /* fmod of a tiny negative can round up to 360 */
    } else {
        if (*az < l->az_min) *az = l->az_min;
        if (*az > l->az_max) *az = l->az_max;
    }
}

static int move_to(cu_sun_ctl *c, double el, double az)
{
    cu_sun_ctl_clamp(&c->lim, &el, &az);
    if (el == c->el && az == c->az)
        return 0;
    c->el = el;
    c->az = az;
    return 1;
}

int cu_sun_ctl_apply(cu_sun_ctl *c, const cu_action *a)
{
    switch (a->kind) {
    case CU_ACT_TURN:
    case CU_ACT_TURN_AZ:
    case CU_ACT_TURN_EL: {
        if (a->detents == 0)
            return 0;
        double g = cu_knob_speed_turn(&c->speed, a);
        cu_sun_axis axis = a->kind == CU_ACT_TURN_AZ ? CU_SUN_AZIMUTH
                         : a->kind == CU_ACT_TURN_EL ? CU_SUN_ELEVATION : c->axis;
        if (axis == CU_SUN_AZIMUTH)
            return move_to(c, c->el, c->az + g * c->step_az * a->detents);
        return move_to(c, c->el + g * c->step_el * a->detents, c->az);
    }
    case CU_ACT_TOGGLE:
        c->axis = c->axis == CU_SUN_AZIMUTH ? CU_SUN_ELEVATION : CU_SUN_AZIMUTH;
        return 0;
    case CU_ACT_SET_SUN:
        return move_to(c, a->el, a->az);
    case CU_ACT_SET_EL:
        return move_to(c, a->el, c->az);
    case CU_ACT_SET_AZ:
        return move_to(c, c->el, a->az);
    default:
        return 0;
    }
}
