/* src/gpu/sky_grid.c: the sky pass's geometry on the CPU (see sky_grid.h). */
#include "sky_grid.h"
#include <stdlib.h>
#include <string.h>
#include "tonemap.h"

vec3 cu_sky_dir(const float *m, double x, double y)
{
    double n[4], f[4];
    for (int r = 0; r < 4; r++) {
        n[r] = m[r] * x + m[4 + r] * y - m[8 + r] + m[12 + r];
        f[r] = m[r] * x + m[4 + r] * y + m[8 + r] + m[12 + r];
    }
    return v3_norm(v3(f[0] / f[3] - n[0] / n[3], f[1] / f[3] - n[1] / n[3], f[2] / f[3] - n[2] / n[3]));
}

/* A direction's height is affine in the screen up to a positive factor (sign(d.y) is that of the far point's y), so
 * over a rectangle its sign is settled at the corners. A margin far above fp32's rounding of the direction in the
 * shader keeps the rows near the horizon with the branch; NaN (a degenerate camera) too. */
int cu_sky_rows(const float *m, double y0, double y1)
{
    const double margin = 1e-4;
    double h[4] = {cu_sky_dir(m, -1, y0).y, cu_sky_dir(m, 1, y0).y, cu_sky_dir(m, -1, y1).y, cu_sky_dir(m, 1, y1).y};
    int above = 1, below = 1, low = 0;
    for (int k = 0; k < 4; k++) {
        above = above && h[k] > margin;
        below = below && h[k] < -margin;
        low = low || h[k] < CU_SKY_LOW_SINE;
    }
    return above ? (low ? CU_SKY_LOW : CU_SKY_ABOVE) : below ? CU_SKY_BELOW : CU_SKY_BOTH;
}

typedef struct plan_in {
    const float *tables;
    vec3 sun_dir;
    const float *m;
    int w, h;
    const int *sun;
    const double *display; /* NULL: radiance; else the exposure's scale by channel and the cap (cu_sky_grid_toned) */
} plan_in;

/* The sky the tables give at pixel (x, y) of the viewport, as a corner of sky.vert's grid sees it: radiance, or the
 * display's value (0..1) as sky.vert makes it with SKY_CORNER_TONE: tone_curve(exposed(L)). */
static void sky_px(const plan_in *in, double x, double y, double out[3])
{
    vec3 d = cu_sky_dir(in->m, 2.0 * x / in->w - 1.0, 2.0 * y / in->h - 1.0);
    cu_sky_from_tables(in->tables, in->tables + 4 * CU_SKY_TABLE, in->sun_dir, d, out);
    if (in->display)
        for (int c = 0; c < 3; c++) {
            double e = fmin(out[c] * in->display[c], in->display[3]);
            out[c] = cu_tonemap_srgb(cu_tonemap_aces(e > 0 ? e : 0));
        }
}

/* Whether the interpolation at point (x, y) of rows [y0, y1) stays close enough to the sky there: within
 * CU_SKY_GRID_REL of its radiance, or CU_SKY_GRID_LEVELS of the display's levels. */
static int close_at(const plan_in *in, double x, double y, int y0, int y1, const double v[3])
{
    if (y < y0 || y >= y1 || (x >= in->sun[0] && x < in->sun[2] && y >= in->sun[1] && y < in->sun[3]))
        return 1;
    double s[3];
    sky_px(in, x, y, s);
    for (int c = 0; c < 3; c++) {
        double bound = in->display ? CU_SKY_GRID_LEVELS / 255.0 : CU_SKY_GRID_REL * s[c] + 1e-12;
        if (!(fabs(v[c] - s[c]) <= bound)) /* NaN (a degenerate camera): not close */
            return 0;
    }
    return 1;
}

/* The corners of a row of cells and of the row above it, each worked out when a cell first needs it: neighbouring
 * cells share them (a corner serves up to four cells). */
typedef struct corners {
    double (*v)[3];     /* 2 x (cols + 1): the row's lower corners, then its upper ones */
    unsigned char *got; /* the same, 1 once worked out */
    int most;           /* room for this many columns of corners */
} corners;

static const double *corner(const plan_in *in, corners *cc, int row, int cols, int i, double x, double y)
{
    int k = row * (cols + 1) + i;
    if (!cc->got[k]) {
        sky_px(in, x, y, cc->v[k]);
        cc->got[k] = 1;
    }
    return cc->v[k];
}

/* Whether cells cw x ch, laid from the viewport's corner and clamped to it as sky.vert lays them, interpolate rows
 * [y0, y1) well enough (cu_sky_grid_plan). Each cell's two triangles share the diagonal from its upper left corner to
 * its lower right (sky.vert's strip: lower, upper, lower, ...). Tested: the part of the cell within the rows (a cell
 * may reach past them, its corners below the horizon), at its corners, edges' midpoints and centre, and at the
 * centroids of the cell's triangles. A cell's left edge is its left neighbour's right edge, interpolated alike (along
 * an edge only its two corners count), so after the first cell of a row it is not tested again. */
