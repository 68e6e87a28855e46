/* src/gpu/target.h: a render target, one or two textures with their framebuffer: what every pass draws into. */
#ifndef CU_TARGET_H
#define CU_TARGET_H
#include "gl.h"

typedef struct cu_target_desc {
    const char *name;   /* for messages, e.g. "sun opacity map" */
    int width, height;
    GLenum format;      /* GL_RGBA32F, GL_RGBA16F, GL_RGBA8 (colour) or GL_DEPTH_COMPONENT32F (depth only) */
    int colors;         /* colour textures, on COLOR0.. (1 or 2); ignored for a depth format */
    int mipmaps;        /* the whole chain, trilinear and clamped (read at a blur's level); else one NEAREST level */
    int depth_stencil;  /* a DEPTH24_STENCIL8 renderbuffer besides the colour */
} cu_target_desc;

typedef struct cu_target {
    GLuint fbo, tex[2], rb;
    int width, height;
    GLenum format;
} cu_target;

/* Allocates the textures, attaches them and checks completeness; an error names the target, its size and format.
 * Leaves framebuffer 0 bound. On failure nothing is left allocated. */
int cu_target_create(cu_target *t, const cu_gl *gl, const cu_target_desc *d, cu_error *err);
/* Deletes what was created (safe on a zeroed or deleted target) and zeroes it. */
void cu_target_delete(cu_target *t, const cu_gl *gl);
#endif
