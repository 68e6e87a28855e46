/* Fitting Bouthors' phenomenological slab model (eq. 3.32) and an alternative form to simulated C tables (GSL LM). */
#ifndef CU_SLAB_FITLIB_H
#define CU_SLAB_FITLIB_H
#include <stdio.h>

/* one row of a cumulo-slab table */
typedef struct { int group; double t, d, thv, phv, thl, C, Cse; } cu_cell;

/* appends the rows of a table file to *cells (realloc'd); returns 0 or -1 with msg */
int cu_cells_read(const char *path, cu_cell **cells, int *n, char *msg, size_t msglen);

/* BOUTHORS: eq. 3.32. LOGSEP: log C = log P*(Theta) + H(d, thV) + K(d, thL). LOGSEP2: as LOGSEP with P* also
 * depending on depth, P*(Theta, d). The log-linear forms get an analytic Jacobian. */
enum { CU_MODEL_BOUTHORS = 0, CU_MODEL_LOGSEP = 1, CU_MODEL_LOGSEP2 = 2 };
#define CU_FIT_MAXN 64
#define CU_FIT_NTH 13   /* P*(Theta) nodes every 15 degrees */

typedef struct {
    int model, group;
    double t;                                    /* thickness, metres */
    int nv, nl, nd;
    double thv[CU_FIT_MAXN], thl[CU_FIT_MAXN], d[CU_FIT_MAXN];
    int npar;                                    /* full parameter vector (fixed entries included) */
    double par[4096];
    int iter, status;
    double cmax;                                 /* largest simulated C in the fitted cells */
} cu_fit;

/* fits one (group, thickness) slice; use[i] != 0 selects training cells (NULL = all of the slice) */
int cu_fit_slice(cu_fit *f, int model, int group, double t, const cu_cell *cells, int n, const int *use);
/* model value at a grid cell (thv, thl must be grid angles; d and phv arbitrary) */
double cu_fit_eval(const cu_fit *f, double d, double thv, double phv, double thl);
/* relative errors |M - C|/C over the slice's cells with C > frac * cmax (and use[i] == want if use given):
 * fills up to max values into err (sorted), returns their count; also the median MC relative error */
int cu_fit_errors(const cu_fit *f, const cu_cell *cells, int n, const int *use, int want, double frac, double *err,
                  int max, double *noise_med);
double cu_quantile(const double *sorted, int n, double q);
void cu_fit_write(FILE *fp, const cu_fit *f);
#endif
