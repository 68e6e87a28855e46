/* src/gpu/camera.h: the frame's camera (gpu_scene.h cu_camera) from a view and a projection matrix: the host's
 * (cu_frame) or the scene's [camera] (scene_camera.h), rebased to the cloud's local frame. */
#ifndef CU_CAMERA_H
#define CU_CAMERA_H
#include "gpu_scene.h"

/* view: world -> eye, proj: eye -> clip (column-major, OpenGL); origin: the cloud's local frame in the world;
 * hull_r: radius about it that holds every hull. Fails, naming the problem, for a matrix that is not finite, a
 * singular view or a projection that is neither perspective nor orthographic. */
int cu_camera_build(cu_camera *c, mat4 view, mat4 proj, vec3 origin, double hull_r, cu_error *err);
/* Narrows c->ndc_rect to the image of a box (lo .. hi about origin, in the cloud's local frame) that holds the
 * cloud, where all its corners lie in front of the eye. */
void cu_camera_clip_rect(cu_camera *c, mat4 view, mat4 proj, vec3 origin, vec3 lo, vec3 hi);
/* The pixels of a width x height image about an NDC rectangle (x0, y0, x1, y1), grown by grow pixels on every side:
 * x0, y0, x1, y1, half-open, within the image (empty where the rectangle is). */
void cu_ndc_rect_pixels(const double ndc[4], int width, int height, int grow, int px[4]);
/* A float matrix as given by the host, or NULL. */
mat4 cu_camera_mat4(const float *m);
#endif
