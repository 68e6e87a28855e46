/* src/gpu/frame.h: the renderer's frame (frame.c) and its shadows (frame_shadow.c); private to src/gpu, as
 * renderer.h. */
#ifndef CU_FRAME_H
#define CU_FRAME_H
#include "renderer.h"

/* cu_render (include/cumulo.h) is frame.c's. */
/* Points the frame context at cloud sl: what the passes read of "the cloud". */
void cu_frame_bind_cloud(cu_renderer *r, cu_cloud_slot *sl);
/* Cloud i's shadow from the clouds between it and the sun, into its shadow map when that is out of date. */
int  cu_frame_cloud_shadow(cu_renderer *r, int i, cu_error *err);
/* The ground's shadow map about the camera (ctx->camera: the sky's), when out of date. */
int  cu_frame_ground_shadow(cu_renderer *r, cu_error *err);
/* Which visible clouds are drawn from impostors this frame (their imp.in_use), and their images made where due
 * (frame_impostor.c). */
int  cu_frame_impostors(cu_renderer *r, const cu_frame *f, int visible, cu_error *err);
#endif
