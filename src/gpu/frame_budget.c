/* src/gpu/frame_budget.c: the frame budget in the renderer (see frame_budget.h): frames timed by frame_timer.c, rungs
 * chosen by budget.c, every change in the log with the median that caused it. */
#include "frame_budget.h"
#include <string.h>

int cu_frame_budget_on(const cu_frame_budget *b)
{
    return b->budget.n > 0 && b->budget.target_ms > 0;
}

void cu_frame_budget_scene(cu_frame_budget *b, const cu_scene *s, const cu_gpu_scene *ctx, cu_get_proc_fn get,
                           void *user, int is_gles)
{
    b->d = s->cloud_downsample;
    b->g = s->temporal_grid;
    cu_budget was = b->budget;
    cu_budget_init(&b->budget, s->target_fps, s->cloud_downsample, s->temporal_grid, s->max_downsample,
                   s->max_temporal_grid);
    if (!(s->target_fps > 0)) {
        b->budget.n = 0;
        return;
    }
    /* The same budget over a new scene (an image generator rebuilding its layers as the weather changes): where it
     * stood and what it measured stay, rather than walking the ladder again from the top. */
    if (was.n == b->budget.n && was.target_ms == b->budget.target_ms &&
        !memcmp(was.rung, b->budget.rung, sizeof was.rung)) {
        b->budget = was;
        b->d = b->budget.rung[b->budget.cur].downsample;
        b->g = b->budget.rung[b->budget.cur].grid;
        return;
    }
    if (!b->timer_ready) {
        cu_frame_timer_init(&b->timer, ctx->gl, get, user, is_gles, !b->no_queries);
        b->timer_ready = 1;
    }
    const cu_budget_rung *last = &b->budget.rung[b->budget.n - 1];
    cu_gpu_log(ctx, CU_LOG_INFO, "frame budget: %g fps (%.1f ms a frame); clouds from 1/%d resolution, grid %d, "
               "to 1/%d, grid %d (%d rungs); timing: %s", s->target_fps, b->budget.target_ms, s->cloud_downsample,
               s->temporal_grid, last->downsample, last->grid, b->budget.n, cu_frame_timer_describe(&b->timer));
}

void cu_frame_budget_most(const cu_frame_budget *b, const cu_scene *s, int *downsample, int *grid)
{
    if (cu_frame_budget_on(b)) {
        *downsample = b->budget.rung[b->budget.n - 1].downsample;
        *grid = b->budget.rung[b->budget.n - 1].grid;
    } else {
        *downsample = s->cloud_downsample;
        *grid = s->temporal_grid;
    }
}

void cu_frame_budget_before(cu_frame_budget *b, const cu_gpu_scene *ctx)
{
    if (!cu_frame_budget_on(b))
        return;
    double ms;
    while (cu_frame_timer_poll(&b->timer, ctx->gl, &ms)) {
        int was = b->budget.cur;
        if (!cu_budget_observe(&b->budget, ms))
            continue;
        const cu_budget_rung *g = &b->budget.rung[b->budget.cur];
        cu_gpu_log(ctx, CU_LOG_INFO, "frame budget: frames take %.1f ms (median of %d) against %.1f ms: clouds at "
                   "1/%d resolution, temporal grid %d (rung %d of %d, was %d)", b->budget.median_ms,
                   CU_BUDGET_WINDOW, b->budget.target_ms, g->downsample, g->grid, b->budget.cur + 1, b->budget.n,
                   was + 1);
    }
    b->d = b->budget.rung[b->budget.cur].downsample;
    b->g = b->budget.rung[b->budget.cur].grid;
}

void cu_frame_budget_begin(cu_frame_budget *b, const cu_gl *gl)
{
    if (cu_frame_budget_on(b))
        cu_frame_timer_begin(&b->timer, gl);
}

void cu_frame_budget_end(cu_frame_budget *b, const cu_gl *gl)
{
    if (cu_frame_budget_on(b))
        cu_frame_timer_end(&b->timer, gl);
}

void cu_frame_budget_free(cu_frame_budget *b, const cu_gl *gl)
{
    if (b->timer_ready)
        cu_frame_timer_free(&b->timer, gl);
    b->timer_ready = 0;
}
