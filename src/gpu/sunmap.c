/* src/gpu/sunmap.c: sun-map geometry on the CPU (see sunmap.h). */
#include "sunmap.h"
#include <math.h>

void cu_sun_basis(vec3 d, vec3 *right, vec3 *up)
{
    vec3 ref = fabs(d.y) < 0.99 ? v3(0, 1, 0) : v3(1, 0, 0);
    *right = v3_norm(v3_cross(ref, d));
    *up = v3_cross(d, *right);
}

double cu_sun_radius(const cu_cloud *cl)
{
    return cl->bound_radius * 1.01 + 1.0;
}

/* An ellipsoid's shadow on a plane, seen along the plane's normal, reaches sqrt(sum (r_k u_k)^2) from its centre's
 * image along any unit u in the plane (the support function of the axis-aligned ellipsoid: an orthographic view). */
void cu_sun_map_texels(const cu_cloud *cl, vec3 right, vec3 up, double R, int size, int box[4])
{
    double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
    for (int i = 0; i < cl->n; i++) {
        vec3 r = cl->r[i], axis[2] = {right, up};
        for (int a = 0; a < 2; a++) {
            vec3 u = axis[a];
            double c = v3_dot(cl->c[i], u);
            double h = sqrt(r.x * r.x * u.x * u.x + r.y * r.y * u.y * u.y + r.z * r.z * u.z * u.z);
            lo[a] = fmin(lo[a], c - h);
            hi[a] = fmax(hi[a], c + h);
        }
    }
    for (int a = 0; a < 2; a++) {
        /* texel t's centre lies at ((t + 0.5) / size * 2 - 1) R: the first at or past lo, the last at or before hi */
        double t0 = floor((lo[a] / R + 1.0) * 0.5 * size - 0.5) - 1.0;
        double t1 = ceil((hi[a] / R + 1.0) * 0.5 * size - 0.5) + 2.0;
        box[a] = t0 < 0 ? 0 : t0 > size ? size : (int)t0;
        box[2 + a] = t1 < box[a] ? box[a] : t1 > size ? size : (int)t1;
    }
}

void cu_sun_band_rows(int size, int lo, int hi, int bands, int b, int rows[2])
{
    if (!(hi > lo)) {
        lo = 0;
        hi = size;
    }
    rows[0] = b <= 0 ? 0 : lo + (int)((long)(hi - lo) * b / bands);
    rows[1] = b >= bands - 1 ? size : lo + (int)((long)(hi - lo) * (b + 1) / bands);
}

/* Chord [x, y] into the n chords t0, t1 sorted by entry (insertion: a ray meets few ellipsoids). */
static void insert_chord(double *t0, double *t1, int n, double x, double y)
{
    int k = n;
    while (k > 0 && t0[k - 1] > x) {
        t0[k] = t0[k - 1];
        t1[k] = t1[k - 1];
        k--;
    }
    t0[k] = x;
    t1[k] = y;
}

int cu_union_intervals(const cu_cloud *cl, vec3 o, vec3 d, double *a, double *b, int max)
{
    double t0[CU_MAX_ELLIPSOIDS], t1[CU_MAX_ELLIPSOIDS];
    int n = 0;
    for (int i = 0; i < cl->n; i++) {
        double x, y;
        if (cu_ray_ellipsoid(o, d, cl->c[i], cl->r[i], &x, &y) && y > 0) {
            if (x < 0)
                x = 0;
            if (y <= x)
                continue;
            insert_chord(t0, t1, n++, x, y);
        }
    }
    int m = 0;
    for (int k = 0; k < n;) {
        double lo = t0[k], hi = t1[k];
        k++;
        while (k < n && t0[k] <= hi) {
            if (t1[k] > hi)
                hi = t1[k];
            k++;
        }
        if (m < max) {
            a[m] = lo;
            b[m] = hi;
        }
        m++;
    }
    return m;
}

/* An ellipsoid's chord along the sun rays of the map, as cu_ray_ellipsoid works it out (from the point of closest
 * approach in its unit-sphere frame), with what depends on the ray's place (u, v) in the sun plane made linear: the
 * closest approach t_c and the point q_c there, and the square its shadow lies in. */
typedef struct shadow_chord {
    double tc[3], qc[3][3]; /* constant, per u, per v */
    double inv_a;           /* 1 / |d / r|^2 */
    double lo[2], hi[2];    /* u, v: the shadow's extent (support function), a little wider */
} shadow_chord;

