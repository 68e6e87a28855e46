/* src/collector.c: strict loader and texture packing of the collector table (see collector.h). */
#include "collector.h"
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int cfail(cu_error *err, const char *path, int line, const char *what)
{
    snprintf(err->msg, sizeof err->msg, "%s:%d: %s", path, line, what);
    return 1;
}

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

int cu_collector_load(cu_collector *c, const char *path, cu_error *err)
{
    memset(c, 0, sizeof *c);
    FILE *fp = fopen(path, "r");
    if (!fp) {
        snprintf(err->msg, sizeof err->msg, "%s: cannot open the collector table: %s (scripts/collector_table.sh "
                 "makes it)", path, strerror(errno));
        return 1;
    }
    size_t cap = 1 << 14, n = 0;
    row *rows = malloc(cap * sizeof *rows);
    unsigned char *seen = NULL;
    char line[512];
    int ln = 0, rc = 1;
    static const char *const names[9] = {"t_m", "thetaL", "d_m", "thetaV", "phiV", "C_ms", "cx_m", "cz_m", "sigma_m"};
    while (rows && fgets(line, sizeof line, fp)) {
        ln++;
        size_t len = strlen(line);
        if (len == 0 || (line[len - 1] != '\n' && !feof(fp))) {
            cfail(err, path, ln, len == sizeof line - 1 ? "line too long" : "NUL byte in the line");
            goto out;
        }
        char *p = line;
        while (*p == ' ' || *p == '\t')
            p++;
        if (*p == '#' || *p == '\n' || *p == 0)
            continue;
        row r = {.line = ln};
        for (int k = 0; k < 9; k++) {
            char *end;
            errno = 0;
            r.v[k] = strtod(p, &end);
            if (end == p || errno == ERANGE || !isfinite(r.v[k])) {
                char what[80];
                snprintf(what, sizeof what, "field '%s': expected a finite number", names[k]);
                cfail(err, path, ln, what);
                goto out;
            }
            p = end;
        }
        while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n')
            p++;
        if (*p) {
            cfail(err, path, ln, "more than 9 fields");
            goto out;
        }
        if (r.v[0] <= 0 || r.v[1] < 0 || r.v[1] > 90 || r.v[3] < 0 || r.v[3] > 180 || r.v[4] < 0 || r.v[4] > 180 ||
            r.v[2] < 0 || r.v[2] > r.v[0] * (1 + 1e-9) || r.v[8] < 0) {
            cfail(err, path, ln, "value out of range (t > 0, 0 <= d <= t, angles in degrees, sigma >= 0)");
            goto out;
        }
        if (n == cap) {
            row *nr = realloc(rows, 2 * cap * sizeof *rows);
            if (!nr) {
                cfail(err, path, ln, "out of memory");
                goto out;
            }
            rows = nr;
            cap *= 2;
        }
        rows[n++] = r;
        if (add_node(c->t, &c->nt, CU_COLL_MAX_T, r.v[0]) || add_node(c->thl, &c->nl, CU_COLL_MAX_L, r.v[1]) ||
            add_node(c->thv, &c->nv, CU_COLL_MAX_V, r.v[3]) || add_node(c->phi, &c->np, CU_COLL_MAX_P, r.v[4])) {
            cfail(err, path, ln, "too many distinct nodes for the grid");
            goto out;
        }
    }
    if (!rows) {
        snprintf(err->msg, sizeof err->msg, "%s: out of memory", path);
        goto out;
    }
    size_t cells = (size_t)c->nt * c->nl * CU_COLL_ND * c->nv * c->np;
    if (n == 0 || n != cells || c->nv < 2) {
        snprintf(err->msg, sizeof err->msg, "%s:%d: %zu rows for a grid of %d x %d x %d x %d x %d = %zu cells", path,
                 ln, n, c->nt, c->nl, CU_COLL_ND, c->nv, c->np, cells);
        goto out;
    }
    c->cell = malloc(sizeof(float) * 3 * cells);
    seen = calloc(cells, 1);
    if (!c->cell || !seen) {
        snprintf(err->msg, sizeof err->msg, "%s: out of memory", path);
        goto out;
    }
    for (size_t i = 0; i < n; i++) {
        const row *r = &rows[i];
        int it = find_node(c->t, c->nt, r->v[0]), il = find_node(c->thl, c->nl, r->v[1]);
        int iv = find_node(c->thv, c->nv, r->v[3]), ip = find_node(c->phi, c->np, r->v[4]);
        double jd = r->v[2] / r->v[0] * 10;
        int j = (int)(jd + 0.5);
        if (fabs(jd - j) > 1e-6) {
            cfail(err, path, r->line, "field 'd_m': depths must be j t / 10");
            goto out;
        }
        size_t idx = ((((size_t)it * c->nl + il) * CU_COLL_ND + j) * c->nv + iv) * c->np + ip;
        if (seen[idx]++) {
            cfail(err, path, r->line, "duplicate cell");
            goto out;
        }
        c->cell[3 * idx] = (float)r->v[6];
        c->cell[3 * idx + 1] = (float)r->v[7];
        c->cell[3 * idx + 2] = (float)r->v[8];
    }
    rc = 0;
out:
    free(seen);
    free(rows);
    fclose(fp);
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
