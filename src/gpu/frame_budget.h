/* src/gpu/frame_budget.h: the renderer's side of the frame budget (quality.target_fps): the controller of
 * src/core/budget.c fed by the frame timer, each change logged, and the resolution and grid a frame is drawn at. */
#ifndef CU_FRAME_BUDGET_H
#define CU_FRAME_BUDGET_H
#include "budget.h"
#include "frame_timer.h"
#include "gpu_scene.h"

typedef struct cu_frame_budget {
    cu_budget budget;     /* the controller (budget.n = 0: no budget) */
    cu_frame_timer timer; /* how it measures a frame, made with the first budget (timer_ready) */
    int timer_ready;
    int no_queries;       /* tests: the wall clock even where timer queries exist */
    int d, g;             /* this frame's cloud_downsample and temporal_grid: the scene's or the budget's */
} cu_frame_budget;

/* At cu_renderer_set_scene: the ladder from the scene's cloud_downsample and temporal_grid to its maxima (off when
 * target_fps is 0), the timer made the first time a budget is set (get, user: the renderer's GL loader). */
void cu_frame_budget_scene(cu_frame_budget *b, const cu_scene *s, const cu_gpu_scene *ctx, cu_get_proc_fn get,
                           void *user, int is_gles);
/* The coarsest resolution and grid this scene may be drawn at: what its passes and shaders are made for. */
void cu_frame_budget_most(const cu_frame_budget *b, const cu_scene *s, int *downsample, int *grid);
/* Before a frame: the frames measured since the last one go to the controller; b->d and b->g are set. */
void cu_frame_budget_before(cu_frame_budget *b, const cu_gpu_scene *ctx);
/* Around the frame's GL work. */
void cu_frame_budget_begin(cu_frame_budget *b, const cu_gl *gl);
void cu_frame_budget_end(cu_frame_budget *b, const cu_gl *gl);
/* 1 when a budget is set. */
int  cu_frame_budget_on(const cu_frame_budget *b);
void cu_frame_budget_free(cu_frame_budget *b, const cu_gl *gl);
#endif
