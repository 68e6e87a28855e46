/* src/gpu/pass_temporal.h: quality.temporal_grid: each frame marches one cloud pixel of every G x G block, in a
 * Bayer order, into a small target of its own (through a projection shifted onto those pixels), and the resolve
 * (temporal.frag) makes the whole cloud image from them and last frame's image reprojected (the camera's motion,
 * each cloud's wind, the distance where the ray enters the cloud). History is dropped, and the frame marched whole,
 * when it cannot be trusted: the first frame, a new scene, a size change, the sun moving more than 0.25 degree
 * since the last frame, the camera inside a cloud's hull or orthographic. */
#ifndef CU_PASS_TEMPORAL_H
#define CU_PASS_TEMPORAL_H
#include "gpu_scene.h"
#include "target.h"

typedef struct cu_temporal_locs {
    GLint grid, offset, size, inv_rot, prev_rot, eye_delta, moved;
} cu_temporal_locs;

typedef struct cu_pass_temporal {
    GLuint prog[2];            /* the resolve reading the history texel by texel, and through the texture unit */
    cu_temporal_locs loc[2];
    cu_target sparse;          /* this frame's marched pixels: colour, alpha x (distance, motion); depth-stencil */
    cu_target hist[2];         /* the cloud image, this frame's and the last one's, the same layout */
    int cur;                   /* hist[cur]: the newest image */
    int valid;                 /* hist[cur] may be reprojected */
    int grid;                  /* G of hist */
    unsigned long frame;       /* frames since the history was made whole: the Bayer position */
    int sparse_now;            /* this frame marches the sparse pixels (else the whole image into hist[cur ^ 1]) */
    int ox, oy;                /* this frame's pixel of each block */
    float prev_rot_vp[16];     /* last frame's directions -> clip (camera at the origin) */
    vec3 prev_eye, prev_sun;   /* world */
    double prev_time;          /* the scene time last frame showed */
} cu_pass_temporal;

int  cu_pass_temporal_create(cu_pass_temporal *p, const cu_gpu_scene *ctx, cu_error *err);
void cu_pass_temporal_destroy(cu_pass_temporal *p, const cu_gl *gl);
/* Drops the history: the next frame is marched whole (a new scene, a jump of the sun). */
void cu_pass_temporal_reset(cu_pass_temporal *p);
/* Starts a frame of the cloud image lw x lh with grid g: decides whether it can be sparse (trust: the history is
 * valid for the same size and grid, the sun within 0.25 degree of last frame's, and the caller's `whole` is 0), makes
 * the targets and binds the one the cloud pass draws into, cleared, with its viewport: the sparse target (1 is
 * returned in *sparse, the pixel of each block in p->ox, p->oy) or the next history image. */
int  cu_pass_temporal_begin(cu_pass_temporal *p, const cu_gpu_scene *ctx, int lw, int lh, int g, GLenum format,
                            int whole, int *sparse, cu_error *err);
/* The projection that puts the sparse target's pixel (i, j) on the cloud image's pixel (g i + ox, g j + oy). */
mat4 cu_pass_temporal_projection(const cu_pass_temporal *p, mat4 proj, int lw, int lh);
/* Ends the frame: resolves the sparse pixels with the history (when sparse) into the next image, makes it the
 * newest and remembers this frame's camera (cam: the view's, at the world origin, unshifted), sun and time. Only
 * about ndc_rect (x0, y0, x1, y1: where the clouds can be) is resolved; the rest of the image is cleared: no fresh
 * sample there sees a cloud, and a history there is a cloud that has left. */
void cu_pass_temporal_end(cu_pass_temporal *p, const cu_gpu_scene *ctx, const cu_camera *cam, double time,
                          const double ndc_rect[4]);
/* The newest cloud image (premultiplied radiance, alpha) for the upsampling. */
GLuint cu_pass_temporal_image(const cu_pass_temporal *p);
#endif
