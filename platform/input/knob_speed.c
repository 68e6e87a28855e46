/* platform/input/knob_speed.c: the acceleration curve of fast knob turns (see knob_speed.h). */
#include "knob_speed.h"
#include <math.h>

void cu_knob_speed_init(cu_knob_speed *k)
{
    k->accel = 0.25;
    k->from = 4.0;
    k->max = 8.0;
    k->t_turn = 0;
}

double cu_knob_speed_gain(const cu_knob_speed *k, int detents, uint64_t dt_ns)
{
    /* A slow turn moves exactly one step per detent (fine positioning); spinning the knob moves faster, so the
     * whole sky is a few turns away. Speed is detents per second over this event's interval. */
    if (k->accel <= 0.0 || dt_ns == 0)
        return 1.0;
    double rate = fabs((double)detents) / ((double)dt_ns * 1e-9);
    double g = 1.0 + k->accel * (rate > k->from ? rate - k->from : 0.0);
    return g > k->max ? k->max : g;
}

double cu_knob_speed_turn(cu_knob_speed *k, const cu_action *a)
{
    uint64_t dt = 0;
    if (a->t_ns && k->t_turn && a->t_ns > k->t_turn)
        dt = a->t_ns - k->t_turn;
    if (a->t_ns)
        k->t_turn = a->t_ns;
    /* A pause longer than a second starts over at fine steps. */
    return dt && dt < 1000000000u ? cu_knob_speed_gain(k, a->detents, dt) : 1.0;
}
