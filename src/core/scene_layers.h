/* src/core/scene_layers.h: a scene's [layer]s as clouds: each generated cloud (src/core/layer.c) with the values a
 * written cloud would have (the layer's wind and lifetime, a life phase and a noise offset of its own), so the
 * renderer draws them and `cumulo expand` writes them out as plain [cloud] sections. */
#ifndef CU_SCENE_LAYERS_H
#define CU_SCENE_LAYERS_H
#include "scene.h"

typedef struct cu_generated {
    cu_cloud_spec *spec;  /* n_clouds, every value given (has_* = 1); first/count index ell */
    cu_ellipsoid *ell;
    int n_clouds, n_ell;
} cu_generated;

/* Every cloud of every [layer] of s (none: empty). Deterministic: the same scene, the same list, bit for bit. */
int  cu_scene_generate(const cu_scene *s, cu_generated *out, cu_error *err);
void cu_generated_free(cu_generated *g);
/* cu_scene_expand (include/cumulo.h) replaces s's layers by these clouds. */
#endif