static int cells_fit(const plan_in *in, int cw, int ch, int y0, int y1, corners *cc)
{
    int cols = (in->w + cw - 1) / cw;
    if (cols + 1 > cc->most)
        return 0; /* not reached: bands() makes room for the finest cells */
    memset(cc->got, 0, (size_t)(cols + 1));
    for (int cy = y0 / ch * ch; cy < y1; cy += ch) {
        memset(cc->got + cols + 1, 0, (size_t)(cols + 1));
        for (int i = 0; i < cols; i++) {
            int cx = i * cw;
            double x0 = cx, x1 = cx + cw < in->w ? cx + cw : in->w;
            double ya = cy, yb = cy + ch < in->h ? cy + ch : in->h;
            const double *c[4] = {corner(in, cc, 0, cols, i, x0, ya), corner(in, cc, 0, cols, i + 1, x1, ya),
                                  corner(in, cc, 1, cols, i, x0, yb), corner(in, cc, 1, cols, i + 1, x1, yb)};
            double lo = fmax(ya, y0 + 0.5), hi = fmax(lo, fmin(yb, y1 - 0.5)); /* the rows' pixel centres */
            double pts[11][2] = {{(2 * x0 + x1) / 3, (2 * ya + yb) / 3}, {(x0 + 2 * x1) / 3, (ya + 2 * yb) / 3}};
            for (int j = 0; j < 9; j++) {
                pts[2 + j][0] = x0 + 0.5 * (j % 3) * (x1 - x0);
                pts[2 + j][1] = lo + 0.5 * (j / 3) * (hi - lo);
            }
            for (int p = 0; p < 11; p++) {
                if (p >= 2 && (p - 2) % 3 == 0 && i > 0)
                    continue; /* the left edge: tested as the neighbour's right */
                if (p >= 2 && (p - 2) % 3 != 1 && (pts[p][1] == ya || pts[p][1] == yb))
                    continue; /* a corner: exact */
                double u = (pts[p][0] - x0) / (x1 - x0), v = (pts[p][1] - ya) / (yb - ya), val[3];
                for (int k = 0; k < 3; k++)
                    val[k] = u + v <= 1 ? c[0][k] + u * (c[1][k] - c[0][k]) + v * (c[2][k] - c[0][k])
                                        : c[3][k] + (1 - u) * (c[2][k] - c[3][k]) + (1 - v) * (c[1][k] - c[3][k]);
                if (!close_at(in, pts[p][0], pts[p][1], y0, y1, val))
                    return 0;
            }
        }
        /* the row above takes this row's upper corners as its lower ones */
        memcpy(cc->v, cc->v + cols + 1, sizeof cc->v[0] * (size_t)(cols + 1));
        memcpy(cc->got, cc->got + cols + 1, (size_t)(cols + 1));
    }
    return 1;
}

/* cu_sky_grid_plan's bands with the scales tried, largest first, down to `least` (1: the last without a test; 0:
 * every one tested, 0 where none passes). */
static int bands(const plan_in *in, int grid, int least, unsigned char scale[CU_SKY_BANDS][2])
{
    int w = in->w, h = in->h, cells = 0;
    const float *m = in->m;
    corners cc = {NULL, NULL, grid > 0 ? (w + grid - 1) / grid + 1 : 0};
    if (grid >= CU_SKY_PLAN_LEAST) {
        cc.v = malloc(sizeof cc.v[0] * 2 * (size_t)cc.most);
        cc.got = malloc(2 * (size_t)cc.most);
        if (!cc.v || !cc.got)
            grid = 0; /* out of memory: no band grows (each keeps `least`), as for a grid too fine to plan */
    }
    for (int b = 0; b < CU_SKY_BANDS; b++) {
        scale[b][0] = scale[b][1] = (unsigned char)least;
        int r0 = b * CU_SKY_BAND, r1 = r0 + CU_SKY_BAND < h ? r0 + CU_SKY_BAND : h;
        if (r0 >= h || grid < CU_SKY_PLAN_LEAST)
            continue;
        /* the band's rows of sky alone (0) and near the horizon (1): first and last of each */
        int first[2] = {r1, r1}, last[2] = {r0 - 1, r0 - 1};
        for (int r = r0; r < r1; r++) {
            int part = cu_sky_rows(m, -1.0 + 2.0 * r / h, -1.0 + 2.0 * (r + 1) / h);
            int k = part == CU_SKY_ABOVE ? 0 : part == CU_SKY_LOW ? 1 : -1;
            if (k >= 0) {
                first[k] = r < first[k] ? r : first[k];
                last[k] = r;
            }
        }
        for (int k = 0; k < 2; k++) {
            if (last[k] < first[k])
                continue;
            int cw = grid, ch = k && grid > 4 ? grid / 4 : grid;
            for (int s = 4; s > least; s /= 2)
                if (cw * s <= CU_SKY_CELL_MAX && ch * s <= CU_SKY_CELL_MAX &&
                    cells_fit(in, cw * s, ch * s, first[k], last[k] + 1, &cc)) {
                    scale[b][k] = (unsigned char)s;
                    break;
                }
            int s = scale[b][k]; /* the cells drawn (counted without the test) */
            for (int cy = s ? first[k] / (ch * s) * ch * s : last[k] + 1; cy <= last[k]; cy += ch * s)
                cells += (w + cw * s - 1) / (cw * s);
        }
    }
    free(cc.v);
    free(cc.got);
    return cells;
}

int cu_sky_grid_plan(const float *tables, vec3 sun_dir, const float *m, int w, int h, int grid, const int sun[4],
                     unsigned char scale[CU_SKY_BANDS][2])
{
    const plan_in in = {tables, sun_dir, m, w, h, sun, NULL};
    return bands(&in, grid, 1, scale);
}

int cu_sky_grid_toned(const float *tables, vec3 sun_dir, const float *m, int w, int h, int grid, const int sun[4],
                      const double display[4], unsigned char scale[CU_SKY_BANDS][2])
{
    const plan_in in = {tables, sun_dir, m, w, h, sun, display};
    return bands(&in, grid, 0, scale);
}
