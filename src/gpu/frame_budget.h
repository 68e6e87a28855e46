/* src/gpu/frame_budget.h: the renderer's side of the frame budget (quality.target_fps): the controller of
 * src/core/budget.c fed by the frame timer, each change logged, and the resolution and grid a frame is drawn at. */
#ifndef CU_FRAME_BUDGET_H
#define CU_FRAME_BUDGET_H
#include "renderer.h"

/* At cu_renderer_set_scene: the ladder from the scene's cloud_downsample and temporal_grid to its maxima (off when
 * target_fps is 0), the timer made the first time a budget is set. */
void cu_frame_budget_scene(cu_renderer *r);
/* The finest and coarsest resolution and grid this scene may be drawn at: what its passes and shaders are made for. */
void cu_frame_budget_most(const cu_renderer *r, int *downsample, int *grid);
/* Before a frame: the frames measured since the last one go to the controller; r->frame_d and r->frame_g are set. */
void cu_frame_budget_before(cu_renderer *r);
/* Around the frame's GL work. */
void cu_frame_budget_begin(cu_renderer *r);
void cu_frame_budget_end(cu_renderer *r);
#endif
