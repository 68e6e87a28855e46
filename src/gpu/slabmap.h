/* src/slabmap.h: GPU side of the multiple-scattering slab model (see slabmap.c). */
#ifndef CU_SLABMAP_H
#define CU_SLABMAP_H
#include "renderer.h"

/* Decides the MS mode in use (slab needs half-float targets) and loads data/slab_fit_bouthors.txt when needed. */
int cu_slab_load(cu_renderer *r, cu_error *err);
/* The shader defines of the loaded model (node counts, SKY_SPLIT); non-zero when buf is too small. */
int cu_slab_defines(const cu_renderer *r, char *buf, size_t n);
/* Table texture, slab-map program (built with `defines`), maps and framebuffers. */
int cu_slab_targets(cu_renderer *r, const char *defines, cu_error *err);
void cu_slab_delete(cu_renderer *r);
/* Renders slab map 0 (from the sun) or 1 (from the zenith) and its mip chain. */
void cu_slab_render(cu_renderer *r, int which);
/* Uniforms of ms_slab.glsl and the cloud pass's slab samplers (texture units 4-8), and binding those units. */
void cu_slab_uniforms(cu_renderer *r, GLuint p);
void cu_slab_bind(cu_renderer *r);
#endif
