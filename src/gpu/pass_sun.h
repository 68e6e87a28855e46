/* src/gpu/pass_sun.h: the sun pass: the map of the sun's transmittance through the clouds, by the scene's method
 * (front depth, peeled opacity map, opacity shadow map, Fourier opacity map; DESIGN.md "Sun transmittance"). */
#ifndef CU_PASS_SUN_H
#define CU_PASS_SUN_H
#include "gpu_scene.h"
#include "target.h"

typedef struct cu_pass_sun {
    int method;           /* CU_SHADOW_*: ctx->shadow when created */
    GLuint prog;          /* front: hulls (sun_depth.frag); else one full-screen pass over the map's tiles */
    cu_density_locs density;
    cu_sun_locs sun;
    GLint viewproj;       /* front only */
    cu_target_desc map_desc; /* each cloud's map (front: the depth map; osm, fom: tiles; peel: interval layers [0]
                                and tau [1]) */
    int tiles;            /* osm: 1 + slices / 4; fom: 1 + N / 2 for N coefficients; peel: the most intervals */
} cu_pass_sun;

/* Builds the program (hull_defs for the front map's hull program, fs_defs for the full-screen ones). */
int cu_pass_sun_create(cu_pass_sun *p, const cu_gpu_scene *ctx, const char *hull_defs, const char *fs_defs,
                       cu_error *err);
void cu_pass_sun_destroy(cu_pass_sun *p, const cu_gl *gl);
/* A cloud's map of size x size texels a tile (the cloud owns it: cu_target_delete) and what the cloud pass reads of
 * it. */
int cu_pass_sun_map_create(const cu_pass_sun *p, const cu_gl *gl, int size, cu_target *map, cu_sun_maps *out,
                           cu_error *err);
/* The scissor a band of a map's rows is drawn with: rows [rows[0], rows[1]) of every tile; none for rows NULL. */
void cu_sun_band_scissor(const cu_gl *gl, const int rows[2]);
/* The bound full-screen program over `tiles` tiles side by side of a map seen along right x up (sun_size texels a
 * tile, over ctx->sun_R), in their rows [rows[0], rows[1]) (NULL: all), only in the box of texels whose rays can meet
 * ctx->cloud (cu_sun_map_texels), or with boxes, tile j in boxes[j] (cu_sun_tile_boxes): the caller has set the
 * others to what a ray meeting nothing gives. Leaves the band's scissor (cu_sun_band_scissor). */
void cu_sun_map_tiles(const cu_gpu_scene *ctx, vec3 right, vec3 up, int tiles, const int rows[2],
                      const int (*boxes)[4]);
/* Renders ctx->cloud's map for ctx's sun direction and updates out: its rows [rows[0], rows[1]) (a band of them,
 * frame_maps.c), or all (rows NULL). Bands are drawn in order from row 0 with one sun: a band after the first keeps
 * the interval count (peel's tiles) that out holds from it. Leaves the scissor test on those rows (every tile), or
 * off for all. */
void cu_pass_sun_update(const cu_pass_sun *p, const cu_gpu_scene *ctx, const cu_target *map, const int rows[2],
                        cu_sun_maps *out);
#endif
