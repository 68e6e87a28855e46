/* src/gpu/frame_budget.c: the frame budget in the renderer (see frame_budget.h): frames timed by frame_timer.c, rungs
 * chosen by budget.c, every change in the log with the median that caused it. */
#include "frame_budget.h"
#include "gpu_scene.h"

static int budget_on(const cu_renderer *r)
{
    return r->budget.n > 0 && r->budget.target_ms > 0;
}

void cu_frame_budget_scene(cu_renderer *r)
{
    const cu_scene *s = &r->scene;
    r->frame_d = s->cloud_downsample;
    r->frame_g = s->temporal_grid;
    cu_budget_init(&r->budget, s->target_fps, s->cloud_downsample, s->temporal_grid, s->max_downsample,
                   s->max_temporal_grid);
    if (!(s->target_fps > 0)) {
        r->budget.n = 0;
        return;
    }
    if (!r->timer_ready) {
        cu_frame_timer_init(&r->timer, &r->gl, r->desc.get_proc_address, r->desc.get_proc_user, r->is_gles,
                            !r->timer_no_queries);
        r->timer_ready = 1;
    }
    const cu_budget_rung *last = &r->budget.rung[r->budget.n - 1];
    cu_gpu_log(&r->ctx, CU_LOG_INFO, "frame budget: %g fps (%.1f ms a frame); clouds from 1/%d resolution, grid %d, "
               "to 1/%d, grid %d (%d rungs); timing: %s", s->target_fps, r->budget.target_ms, s->cloud_downsample,
               s->temporal_grid, last->downsample, last->grid, r->budget.n, cu_frame_timer_describe(&r->timer));
}

void cu_frame_budget_most(const cu_renderer *r, int *downsample, int *grid)
{
    if (budget_on(r)) {
        *downsample = r->budget.rung[r->budget.n - 1].downsample;
        *grid = r->budget.rung[r->budget.n - 1].grid;
    } else {
        *downsample = r->scene.cloud_downsample;
        *grid = r->scene.temporal_grid;
    }
}

void cu_frame_budget_before(cu_renderer *r)
{
    if (!budget_on(r))
        return;
    double ms;
    while (cu_frame_timer_poll(&r->timer, &r->gl, &ms)) {
        int was = r->budget.cur;
        if (!cu_budget_observe(&r->budget, ms))
            continue;
        const cu_budget_rung *g = &r->budget.rung[r->budget.cur];
        cu_gpu_log(&r->ctx, CU_LOG_INFO, "frame budget: frames take %.1f ms (median of %d) against %.1f ms: clouds "
                   "at 1/%d resolution, temporal grid %d (rung %d of %d, was %d)", r->budget.median_ms,
                   CU_BUDGET_WINDOW, r->budget.target_ms, g->downsample, g->grid, r->budget.cur + 1, r->budget.n,
                   was + 1);
    }
    r->frame_d = r->budget.rung[r->budget.cur].downsample;
    r->frame_g = r->budget.rung[r->budget.cur].grid;
}

void cu_frame_budget_begin(cu_renderer *r)
{
    if (budget_on(r))
        cu_frame_timer_begin(&r->timer, &r->gl);
}

void cu_frame_budget_end(cu_renderer *r)
{
    if (budget_on(r))
        cu_frame_timer_end(&r->timer, &r->gl);
}

int cu_renderer_budget(const cu_renderer *r, int *cloud_downsample, int *temporal_grid, double *frame_ms)
{
    *cloud_downsample = r->frame_d > 0 ? r->frame_d : 1;
    *temporal_grid = r->frame_g > 0 ? r->frame_g : 1;
    *frame_ms = budget_on(r) ? r->budget.median_ms : 0;
    return budget_on(r) ? 0 : 1;
}
