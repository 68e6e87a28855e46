/* src/core/cumulus_type.h: what a cumulus type is (humilis, mediocris, congestus: sizes, aspect, ellipsoid counts)
 * and how one cloud of it is made: a deterministic random stream, a power-law size, its ellipsoid cluster. The
 * layer generator (layer.c) places such clouds. */
#ifndef CU_CUMULUS_TYPE_H
#define CU_CUMULUS_TYPE_H
#include <stdint.h>

#define CU_LAYER_MAX_PER_CLOUD 16    /* ellipsoids per cloud, at most */
#define CU_LAYER_MIN_RADIUS 20.0     /* m, every ellipsoid radius is at least this */
/* Exponent b of the footprint diameter density N(D) ~ D^-b every type draws from (the sources are in layer.c). */
#define CU_LAYER_SIZE_EXPONENT 1.7

typedef enum cu_cumulus_type { CU_CUMULUS_HUMILIS, CU_CUMULUS_MEDIOCRIS, CU_CUMULUS_CONGESTUS } cu_cumulus_type;
#define CU_CUMULUS_TYPES 3

/* What a type's clouds look like; the generator reads only this table (layer.c, with the reasons for each range). */
typedef struct cu_cumulus_info {
    const char *name;              /* "cumulus-humilis", ... as the scene file spells it */
    double d_min, d_max;           /* m, range of footprint diameters D the power law is truncated to */
    double aspect_min, aspect_max; /* height / D, drawn uniformly per cloud, then clipped to the layer thickness */
    int ell_min, ell_max;          /* ellipsoids per cloud, drawn uniformly */
} cu_cumulus_info;

/* The table row of t, or NULL for a value outside the enum. */
const cu_cumulus_info *cu_cumulus_type_info(cu_cumulus_type t);
/* "cumulus-humilis" | "cumulus-mediocris" | "cumulus-congestus" (exact, case-sensitive): 0 and *out set; non-zero
 * for anything else (NULL included), *out untouched. */
int cu_cumulus_type_parse(const char *name, cu_cumulus_type *out);
/* The name parse accepts, or "unknown" for a value outside the enum. */
const char *cu_cumulus_type_name(cu_cumulus_type t);

/* One cloud's ellipsoids relative to its footprint centre: off = (dx, height of the centre above the base, dz). */
typedef struct cu_layer_shape {
    int n;
    double off[CU_LAYER_MAX_PER_CLOUD][3], r[CU_LAYER_MAX_PER_CLOUD][3];
    double radius, height;
} cu_layer_shape;

/* splitmix64: the next 64 bits of stream *s; a uniform double in [0, 1); in [lo, hi); a unit vector in the xz plane. */
uint64_t cu_layer_rng_next(uint64_t *s);
double cu_layer_rng_unit(uint64_t *s);
double cu_layer_rng_range(uint64_t *s, double lo, double hi);
void cu_layer_rng_dir(uint64_t *s, double *x, double *z);
/* d rounded to 1/16 m (sizes and positions: a last-ulp libm difference rarely changes one). */
double cu_layer_quantize(double d);
/* A footprint diameter from the truncated power law between lo and hi (m), rounded to 1/16 m. */
double cu_layer_draw_size(uint64_t *s, double lo, double hi);
/* The ellipsoids of a cloud of type t and diameter d (m) under a layer of the given thickness, from its seed. */
void cu_layer_build_shape(cu_cumulus_type t, double d, double thickness, uint64_t seed, cu_layer_shape *sh);
/* The area (m^2) of the shape's footprint seen from above, each ellipse shrunk by margin. */
double cu_layer_shape_area(const cu_layer_shape *sh, double margin);
#endif
