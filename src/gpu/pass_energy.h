/* src/gpu/pass_energy.h: the slab model's energy closure: one pair of gains per sun direction and cloud that keeps
 * the light a cloud sends out within the sunlight it intercepts (pass_energy.c). */
#ifndef CU_PASS_ENERGY_H
#define CU_PASS_ENERGY_H
#include "phase.h"
#include "shading.h"
#include "target.h"

#define CU_ENERGY_BANDS 8

typedef struct cu_pass_energy {
    GLuint prog;                       /* cloud.frag with ENERGY_PASS */
    cu_shading_locs locs;
    GLint budget_view;
    cu_target target;
    double ss_w[CU_ENERGY_BANDS];      /* single-scattering weight per band of angles, from the phase table */
    int valid;                         /* the gains were measured for these clouds... */
    vec3 sun;                          /* ...and this sun direction */
    double gain[2];                    /* on multiple scattering reflected and transmitted, <= 1 */
} cu_pass_energy;

/* Sets the gains to 1 and the weights from the phase table t; builds program and target when ctx->ms_mode is the
 * slab model or the collector search and the scene asks for the closure. `fs_defs` are the full-screen cloud
 * program's defines. */
int cu_pass_energy_create(cu_pass_energy *p, const cu_gpu_scene *ctx, const cu_phase_table *t, const char *fs_defs,
                          cu_error *err);
void cu_pass_energy_destroy(cu_pass_energy *p, const cu_gl *gl);
/* Measures the gains for ctx's sun (kept while the sun stays within 1 deg). Call after the sun and slab passes
 * have published their maps into ctx. */
void cu_pass_energy_update(cu_pass_energy *p, const cu_gpu_scene *ctx);
#endif
