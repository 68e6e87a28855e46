/* src/core/ms_diffusion.h: multiple scattering as flux-limited diffusion on a grid over one cloud (ms.mode =
 * diffusion): the sunbeam's first scattering is the source, the diffuse light's fluence and flux the answer, solved
 * on the CPU when the cloud or the sun changes and read by the cloud shader from a 3D texture (shaders_gles/
 * ms_diffusion.glsl). The transport the octave and slab models guess from the column toward the sun is here
 * computed from the cloud's shape: light leaks out of thin edges and sides, and falls off toward the shadowed side
 * and the base as diffusion says (Stam 1995; Koerner et al. 2014, "Flux-limited diffusion for multiple scattering
 * in participating media", with Wilson's sum limiter). */
#ifndef CU_MS_DIFFUSION_H
#define CU_MS_DIFFUSION_H
#include "density.h"
#include "error.h"

#define CU_MSD_MIN_CELLS 8
#define CU_MSD_MAX_CELLS 96
#define CU_MSD_THIN 0.1 /* optical depth across a cell below which it counts as empty space (ms_diffusion.c) */
#define CU_MSD_MARGIN 2 /* cells of empty space about the cloud's bounds on every side: where its light leaks to */

typedef struct cu_msd {
    int n[3];             /* cells along x, y, z */
    double h[3];          /* cell sides along x, y, z, m */
    double side;          /* their geometric mean: a cell holds cloud when k_e side >= CU_MSD_THIN */
    vec3 lo;              /* cloud-local position of the grid's lowest corner */
    float *ke;            /* extinction, the mean of 8 samples in each cell, m^-1 (true, not delta-M) */
    float *q;             /* the sunbeam's first scattering per unit volume and unit irradiance (delta-M), m^-1 */
    float *push;          /* its forward flux along the beam, limited (ms_diffusion.c) */
    float *phi;           /* fluence of the diffuse light per unit sun irradiance */
    float *d;             /* the limited diffusion coefficient, m */
    float *leak;          /* per cloud cell: the true surface's area over its faces' to empty space (ms_diffusion.c) */
    float *out;           /* 4 per cell: fluence and flux (x, y, z) per unit sun irradiance: the texture */
    int sweeps;           /* the last solve's relaxation sweeps (all rounds) */
    double change;        /* its last sweep's summed change relative to the summed fluence */
    /* a solve under way (cu_msd_solve_begin, cu_msd_solve_continue) */
    int solving;          /* 1 until it is done and out filled */
    int round, in_round;  /* its Picard round, and the sweeps taken in it */
    int round_most;       /* the most that round may take; 0 before its coefficients are taken */
    int max_sweeps;
    double tol, s_tr_per_ke, g3;
    vec3 u;               /* the way the push goes */
} cu_msd;

/* A grid over cloud cl's bounds and CU_MSD_MARGIN cells about them, `cells` along its longest side
 * (CU_MSD_MIN_CELLS .. CU_MSD_MAX_CELLS) and cubic cells, but at least a quarter of them across each side; the
 * fluence starts at zero. */
int cu_msd_init(cu_msd *g, const cu_cloud *cl, int cells, cu_error *err);
void cu_msd_free(cu_msd *g);
/* The cloud's extinction into the cells (again whenever its density changes). */
void cu_msd_sample(cu_msd *g, const cu_cloud *cl);
/* The same for the cells of slices k0 <= k < k1 only (a renderer spreads the sampling over frames; no solve may run
 * in between). */
void cu_msd_sample_slices(cu_msd *g, const cu_cloud *cl, int k0, int k1);
/* Solves for the sun toward sun_dir (cloud-local, unit, pointing at the sun) with the phase function's chopped
 * peak f and the asymmetry g of the rest (delta-M; f = 0 and g for Henyey-Greenstein), starting from the grid's
 * present fluence (a sun that moved a little converges in a few sweeps), until a sweep changes the fluence by at
 * most tol of its sum (L1) or after max_sweeps; fills out. */
void cu_msd_solve(cu_msd *g, vec3 sun_dir, double f, double asym, int max_sweeps, double tol);
/* The same solve in steps, so that a renderer can spread it over frames (the answer is bit for bit the same):
 * _begin does what comes before the sweeps (the sunbeam's first scattering, the surface's leak weights, for a fine
 * grid with no light yet the coarse grid's solve) and sets g->solving; each _continue runs at most `sweeps` more
 * relaxation sweeps and returns how many it ran; when the solve is done it fills out and clears g->solving. */
void cu_msd_solve_begin(cu_msd *g, vec3 sun_dir, double f, double asym, int max_sweeps, double tol);
int cu_msd_solve_continue(cu_msd *g, int sweeps);
/* Nested grids (a fine grid's first solve from a coarse one's answer, ms_diffusion.c): c becomes the grid of half
 * the cells a side over g's box (each cell the mean of the 8 of g's it covers; past an odd grid's end, empty space),
 * its fluence zero; 1 (and nothing held) when out of memory. */
int cu_msd_coarsen(const cu_msd *g, cu_msd *c);
/* g's fluence, where g holds cloud, from c's answer (c coarsened from g, then solved), read trilinearly at g's cells'
 * centres with the surface values c's empty cells hold: where a solve of g then starts. */
void cu_msd_start_from(cu_msd *g, const cu_msd *c);
/* The solve's source (ms_diffusion_beam.c): fills g->q, per cell and per unit sun irradiance the power the delta-M
 * sunbeam (toward the sun sun, unit, cloud-local; f the chopped peak) loses in it over its volume. */
void cu_msd_first_scattering(cu_msd *g, vec3 sun, double f);
/* Index of cell (i, j, k). */
static inline int cu_msd_at(const cu_msd *g, int i, int j, int k)
{
    return (k * g->n[1] + j) * g->n[0] + i;
}
/* The centre of cell (i, j, k), cloud-local. */
static inline vec3 cu_msd_centre(const cu_msd *g, int i, int j, int k)
{
    return v3(g->lo.x + (i + 0.5) * g->h[0], g->lo.y + (j + 0.5) * g->h[1], g->lo.z + (k + 0.5) * g->h[2]);
}
#endif
