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
    GLuint tex;               /* RGBA16F: fluence and flux per unit sun irradiance */
    int sampled;              /* the grid holds the cloud's density */
    int resample;             /* ... of an earlier look: sample again at the next solve */
    int solved;               /* its light has been solved, for sun */
    vec3 sun;
} cu_cloud_msd;

/* Brings cloud cl's grid up to date (cl at its mature density, as its maps are made): samples its density again
 * when resample is set (now or at an earlier call) or it has none, solves when it was resampled or the sun (world =
 * the cloud's frame's axes) turned past CU_MSD_SUN_STEP, and uploads what changed. A grid never solved is solved at
 * once; any other solve takes one of *allowance (NULL: no limit) and waits for a later call when none is left, so a
 * frame in which many clouds' maps follow the sun pays for one solve, not for all (each is 0.1-0.3 s of CPU). */
int cu_pass_msd_update(const cu_gpu_scene *ctx, cu_cloud_msd *m, const cu_cloud *cl, vec3 sun, int resample,
                       int *allowance, cu_error *err);
/* Points the frame context at m's texture and box (what cloud.frag reads for the cloud being drawn). */
void cu_pass_msd_bind(cu_gpu_scene *ctx, const cu_cloud_msd *m);
void cu_pass_msd_free(cu_cloud_msd *m, const cu_gl *gl);
#endif
