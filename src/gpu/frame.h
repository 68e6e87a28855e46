/* src/gpu/frame.h: the renderer's frame (frame.c), its clouds' maps (frame_maps.c) and shadows (frame_shadow.c,
 * frame_ground.c); private to src/gpu, as renderer.h. */
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
/* The ground's shadow maps about the camera (ctx->camera: the sky's), when out of date (frame_ground.c). */
int  cu_frame_ground_shadow(cu_renderer *r, cu_error *err);
/* FNV-1a over what a shadow map depends on, so it is remade only when that changed: 64 bits, or a value rounded. */
uint64_t cu_sig_bits(uint64_t h, uint64_t q);
uint64_t cu_sig_add(uint64_t h, double v);
/* The texels [x0, x1) x [y0, y1) of a size-texel map of half-side R about its centre (axes ax, ay on the plane of
 * normal n through it) that cloud cl can shade along the sun sd, its origin at rel from the centre: where the
 * corners of the cloud's box fall along sd. Tighter than its bounding sphere's disc for the wide, flat clouds of a
 * layer (a third of the texels on field_noon's ground), and as conservative: no ray outside it meets an ellipsoid. */
void cu_shadow_box_rect(const cu_cloud *cl, vec3 rel, vec3 sd, vec3 n, vec3 ax, vec3 ay, double R, int size,
                        int rect[4]);
/* Which visible clouds are drawn from impostors this frame (their imp.in_use), and their images made where due
 * (frame_impostor.c). */
int  cu_frame_impostors(cu_renderer *r, const cu_frame *f, int visible, cu_error *err);
#endif
