/* src/gpu/glstate.h: the GL state a cumulo call may change, saved on entry and restored on exit, so a host's
 * renderer finds its state as it left it (the list is README "Embedding in your renderer"). */
#ifndef CU_GLSTATE_H
#define CU_GLSTATE_H
#include "gl.h"

/* Texture units cumulo binds (gpu_scene.h's CU_UNIT_*, the host depth unit included). */
#define CU_GLSTATE_UNITS 15

typedef struct cu_glstate {
    GLint draw_fbo, read_fbo, program, vao, array_buffer, renderbuffer, active_texture;
    GLint tex2d[CU_GLSTATE_UNITS], tex3d[CU_GLSTATE_UNITS], sampler[CU_GLSTATE_UNITS];
    GLint viewport[4], scissor_box[4];
    GLboolean blend, depth_test, stencil_test, cull_face, scissor_test, polygon_offset, rasterizer_discard;
    GLboolean alpha_to_coverage, sample_coverage;
    GLint blend_src_rgb, blend_dst_rgb, blend_src_a, blend_dst_a, blend_eq_rgb, blend_eq_a;
    GLboolean depth_mask, color_mask[4];
    GLint depth_func;
    GLint stencil_func[2], stencil_ref[2], stencil_value_mask[2], stencil_writemask[2];
    GLint stencil_fail[2], stencil_zfail[2], stencil_zpass[2]; /* [0] front, [1] back */
    GLfloat clear_color[4], clear_depth;
    GLint clear_stencil, pack_alignment, unpack_alignment;
} cu_glstate;

/* Records the state, then sets what cumulo's passes assume and a host may have changed (no scissor, no polygon
 * offset, no rasterizer discard, no coverage from alpha, additive blend equations, every colour channel written). */
void cu_glstate_enter(const cu_gl *gl, cu_glstate *s);
/* Puts back everything cu_glstate_enter recorded. */
void cu_glstate_leave(const cu_gl *gl, const cu_glstate *s);
#endif
