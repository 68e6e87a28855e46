/* platform/input/sun_control.h: maps input actions to the sun's elevation and azimuth: which axis the knob drives,
 * its steps (fast turns accelerate: knob_speed.h), and the limits. Pure: no I/O, no renderer. */
#ifndef CU_PLATFORM_SUN_CONTROL_H
#define CU_PLATFORM_SUN_CONTROL_H
#include "input.h"
#include "knob_speed.h"

typedef enum cu_sun_axis { CU_SUN_AZIMUTH = 0, CU_SUN_ELEVATION = 1 } cu_sun_axis;

typedef struct cu_sun_limits {
    double el_min, el_max;  /* degrees, within [-90, 90] */
    double az_min, az_max;  /* degrees; a span of 360 or more wraps around instead of stopping */
} cu_sun_limits;

typedef struct cu_sun_ctl {
    double el, az;
    cu_sun_axis axis;       /* what the knob drives now; the button toggles it */
    cu_sun_limits lim;
    double step_az, step_el;/* degrees per detent at slow speed */
    cu_knob_speed speed;    /* the acceleration of fast turns */
} cu_sun_ctl;

/* Defaults: knob on azimuth, 1 deg/detent azimuth, 0.5 deg/detent elevation, acceleration 0.25 per detent/s above
 * 4 detents/s capped at x8, elevation -10..90, azimuth wraps. */
void cu_sun_ctl_init(cu_sun_ctl *c, double el, double az);
/* Starts c with the settings of `settings` (limits, axis, steps, acceleration) and the sun at (el, az), put inside
 * the default limits as cu_sun_ctl_init does, then inside the settings' own. */
void cu_sun_ctl_start(cu_sun_ctl *c, const cu_sun_ctl *settings, double el, double az);
/* "MIN:MAX" in degrees; returns non-zero with a message naming the option. */
int  cu_sun_parse_range(const char *opt, const char *s, double lo, double hi, double *min, double *max,
                        char *err, size_t errlen);
/* Applies one action. Returns 1 when the sun moved (the caller then calls cu_renderer_set_sun), 0 otherwise. */
int  cu_sun_ctl_apply(cu_sun_ctl *c, const cu_action *a);
/* Puts (el, az) inside the limits: elevation clamps, azimuth wraps to [0, 360) or clamps to a partial range. */
void cu_sun_ctl_clamp(const cu_sun_limits *l, double *el, double *az);

#endif
