/* src/gpu/pass_sky.h: the sky pass: one full-screen triangle of analytic sky (Preetham, through the Perez tables of
 * cu_sky_tables, rebuilt when the sky changes) or constant sky, the sun disk and the ground, under the clouds
 * (shaders_gles/sky.frag). */
#ifndef CU_PASS_SKY_H
#define CU_PASS_SKY_H
#include "gpu_scene.h"
#include "sky_grid.h"

typedef struct cu_sky_locs {
    cu_sun_locs sun;
    GLint inv_viewproj, sun_irr, out_max, ground, out_scale, sky_color;
    GLint ground_sun, eye, gmap, gmap2, shadow_g, cloud_factor, refined_on;
    GLint grid_box, grid_cell, grid_size, grid_cols;
} cu_sky_locs;

/* The programs by kind: radiance into the HDR target under the clouds; the display's colours straight into the
 * output (the tone map's curve in the same pass: one full-screen pass, not two), beside a cloud image composited;
 * the same with the image composited on the way; and for a frame with no cloud in view, the display's colours with
 * the curve taken at the grid's corners where the plan allows (sky_grid.h cu_sky_grid_toned; elsewhere as OUT). */
enum { CU_SKY_HDR, CU_SKY_OUT, CU_SKY_OVER, CU_SKY_ALONE, CU_SKY_KINDS };
/* And by the rows they draw (sky_grid.h: CU_SKY_BOTH, CU_SKY_ABOVE, CU_SKY_BELOW). */
/* And by how many of the ground's shadow maps hold shadows (gpu_scene.h ground_maps: 0 to CU_GROUND_MAPS); and by
 * where the colour is worked out (sky.vert's SKY_VERTEX): at every pixel; at the corners of quality.sky_grid's cells
 * (rows of the Perez sky alone; the sun's disk then drawn over a pixel at a time); once, for a colour the same at every
 * pixel (the ground where no shadow map reaches, a constant sky with its sun's disk drawn over). */
enum { CU_SKY_PIXEL, CU_SKY_GRID, CU_SKY_FLAT, CU_SKY_SHAPES };
#define CU_SKY_PLAN_KEY 23 /* the plan's key: the sky's matrix (16), the sun (3), size (2), grid, tables_made */
typedef struct cu_pass_sky {
    /* [kind][CU_SKY_BOTH][0][0] made at once, the others when first drawn */
    GLuint prog[CU_SKY_KINDS][CU_SKY_PARTS][CU_GROUND_MAPS + 1][CU_SKY_SHAPES];
    cu_sky_locs loc[CU_SKY_KINDS][CU_SKY_PARTS][CU_GROUND_MAPS + 1][CU_SKY_SHAPES];
    char defines[2048];         /* the scene's, for the programs made later */
    GLuint tables;              /* RGBA32F CU_SKY_TABLE x 2: the zenith factor (row 0), the sun factor (row 1) */
    double tables_of[21];       /* the Perez coefficients, zenith values and norms they were built from */
    int tables_built;
    unsigned tables_made;       /* how many times they were built: the plans below key on it */
    float table[2 * 4 * CU_SKY_TABLE]; /* the same tables on the CPU (grid_plan's estimate) */
    unsigned char scale[CU_SKY_BANDS][2]; /* the grid's cells by band of rows (cu_sky_grid_plan) */
    unsigned char toned[CU_SKY_BANDS][2]; /* with the curve at their corners (cu_sky_grid_toned; 0: at every pixel) */
    double plan_of[CU_SKY_PLAN_KEY];  /* what scale was made for: the sky's matrix, the sun, the tables, size, grid */
    double toned_of[CU_SKY_PLAN_KEY + 4]; /* what toned was made for: the same, the exposure and the cap (made only
                                           * for CU_SKY_ALONE, so a frame with clouds keeps it for the next without) */
    double toned_ask[CU_SKY_PLAN_KEY + 4]; /* what the last frame of sky alone asked toned for (pass_sky.c plan) */
    int plan_made, toned_made, toned_asked;
    int toned_now;              /* this frame takes toned: it asks what the last frame of sky alone asked */
    long plans, toned_plans;    /* how many of each were made (a test's window on the cache) */
    int toned_runs;             /* runs of rows the last draw gave the curve at the corners (CU_SKY_ALONE) */
    int refined;                /* within cu_pass_sky_draw_over: an edge refinement image is bound (pass_refine.h) */
} cu_pass_sky;

int cu_pass_sky_create(cu_pass_sky *p, const cu_gpu_scene *ctx, const char *defines, cu_error *err);
void cu_pass_sky_destroy(cu_pass_sky *p, const cu_gl *gl);
/* Draws into the bound target, whose viewport is ctx->width x ctx->height, for the directions of ctx->camera:
 * radiance, or (to_output) tone-mapped colour. Fails only where a program could not be made. */
int cu_pass_sky_draw(cu_pass_sky *p, const cu_gpu_scene *ctx, int to_output, cu_error *err);
/* The sky with a cloud image (1/factor of the frame's size, premultiplied) over it, tone-mapped, into the bound
 * target: the frame's last pass when the clouds were drawn at a lower resolution or on the temporal grid. Pixels
 * outside rect (x0, y0, x1, y1, half-open), which the image cannot reach, are drawn without it (the same colours).
 * refined (0: none): quality.edge_refine's full-resolution image, taken instead where its alpha is at most 1. */
int cu_pass_sky_draw_over(cu_pass_sky *p, const cu_gpu_scene *ctx, GLuint clouds, GLuint refined, int factor,
                          const int rect[4], cu_error *err);
#endif
