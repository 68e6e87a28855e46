/* src/core/collector.c: strict loader and texture packing of the collector table (see collector.h). */
#include "collector.h"
#include "error.h"
#include "textfile.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Inserts x into the ascending list v (n entries, at most max) unless present; -1 when full. */
static int add_node(double *v, int *n, int max, double x)
{
    int i = 0;
    while (i < *n && v[i] < x - 1e-9 * (1 + fabs(x)))
        i++;
    if (i < *n && fabs(v[i] - x) <= 1e-9 * (1 + fabs(x)))
        return 0;
    if (*n == max)
        return -1;
    memmove(v + i + 1, v + i, sizeof(double) * (size_t)(*n - i));
    v[i] = x;
    (*n)++;
    return 0;
}

static int find_node(const double *v, int n, double x)
{
    for (int i = 0; i < n; i++)
        if (fabs(v[i] - x) <= 1e-9 * (1 + fabs(x)))
            return i;
    return -1;
}

typedef struct { double v[9]; int line; } row;

/* Each field's range: the slab thickness t_m > 0, the depth d_m within it, angles in degrees, the weight C_ms and
 * the spread sigma_m >= 0 (the shader takes its square root); the centroid offsets cx_m, cz_m may have any sign. */
static int check_row(const double *v, const char *path, int ln, const char *const *names, cu_error *err)
{
    static const double lo[9] = {0, 0, 0, 0, 0, 0, -INFINITY, -INFINITY, 0};
    static const double hi[9] = {INFINITY, 90, INFINITY, 180, 180, INFINITY, INFINITY, INFINITY, INFINITY};
    for (int k = 0; k < 9; k++) {
        double top = k == 2 ? v[0] * (1 + 1e-9) : hi[k];
        if (v[k] < lo[k] || v[k] > top || (k == 0 && v[k] == 0)) {
            if (k == 2)
                return cu_fail(err, "%s:%d: field 'd_m': %.9g is out of range [0, t_m = %.9g]", path, ln, v[k], v[0]);
            return cu_fail(err, "%s:%d: field '%s': %.9g is out of range %c%g, %g%c", path, ln, names[k], v[k],
                           k == 0 ? '(' : '[', lo[k], hi[k], isinf(hi[k]) ? ')' : ']');
        }
    }
    return 0;
}

static int read_collector(cu_collector *c, cu_textfile f, cu_error *err);

int cu_collector_load(cu_collector *c, const char *path, cu_error *err)
{
    memset(c, 0, sizeof *c);
    cu_textfile f;
    if (cu_textfile_open(&f, path, "the collector table", "scripts/collector_table.sh makes it", err))
        return 1;
    return read_collector(c, f, err);
}

int cu_collector_parse(cu_collector *c, const char *name, const char *text, size_t len, cu_error *err)
{
    memset(c, 0, sizeof *c);
    cu_textfile f;
    if (cu_textfile_open_mem(&f, name, text, len, err))
        return 1;
    return read_collector(c, f, err);
}

