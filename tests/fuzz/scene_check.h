/* tests/fuzz/scene_check.h: invariants of a scene the parser accepted, shared by the scene and --set fuzz targets. */
#ifndef CU_FUZZ_SCENE_CHECK_H
#define CU_FUZZ_SCENE_CHECK_H
#include "scene.h"

/* Every key's value is what its table row allows: numbers finite and in [lo, hi] (lo excluded when lo_open), whole
 * numbers multiples of `multiple`, enum and bool indices in range; 1 to CU_MAX_ELLIPSOIDS ellipsoids. */
void fuzz_scene_check(const cu_scene *s);

/* Writes s as a scene file, every key explicit, numbers with 17 digits (so they read back exactly). Returns the
 * length, or 0 when it does not fit in cap. */
size_t fuzz_scene_write(const cu_scene *s, char *buf, size_t cap);

/* fuzz_scene_write, then cu_scene_parse: the file must be accepted and read back s's values. Returns 1, or 0 when the
 * file is refused (with the message in why, for the caller's own check). */
int fuzz_scene_roundtrip(const cu_scene *s, char *why, size_t whylen);
#endif
