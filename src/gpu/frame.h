/* src/gpu/frame.h: the renderer's frame (frame.c), its clouds' maps (frame_maps.c) and shadows (frame_shadow.c);
 * private to src/gpu, as renderer.h. */
#ifndef CU_FRAME_H
#define CU_FRAME_H
#include "renderer.h"

/* cu_render (include/cumulo.h) is frame.c's. */
/* Points the frame context at cloud sl: what the passes read of "the cloud". */
void cu_frame_bind_cloud(cu_renderer *r, cu_cloud_slot *sl);
/* Cloud sl's sun and slab maps, made, or brought up to date for the sun and the noise now, whole or a band of rows
 * this frame; *budget counts the bands and maps this frame may still make (frame_maps.c). */
int  cu_frame_cloud_maps(cu_renderer *r, cu_cloud_slot *sl, int *budget, cu_error *err);
/* Cloud i's shadow from the clouds between it and the sun, into its shadow map when that is out of date. */
int  cu_frame_cloud_shadow(cu_renderer *r, int i, cu_error *err);
/* The ground's shadow map about the camera (ctx->camera: the sky's), when out of date. */
int  cu_frame_ground_shadow(cu_renderer *r, cu_error *err);
/* Which visible clouds are drawn from impostors this frame (their imp.in_use), and their images made where due
 * (frame_impostor.c). */
int  cu_frame_impostors(cu_renderer *r, const cu_frame *f, int visible, cu_error *err);
#endif
