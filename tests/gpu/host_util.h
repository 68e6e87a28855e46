/* tests/gpu/host_util.h: the embedding tests' host: an EGL context with a renderer (render_util.h), framebuffers
 * of its own (RGBA8 and RGBA32F colour sharing one depth texture), a quad drawn with depth at a chosen eye
 * distance, and the test scene (two ellipsoids on the view axis, noise off, so the CPU twin needs no noise). */
#ifndef CU_TEST_HOST_UTIL_H
#define CU_TEST_HOST_UTIL_H
#include "render_util.h"
#include <GLES3/gl3.h>

#define W 96
#define H 72
#define N (W * H)

extern tr_ctx host_ctx;
extern cu_scene *host_scene;
extern GLuint fbo8, fbo32, depth_tex, host_quad_prog; /* the quad's program, for the state test */
extern const char HOST_SCENE_TEXT[];
extern const float BLACK0[4];

/* cmocka group setup and teardown: the context, the scene set on the renderer, the framebuffers. */
int host_setup(void **st);
int host_teardown(void **st);
/* The host's matrices: the scene's view, a projection with the host's own planes. */
void host_matrices(float view[16], float proj[16], double znear, double zfar);
/* The host's frame: colour cleared to `bg`, depth cleared to 1, then (eye_dist > 0) a quad of colour `fg` at eye
 * distance eye_dist over the pixels x < W/2, written with depth under proj. */
void host_draw(GLuint fbo, const float bg[4], const float fg[4], double eye_dist, const float proj[16]);
/* cu_render, failing the test on an error. */
void host_render(cu_frame f);
/* Pixels of fbo, bottom row first (GL's order), as floats: 0-255 for RGBA8, radiance for RGBA32F. */
void host_read(GLuint fbo, int is_float, float *px);
/* The clouds' coverage per pixel: clouds only, linear, over transparent black; the host's quad at quad_dist
 * (0: none, and no depth texture). */
void host_coverage(float *alpha, double quad_dist, const float *view, const float *proj);
#endif
