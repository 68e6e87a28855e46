/* src/core/scene_write.h: a scene as the text of a scene file that parses back to the same values (every key the
 * scene holds, its clouds with their ellipsoids, its layers): what `cumulo expand` writes and the fuzzers read back. */
#ifndef CU_SCENE_WRITE_H
#define CU_SCENE_WRITE_H
#include "scene.h"
#include <stddef.h>

/* Writes s into buf (cap bytes, NUL-terminated) and returns its length, or 0 when it does not fit. */
size_t cu_scene_format(const cu_scene *s, char *buf, size_t cap);
#endif
