/* platform/input/knob_speed.h: the acceleration of fast knob turns, shared by what a knob drives (sun_control.c: the
 * sun's angles; clock_control.c: the time of day). Pure: no I/O. */
#ifndef CU_PLATFORM_KNOB_SPEED_H
#define CU_PLATFORM_KNOB_SPEED_H
#include "input.h"

typedef struct cu_knob_speed {
    double accel;           /* extra gain per detent/s above `from` (0 = none) */
    double from;            /* detents per second below which a turn is exact (fine positioning) */
    double max;             /* cap on the gain */
    uint64_t t_turn;        /* time of the previous knob turn, for the speed */
} cu_knob_speed;

/* Defaults: 0.25 per detent/s above 4 detents/s, capped at x8. */
void   cu_knob_speed_init(cu_knob_speed *k);
/* The gain for `detents` turned `dt_ns` after the previous turn. */
double cu_knob_speed_gain(const cu_knob_speed *k, int detents, uint64_t dt_ns);
/* The gain of one turn action, remembering its time (a->t_ns; 0 = unknown): 1 for the first turn and after a pause
 * of more than a second. */
double cu_knob_speed_turn(cu_knob_speed *k, const cu_action *a);

#endif
