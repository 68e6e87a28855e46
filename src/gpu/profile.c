/* src/gpu/profile.c: where a frame's time goes (cu_renderer_set_profiling): the time between the passes' boundaries,
 * which frame.c marks, by GPU timestamps or the wall clock between glFinish calls (pass_clock.c). */
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

const char *cu_renderer_profiling_clock(const cu_renderer *r)
{
    return cu_pass_clock_describe(&r->prof);
}

/* A rasteriser on the CPU (Mesa's llvmpipe and softpipe, SwiftShader) records a timestamp when the command is
 * submitted and draws later, when the scene is flushed: its timestamps put a pass's work at whichever boundary
 * happened to flush it (the clouds' under "sky" on llvmpipe). There the wall clock between glFinish calls is the
 * truthful one. */
static int software_rasteriser(const cu_renderer *r)
{
    return strstr(r->renderer_name, "llvmpipe") || strstr(r->renderer_name, "softpipe") ||
           strstr(r->renderer_name, "SwiftShader");
}

void cu_profile_begin(cu_renderer *r)
{
    if (!r->profile)
        return;
    if (r->prof.mode == CU_PASS_CLOCK_UNSET) {
        int soft = software_rasteriser(r);
        cu_pass_clock_init(&r->prof, &r->gl, r->desc.get_proc_address, r->desc.get_proc_user, r->is_gles, !soft);
        cu_gpu_log(&r->ctx, CU_LOG_INFO, "profiling: passes timed by %s%s", cu_pass_clock_describe(&r->prof),
                   soft ? " (a CPU rasteriser: its timestamps mark submission, not drawing)" : "");
    }
    memset(r->pass_ms, 0, sizeof r->pass_ms);
    if (r->prof.mode == CU_PASS_CLOCK_TIMESTAMPS) {
        cu_pass_clock_start(&r->prof, &r->gl);
        return;
    }
    r->gl.Finish(); /* what the host queued before the frame is not the frame's */
    r->prof_t = now_ms();
}

void cu_profile_mark(cu_renderer *r, int pass)
{
    if (!r->profile)
        return;
    if (r->prof.mode == CU_PASS_CLOCK_TIMESTAMPS) {
        cu_pass_clock_boundary(&r->prof, &r->gl, pass);
        return;
    }
    r->gl.Finish();
    double t = now_ms();
    r->pass_ms[pass] += t - r->prof_t;
    r->prof_t = t;
    r->profiled = 1;
}

void cu_profile_end(cu_renderer *r, int frame_ok)
{
    if (!r->profile || r->prof.mode != CU_PASS_CLOCK_TIMESTAMPS || !frame_ok)
        return;
    double ms[CU_PASS_COUNT] = {0};
    if (cu_pass_clock_finish(&r->prof, &r->gl, ms, CU_PASS_COUNT) == 0) {
        memcpy(r->pass_ms, ms, sizeof ms);
        r->profiled = 1;
    }
}
