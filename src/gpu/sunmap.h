/* src/gpu/sunmap.h: CPU side of the sun's opacity map: how many separate in-cloud intervals a sun ray can cross (the
 * map's layer count follows the scene), and the sun-space frame shared with the shaders. */
#ifndef CU_SUNMAP_H
#define CU_SUNMAP_H
#include "density.h"

/* The most intervals of the ellipsoid union along any of grid x grid sun rays over the cloud's bounds. */
int cu_sun_max_intervals(const cu_cloud *cl, vec3 sun_dir, int grid);
/* Orthonormal basis of the sun plane (right, up), stable for every sun direction including the zenith. */
void cu_sun_basis(vec3 sun_dir, vec3 *right, vec3 *up);
/* Half-size R of the sun maps: the plane sits at 2R along the sun direction, depths span 4R. */
double cu_sun_radius(const cu_cloud *cl);
/* The texels (x0, y0, x1, y1, half-open) of a size x size map over [-R, R]^2 in the sun plane (right, up) whose rays
 * through their centres can meet an ellipsoid of cl, a texel wider each way; an empty box for none. */
void cu_sun_map_texels(const cu_cloud *cl, vec3 right, vec3 up, double R, int size, int box[4]);
/* Rows [rows[0], rows[1]) of band b (0 .. bands - 1) of a size-row map made again a band a frame: the rows [lo, hi)
 * of its box (cu_sun_map_texels) shared out evenly, the rows below the box going with the first band and those above
 * with the last (outside the box a band only clears), so that every band casts about as many rays. In order, the
 * bands cover [0, size) once; an empty box shares out the whole map. */
void cu_sun_band_rows(int size, int lo, int hi, int bands, int b, int rows[2]);
/* Number of union intervals along the ray o + t d, and their ends (up to max). */
int cu_union_intervals(const cu_cloud *cl, vec3 o, vec3 d, double *a, double *b, int max);
#endif
