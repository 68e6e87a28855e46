/* src/energy.h: the slab model's energy closure: one gain per sun direction and cloud that keeps the light a cloud
 * sends out within the sunlight it intercepts (src/energy.c). */
#ifndef CU_ENERGY_H
#define CU_ENERGY_H
#include "renderer.h"

/* Builds the closure's program and target when the multiple-scattering mode is the slab model or the collector
 * search; `fs_defs` are the full-screen cloud program's defines. Sets the gain to 1. */
int cu_energy_init(cu_renderer *r, const char *fs_defs, cu_error *err);
/* Renders the closure's views and sets r->ms_gain. Call after the sun pass, with the cloud textures bound. */
void cu_energy_update(cu_renderer *r);
void cu_energy_delete(cu_renderer *r);
/* The closure's single-scattering weights from the phase table (P~, green): call when the phase changes. */
void cu_energy_phase_weights(cu_renderer *r, const cu_phase_table *t);
#endif
