/* src/gpu/profile.c: where a frame's time goes (cu_renderer_set_profiling): the wall clock between glFinish calls at
 * the passes' boundaries, which frame.c marks. */
#include "profile.h"
#include <string.h>
#include <time.h>

static const char *const names[CU_PASS_COUNT] = {"maps", "shadows", "energy", "sky", "clouds", "upsample", "tonemap"};

const char *cu_pass_name(int pass)
{
    return pass >= 0 && pass < CU_PASS_COUNT ? names[pass] : NULL;
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

void cu_renderer_set_profiling(cu_renderer *r, int on)
{
    r->profile = on != 0;
}

int cu_renderer_pass_times(const cu_renderer *r, double ms[CU_PASS_COUNT])
{
    if (!r->profiled)
        return 1;
    memcpy(ms, r->pass_ms, sizeof r->pass_ms);
    return 0;
}

void cu_profile_begin(cu_renderer *r)
{
    if (!r->profile)
        return;
    r->gl.Finish(); /* what the host queued before the frame is not the frame's */
    memset(r->pass_ms, 0, sizeof r->pass_ms);
    r->prof_t = now_ms();
}

void cu_profile_mark(cu_renderer *r, int pass)
{
    if (!r->profile)
        return;
    r->gl.Finish();
    double t = now_ms();
    r->pass_ms[pass] += t - r->prof_t;
    r->prof_t = t;
    r->profiled = 1;
}
