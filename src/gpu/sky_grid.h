/* src/gpu/sky_grid.h: the sky pass's geometry on the CPU: the view direction at a point of the viewport, what a run of
 * rows holds (sky, ground, the horizon), and where quality.sky_grid's cells may grow because the sky bends little
 * there (cu_sky_grid_plan). No GL: pass_sky.c draws what these decide. */
#ifndef CU_SKY_GRID_H
#define CU_SKY_GRID_H
#include "sky.h"
#include "vecmath.h"

/* What rows hold, and the sky pass's programs by the rows they draw (sky.frag's SKY_PART): rows holding the horizon,
 * rows of sky alone, rows of ground alone. A software rasteriser runs both sides of a shader's branch on every pixel;
 * a program without the branch does not. */
enum { CU_SKY_BOTH, CU_SKY_ABOVE, CU_SKY_BELOW, CU_SKY_PARTS };
/* And for cu_sky_rows (the program of CU_SKY_ABOVE, the grid's cells lower): sky alone within CU_SKY_LOW_SINE
 * of the horizon, where the Perez sky's colour bends toward the horizon's within a few degrees (its zenith terms
 * e^(B / cos theta)): the grid's rows there are a quarter as high (within a level of the display where square cells
 * would be 3-5 off). */
#define CU_SKY_LOW 3
#define CU_SKY_LOW_SINE 0.0872 /* the sine of 5 degrees */

/* The bands of rows that each pick their cells (cu_sky_grid_plan), the largest cell, and the estimate's bound. */
#define CU_SKY_BAND 64
#define CU_SKY_BANDS (16384 / CU_SKY_BAND) /* output.size's largest */
#define CU_SKY_CELL_MAX 64
#define CU_SKY_GRID_REL 0.01
#define CU_SKY_GRID_LEVELS 0.3 /* of 255: the display's values interpolated (cu_sky_grid_toned) */
/* Finer grids keep their cells, the curve at every pixel: the plan's cost grows as 1 / N^2 (on this machine's CPU at
 * 800x480, before cells_fit shared corners: 0.2 ms at N = 16, 0.33 at 8, 0.7 at 4, 10.7 at 1; 0.145 at 16 after),
 * paid whenever the camera or the sun moves. */
#define CU_SKY_PLAN_LEAST 8

/* The view direction (unit) at the viewport's NDC (x, y) through the sky's matrix m (column-major, clip ->
 * direction), as sky.vert and sky.frag make it. */
vec3 cu_sky_dir(const float *m, double x, double y);
/* What the rows between NDC y0 and y1 hold (above). */
int cu_sky_rows(const float *m, double y0, double y1);

/* For each band of CU_SKY_BAND rows of a w x h viewport (from its bottom row), the scale (1, 2 or 4) of the grid's
 * cells over quality.sky_grid's `grid` pixels (the horizon's rows: grid wide, a quarter as high), in its rows of sky
 * alone (scale[b][0]) and in its rows near the horizon (scale[b][1]): the largest, at most CU_SKY_CELL_MAX pixels a
 * side, whose cells (laid as sky.vert lays them, two triangles each) interpolate the sky of the tables (cu_sky_tables:
 * zenith part, then sun part) within CU_SKY_GRID_REL of it in every channel, at a 3 x 3 lattice over the part of each
 * cell within the band's rows of that kind and at the centroids of its triangles; points in sun (x0, y0, x1, y1,
 * half-open pixels: drawn a pixel at a time) are not tested. Bands past the viewport, and every band of a grid finer
 * than CU_SKY_PLAN_LEAST, get 1. Returns how many cells the bands' rows of sky take (a measure for tests and logs). */
int cu_sky_grid_plan(const float *tables, vec3 sun_dir, const float *m, int w, int h, int grid, const int sun[4],
                     unsigned char scale[CU_SKY_BANDS][2]);
/* The same for cells that carry the display's values (a frame of sky alone: sky.vert with SKY_CORNER_TONE, the tone
 * curve at the corners instead of at every pixel): the largest scale (4, 2, 1) whose interpolated display values
 * stay within CU_SKY_GRID_LEVELS levels of the curve of the sky at the points tested; 0 where none does (the band
 * keeps the curve at every pixel, with cu_sky_grid_plan's cells). It may take smaller cells than that plan: on
 * llvmpipe the curve at every pixel costs more than the triangles (tools/bench/sky.sh). display: the exposure's scale
 * by channel (cu_out_scale) and the cap (cu_out_max). Returns the cells those bands take. */
int cu_sky_grid_toned(const float *tables, vec3 sun_dir, const float *m, int w, int h, int grid, const int sun[4],
                      const double display[4], unsigned char scale[CU_SKY_BANDS][2]);
#endif
