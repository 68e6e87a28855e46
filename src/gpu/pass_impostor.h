/* src/gpu/pass_impostor.h: impostors (quality.impostor_pixels): a cloud small on screen drawn from an image the cloud
 * pass made of it from the eye, kept while the view of it barely changes. This pass draws that image on a square
 * through the cloud's centre; frame_impostor.c decides when an image is made again and makes it. */
#ifndef CU_PASS_IMPOSTOR_H
#define CU_PASS_IMPOSTOR_H
#include "gpu_scene.h"
#include "target.h"

/* One cloud's impostor, in the cloud's local frame (it moves with the cloud). */
typedef struct cu_impostor {
    cu_target image;       /* size x size, premultiplied, the cloud pass's units */
    int size;
    int valid, in_use;     /* made and still the cloud's look; drawn from it the last frame the cloud was seen */
    unsigned long seen;    /* the renderer's frame_no when it was last drawn from it */
    vec3 axis, u, v;       /* unit: from the eye it was made from to the centre; the image's right and up */
    double half;           /* m: half the square's side (the image's frustum at the centre) */
    vec3 sun, boil;        /* the cloud's maps_sun and boil it was made with */
    double factor;         /* ... its density factor (life cycle) */
    uint64_t shadow_sig;   /* ... the other clouds' shadow on it (0: none) */
    int linear;            /* ... made for linear output */
} cu_impostor;

typedef struct cu_pass_impostor {
    GLuint prog, sampler;
    GLint rot_vp, corner0, du, dv, motion, image;
} cu_pass_impostor;

/* defs: the scene's hull defines (TEMPORAL is what it reads). */
int  cu_pass_impostor_create(cu_pass_impostor *p, const cu_gpu_scene *ctx, const char *defs, cu_error *err);
void cu_pass_impostor_destroy(cu_pass_impostor *p, const cu_gl *gl);
/* The image's target at `size` texels a side (made again when the size or format changes); bound, cleared, with
 * the viewport set, ready for the cloud pass. */
int  cu_pass_impostor_begin(cu_impostor *im, const cu_gpu_scene *ctx, int size, GLenum format, cu_error *err);
/* Draws cloud ctx->cloud from its impostor with ctx->camera (this frame's, cloud-local), premultiplied over what the
 * bound target holds. */
void cu_pass_impostor_draw(const cu_pass_impostor *p, const cu_gpu_scene *ctx, const cu_impostor *im);
void cu_impostor_free(cu_impostor *im, const cu_gl *gl);
#endif
