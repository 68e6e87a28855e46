/* src/core/collector.h: the collector table of ms.mode = collector (Bouthors' iterative collector search, Kol eqs.
 * 3.59-3.63): where on a slab's lit face the light that reaches a viewpoint entered, and how wide that area is,
 * tabulated from the slab simulations by scripts/collector_table.sh (data/slab_collector.txt). */
#ifndef CU_COLLECTOR_H
#define CU_COLLECTOR_H
#include "cumulo.h"

#define CU_COLL_MAX_T 16
#define CU_COLL_MAX_L 16
#define CU_COLL_ND 11      /* depths j t / 10, j = 0..10 */
#define CU_COLL_MAX_V 32
#define CU_COLL_MAX_P 16

typedef struct cu_collector {
    int nt, nl, nv, np;
    double t[CU_COLL_MAX_T], thl[CU_COLL_MAX_L], thv[CU_COLL_MAX_V], phi[CU_COLL_MAX_P];
    /* (c_x, c_z, sigma) in metres at k_e = 0.0905 m^-1, indexed [it][il][jd][iv][ip] */
    float *cell; /* nt * nl * ND * nv * np * 3 */
} cu_collector;

/* Reads the table: a complete regular grid (every combination exactly once, ascending nodes, depths j t / 10),
 * finite numbers, sigma >= 0. Errors read "path:line: ...". */
int cu_collector_load(cu_collector *c, const char *path, cu_error *err);
/* The same reader over text[0..len), named name in messages. */
int cu_collector_parse(cu_collector *c, const char *name, const char *text, size_t len, cu_error *err);
void cu_collector_free(cu_collector *c);
/* RGBA32F texture: width ND * np (depth fastest), height nv * nl * nt (theta_V fastest); texel = (cx, cz, sigma, 0). */
void cu_collector_pack(const cu_collector *c, float *rgba);
#endif