/* The table from f, an open reader that this closes. */
static int read_collector(cu_collector *c, cu_textfile f, cu_error *err)
{
    const char *path = f.path;
    size_t cap = 1 << 14, n = 0;
    row *rows = malloc(cap * sizeof *rows);
    unsigned char *seen = NULL;
    int rc = 1, r;
    static const char *const names[9] = {"t_m", "thetaL", "d_m", "thetaV", "phiV", "C_ms", "cx_m", "cz_m", "sigma_m"};
    while (rows && (r = cu_textfile_next(&f, err)) != 0) {
        int ln = f.line;
        if (r < 0)
            goto out;
        row rw = {.line = ln};
        for (int k = 0; k < 9; k++) {
            cu_num_status s = k < f.ntok ? cu_text_number(f.tok[k], &rw.v[k]) : CU_NUM_BAD;
            if (s == CU_NUM_NOT_FLOAT) {
                cu_text_fail_float(&f, err, names[k], f.tok[k]);
                goto out;
            }
            if (s != CU_NUM_OK) {
                cu_fail(err, "%s:%d: field '%s': expected a finite number", path, ln, names[k]);
                goto out;
            }
        }
        if (f.ntok > 9) {
            cu_fail(err, "%s:%d: more than 9 fields", path, ln);
            goto out;
        }
        const double *v = rw.v;
        if (check_row(v, path, ln, names, err))
            goto out;
        if (n == cap) {
            row *nr = realloc(rows, 2 * cap * sizeof *rows);
            if (!nr) {
                cu_fail(err, "%s:%d: out of memory", path, ln);
                goto out;
            }
            rows = nr;
            cap *= 2;
        }
        rows[n++] = rw;
        if (add_node(c->t, &c->nt, CU_COLL_MAX_T, v[0]) || add_node(c->thl, &c->nl, CU_COLL_MAX_L, v[1]) ||
            add_node(c->thv, &c->nv, CU_COLL_MAX_V, v[3]) || add_node(c->phi, &c->np, CU_COLL_MAX_P, v[4])) {
            cu_fail(err, "%s:%d: too many distinct nodes for the grid", path, ln);
            goto out;
        }
    }
    int ln = f.line;
    if (!rows) {
        cu_fail(err, "%s: out of memory", path);
        goto out;
    }
    size_t cells = (size_t)c->nt * c->nl * CU_COLL_ND * c->nv * c->np;
    if (n == 0 || n != cells || c->nv < 2) {
        cu_fail(err, "%s:%d: %zu rows for a grid of %d x %d x %d x %d x %d = %zu cells", path, ln, n, c->nt, c->nl,
                CU_COLL_ND, c->nv, c->np, cells);
        goto out;
    }
    c->cell = malloc(sizeof(float) * 3 * cells);
    seen = calloc(cells, 1);
    if (!c->cell || !seen) {
        cu_fail(err, "%s: out of memory", path);
        goto out;
    }
    for (size_t i = 0; i < n; i++) {
        const row *q = &rows[i];
        int it = find_node(c->t, c->nt, q->v[0]), il = find_node(c->thl, c->nl, q->v[1]);
        int iv = find_node(c->thv, c->nv, q->v[3]), ip = find_node(c->phi, c->np, q->v[4]);
        double jd = q->v[2] / q->v[0] * 10;
        int j = (int)(jd + 0.5);
        if (fabs(jd - j) > 1e-6) {
            cu_fail(err, "%s:%d: field 'd_m': depths must be j t / 10", path, q->line);
            goto out;
        }
        size_t idx = ((((size_t)it * c->nl + il) * CU_COLL_ND + j) * c->nv + iv) * c->np + ip;
        if (seen[idx]++) {
            cu_fail(err, "%s:%d: duplicate cell", path, q->line);
            goto out;
        }
        c->cell[3 * idx] = (float)q->v[6];
        c->cell[3 * idx + 1] = (float)q->v[7];
        c->cell[3 * idx + 2] = (float)q->v[8];
    }
    rc = 0;
out:
    free(seen);
    free(rows);
    cu_textfile_close(&f);
    if (rc)
        cu_collector_free(c);
    return rc;
}

void cu_collector_free(cu_collector *c)
{
    free(c->cell);
    c->cell = NULL;
}

void cu_collector_pack(const cu_collector *c, float *rgba)
{
    int w = CU_COLL_ND * c->np;
    for (int it = 0; it < c->nt; it++)
        for (int il = 0; il < c->nl; il++)
            for (int j = 0; j < CU_COLL_ND; j++)
                for (int iv = 0; iv < c->nv; iv++)
                    for (int ip = 0; ip < c->np; ip++) {
                        size_t idx = ((((size_t)it * c->nl + il) * CU_COLL_ND + j) * c->nv + iv) * c->np + ip;
                        int x = ip * CU_COLL_ND + j, y = (it * c->nl + il) * c->nv + iv;
                        float *o = rgba + 4 * ((size_t)y * w + x);
                        o[0] = c->cell[3 * idx];
                        o[1] = c->cell[3 * idx + 1];
                        o[2] = c->cell[3 * idx + 2];
                        o[3] = 0;
                    }
}
