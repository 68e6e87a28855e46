/* src/core/layer.h: generated cumulus layers: a field of clouds of one type (humilis, mediocris, congestus), each a
 * cluster of ellipsoids with a flat base, placed without overlap on a periodic square so that a layer can drift with
 * the wind and wrap. Pure CPU, deterministic for a seed; the scene parser calls it, it knows nothing of cu_scene. */
#ifndef CU_LAYER_H
#define CU_LAYER_H
#include "cumulo.h"
#include "cumulus_type.h"
#include <stdint.h>

/* The ranges cu_layer_generate accepts, one place for the parser, the docs and the tests (m unless stated). */
#define CU_LAYER_BASE_MIN 0.0
#define CU_LAYER_BASE_MAX 20000.0
#define CU_LAYER_THICKNESS_MIN 50.0
#define CU_LAYER_THICKNESS_MAX 15000.0
#define CU_LAYER_EXTENT_MIN 100.0
#define CU_LAYER_EXTENT_MAX 500000.0
#define CU_LAYER_MAX_CLOUDS 20000    /* a layer needing more clouds than this is an error, not an allocation */


/* World axes: x east, y up, z south. Every field is checked by cu_layer_generate; zero is not a default. */
typedef struct cu_layer_spec {
    cu_cumulus_type type;
    double base;      /* m, cloud base height above the ground, [0, 20000] */
    double thickness; /* m, from the base to the tallest tops the layer allows, [50, 15000] */
    double coverage;  /* 0..1, fraction of the extent's area covered seen from straight above (counted as
                         cu_layer_coverage does: footprints shrunk by margin) */
    double extent;    /* m, side of the square centred on the origin the layer tiles periodically, [100, 500000] */
    double margin;    /* m, >= 0: how far inside a hull the visible edge sits (the renderer passes its boundary
                         thickness h/2); coverage counts footprints shrunk by this */
    uint64_t seed;    /* same seed and spec, same layer, bit for bit */
} cu_layer_spec;

typedef struct cu_layer_ellipsoid {
    double center[3]; /* m, world: the cloud's footprint centre plus an offset, not wrapped (a cloud near the edge
                         overhangs the square; its overhang belongs at the opposite side) */
    double radii[3];  /* m, along world x, y, z; each >= CU_LAYER_MIN_RADIUS */
} cu_layer_ellipsoid;

typedef struct cu_layer_cloud {
    double center[3]; /* m: footprint centre, x and z in [-extent/2, extent/2), y = spec base */
    double radius;    /* m: footprint radius, the bounding circle of its ellipsoids seen from above; footprints of
                         two clouds never overlap under the periodic (wrapped) distance */
    double height;    /* m: from the base to the highest top, <= spec thickness */
    int first, count; /* its ellipsoids: ell[first .. first + count - 1], count in [ell_min, ell_max] of its type */
    uint64_t seed;    /* per cloud, for the renderer's noise offset and life cycle phase */
} cu_layer_cloud;

typedef struct cu_layer {
    cu_layer_cloud *clouds;  /* n_clouds, in placement order: largest first, then any smaller clouds that filled
                                the gaps left where larger ones had to shrink */
    int n_clouds;
    cu_layer_ellipsoid *ell; /* n_ell, each cloud's run contiguous, base row (bottoms at the base) first */
    int n_ell;
} cu_layer;

/* Validates spec (a message naming the field), then draws and places the clouds. 0 on success; non-zero with *err
 * filled and *out empty (NULL arrays, zero counts) otherwise. coverage 0 gives no clouds. Coverage a packing cannot
 * reach (near 1) is not an error: the layer stops, after bounded work, at the most it could place. */
int cu_layer_generate(const cu_layer_spec *spec, cu_layer *out, cu_error *err);
/* Frees the arrays and empties *l; l may be NULL or already empty. */
void cu_layer_free(cu_layer *l);
/* Covered fraction of the extent seen from straight above, sampled at the centres of a grid x grid raster (grid in
 * [1, 8192]): a cell counts when it lies in some ellipsoid's footprint ellipse with semi-axes shrunk by
 * spec->margin, positions wrapped periodically onto the square. -1 for a bad grid or spec, or out of memory. */
double cu_layer_coverage(const cu_layer *l, const cu_layer_spec *spec, int grid);
#endif
