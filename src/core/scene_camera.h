/* src/core/scene_camera.h: the scene's [camera] as matrices (world -> eye view; see cumulo.h
 * cu_scene_camera_matrices for the public, float form). */
#ifndef CU_SCENE_CAMERA_H
#define CU_SCENE_CAMERA_H
#include "cumulo.h"
#include "scene.h"
#include "vecmath.h"

/* World -> eye, double precision: looking from cam_pos toward cam_look, y up. */
mat4 cu_scene_view(const cu_scene *s);
#endif
