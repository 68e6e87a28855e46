/* src/gpu/pass_msd.h: ms.mode = diffusion: each cloud's diffusion grid (src/core/ms_diffusion.h) solved on the CPU
 * when the cloud's look or the sun changes, and uploaded as the 3D texture cloud.frag reads (ms_diffusion.glsl). */
#ifndef CU_PASS_MSD_H
#define CU_PASS_MSD_H
#include "gpu_scene.h"
#include "ms_diffusion.h"

/* Degrees the sun may turn before a cloud's grid is solved again: its diffuse light changes slowly with the sun's
 * direction, and each solve starts from the last, so a creeping sun costs a few sweeps a degree. */
#define CU_MSD_SUN_STEP 0.5

typedef struct cu_cloud_msd {
    cu_msd grid;
    cu_msd coarse;            /* a new cloud's grid of half the cells a side, until its own grid's solve starts */
    GLuint tex;               /* RGBA16F: fluence and flux per unit sun irradiance */
    vec3 tex_lo, tex_size;    /* its box, cloud-local (m): the grid's, or its coarse grid's (pass_msd.c) */
    int sampled;              /* the grid holds the cloud's density */
    int resample;             /* ... of an earlier look: sample again at the next solve */
    int sample_k;             /* a sampling spread over frames: the next slice of cells to sample; 0 when none */
    int stale;                /* sampled since its last solve began: to be solved again */
    int solved;               /* its light has been solved, for sun (the texture's) */
    vec3 sun;
    vec3 solving_sun;         /* the sun of the solve under way (grid.solving), over as many frames as it takes */
    int solve_frames;         /* the frames it has taken so far */
    double solve_ms;          /* and their CPU time */
    int pending;              /* after cu_pass_msd_update: its light is not yet what was asked (a later frame's) */
} cu_cloud_msd;

/* Brings cloud cl's grid up to date (cl at its mature density, as its maps are made): samples its density again
 * when resample is set (now or at an earlier call) or it has none, solves when it was resampled or the sun (world =
 * the cloud's frame's axes) turned past CU_MSD_SUN_STEP, and uploads the answer. With work NULL (a scene's first
 * frame) a solve is done whole at once. Otherwise a solve is spread over frames: each call advances it by at most
 * *work cell updates (a cell in a sweep; at least one sweep) and takes them off *work, and until it is done the cloud
 * keeps the light it has (bit for bit the same answer in the end); a frame whose work is spent starts no solve, and
 * sampling the cloud's density again goes a slice of cells at a time within the same work. A cloud that has no
 * light yet (new to a running sky: it came into view, or was born) gets its grid of half the cells a side sampled
 * and solved whole at once, about a sixteenth of the work, and shown until its own grid, sampled and solved within
 * the work from that answer, is done. So a frame pays a bounded CPU time for the grids however many clouds' maps follow the sun,
 * change their look or come into view: a whole solve is 10-100 ms of CPU at 32 cells, 0.1-1 s at 64. */
int cu_pass_msd_update(const cu_gpu_scene *ctx, cu_cloud_msd *m, const cu_cloud *cl, vec3 sun, int resample,
                       long *work, cu_error *err);
/* Points the frame context at m's texture and box (what cloud.frag reads for the cloud being drawn). */
void cu_pass_msd_bind(cu_gpu_scene *ctx, const cu_cloud_msd *m);
void cu_pass_msd_free(cu_cloud_msd *m, const cu_gl *gl);
#endif
