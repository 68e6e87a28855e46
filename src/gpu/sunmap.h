/* src/gpu/sunmap.h: CPU side of the sun's opacity map: how many separate in-cloud intervals a sun ray can cross (the
 * map's layer count follows the scene), and the sun-space frame shared with the shaders. */
#ifndef CU_SUNMAP_H
#define CU_SUNMAP_H
#include "density.h"

#define CU_SUN_TILES_MAX 4 /* light.sun_intervals' largest value: the most tiles of a peeled opacity map */

/* The most intervals of the ellipsoid union along the ray through any texel's centre of a size x size opacity map
 * (returned, uncapped), and for each j < tiles the texels (x0, y0, x1, y1, half-open) where the (j + 1)-th interval's
 * tile is drawn: j = 0 cu_sun_map_texels' box (every ray that meets the cloud), j > 0 the box of the texels whose
 * rays cross more than j intervals, a texel wider each way (empty: none does). Chords that overlap by less than
 * 1e-4 R count apart, so that fp32's union on the GPU finds no more intervals than these boxes hold. A ray a texel
 * of the first box, once per map made (a band a frame: at its first band); on the cumulus 1 % of the texels cross a
 * second interval, in a box a third of the first, which the tile of that interval was drawn over in full. */
int cu_sun_tile_boxes(const cu_cloud *cl, vec3 sun_dir, int size, int tiles, int boxes[][4]);
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