static void chord_setup(shadow_chord *ch, vec3 c, vec3 r, vec3 right, vec3 up, vec3 sun_dir, double R)
{
    vec3 ir = v3(1.0 / r.x, 1.0 / r.y, 1.0 / r.z), ds = v3_mul(v3_scale(sun_dir, -1), ir);
    vec3 q[3] = {v3_mul(v3_sub(v3_scale(sun_dir, 2 * R), c), ir), v3_mul(right, ir), v3_mul(up, ir)};
    ch->inv_a = 1.0 / v3_dot(ds, ds);
    for (int k = 0; k < 3; k++) { /* q_s = q[0] + u q[1] + v q[2]; t_c = -q_s.d_s / A; q_c = q_s + d_s t_c */
        ch->tc[k] = -v3_dot(q[k], ds) * ch->inv_a;
        vec3 qc = v3_add(q[k], v3_scale(ds, ch->tc[k]));
        ch->qc[k][0] = qc.x, ch->qc[k][1] = qc.y, ch->qc[k][2] = qc.z;
    }
    vec3 axis[2] = {right, up};
    for (int a = 0; a < 2; a++) {
        vec3 e = axis[a];
        double mid = v3_dot(c, e), h = sqrt(r.x * r.x * e.x * e.x + r.y * r.y * e.y * e.y + r.z * r.z * e.z * e.z);
        ch->lo[a] = mid - h * 1.001 - 1e-6 * R;
        ch->hi[a] = mid + h * 1.001 + 1e-6 * R;
    }
}

/* How many intervals the sun ray at (u, v) crosses, counting two chords apart unless they overlap by more than slack,
 * and a ray that grazes an ellipsoid (within rounding) as crossing it: at least as many as the shader's fp32 union
 * finds (or cu_union_intervals) where chords barely touch or a ray barely meets one. */
static int intervals_apart(const shadow_chord *ch, const int *in_row, int n_row, double u, double v, double slack)
{
    double t0[CU_MAX_ELLIPSOIDS], t1[CU_MAX_ELLIPSOIDS];
    int n = 0, m = 0;
    for (int e = 0; e < n_row; e++) {
        const shadow_chord *c = &ch[in_row[e]];
        if (u < c->lo[0] || u > c->hi[0])
            continue;
        double h2 = 1.0;
        for (int k = 0; k < 3; k++) {
            double q = c->qc[0][k] + u * c->qc[1][k] + v * c->qc[2][k];
            h2 -= q * q;
        }
        if (!(h2 >= -1e-9))
            continue;
        double tc = c->tc[0] + u * c->tc[1] + v * c->tc[2], hw = sqrt(fmax(h2, 0.0) * c->inv_a) + 1e-9 * slack;
        double x = tc - hw, y = tc + hw;
        if (!(y > 0))
            continue;
        x = x < 0 ? 0 : x;
        insert_chord(t0, t1, n++, x, y);
    }
    for (int k = 0; k < n; m++) {
        double hi = t1[k++];
        for (; k < n && t0[k] < hi - slack; k++)
            hi = t1[k] > hi ? t1[k] : hi;
    }
    return m;
}

int cu_sun_tile_boxes(const cu_cloud *cl, vec3 sun_dir, int size, int tiles, int boxes[][4])
{
    vec3 right, up;
    cu_sun_basis(sun_dir, &right, &up);
    double R = cu_sun_radius(cl);
    int best = 0, first[4], n = cl->n < CU_MAX_ELLIPSOIDS ? cl->n : CU_MAX_ELLIPSOIDS, in_row[CU_MAX_ELLIPSOIDS];
    shadow_chord ch[CU_MAX_ELLIPSOIDS];
    for (int i = 0; i < n; i++)
        chord_setup(&ch[i], cl->c[i], cl->r[i], right, up, sun_dir, R);
    if (tiles > CU_SUN_TILES_MAX)
        tiles = CU_SUN_TILES_MAX;
    cu_sun_map_texels(cl, right, up, R, size, first);
    for (int j = 0; j < tiles; j++)
        for (int k = 0; k < 4; k++)
            boxes[j][k] = j == 0 ? first[k] : k < 2 ? size : 0; /* empty until a texel widens it */
    /* every texel of the first box, through its centre as the shader casts it, against the ellipsoids whose shadow
     * reaches its row */
    for (int y = first[1]; y < first[3]; y++) {
        double v = ((y + 0.5) / size * 2 - 1) * R;
        int n_row = 0;
        for (int i = 0; i < n; i++)
            if (v >= ch[i].lo[1] && v <= ch[i].hi[1])
                in_row[n_row++] = i;
        for (int x = first[0]; x < first[2] && n_row > 1; x++) {
            double u = ((x + 0.5) / size * 2 - 1) * R;
            int m = intervals_apart(ch, in_row, n_row, u, v, 1e-4 * R);
            best = m > best ? m : best;
            for (int j = 1; j < m && j < tiles; j++) {
                int *bx = boxes[j];
                bx[0] = x < bx[0] ? x : bx[0];
                bx[1] = y < bx[1] ? y : bx[1];
                bx[2] = x + 1 > bx[2] ? x + 1 : bx[2];
                bx[3] = y + 1 > bx[3] ? y + 1 : bx[3];
            }
        }
        if (n_row == 1 && best < 1)
            best = 1; /* a row one ellipsoid's shadow alone crosses: one interval where it meets it */
    }
    for (int j = 1; j < tiles; j++) /* a texel wider each way, within the first box */
        if (boxes[j][2] > boxes[j][0])
            for (int k = 0; k < 2; k++) {
                boxes[j][k] = boxes[j][k] - 1 > first[k] ? boxes[j][k] - 1 : first[k];
                boxes[j][k + 2] = boxes[j][k + 2] + 1 < first[k + 2] ? boxes[j][k + 2] + 1 : first[k + 2];
            }
    return best;
}
