/* src/core/slabmodel.c: the fitted slab multiple-scattering tables (eq. 3.32): strict loader, CPU evaluation (the twin
 * of shaders_gles/ms_slab.glsl) and texture packing. */
#include "slabmodel.h"
#include "error.h"
#include "phase.h"
#include "textfile.h"
#include "vecmath.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const group_names[CU_SLAB_GROUPS] = {"1", "2", "3", "4", "5-6", "7-9", "10-15", "16+"};
/* the lowest scattering order of each group: a thin slab's group n scales like tau^n */
static const int group_min_order[CU_SLAB_GROUPS] = {1, 2, 3, 4, 5, 7, 10, 16};

enum { F_P, F_A1, F_B1, F_C, F_D, F_A2, F_B2, F_COUNT };
static const char *const field_names[F_COUNT] = {"P", "A1", "B1", "C", "D", "A2", "B2"};
static const char *const node_keys[F_COUNT] = {"Theta", "thetaV", "thetaV", "thetaV", "thetaV", "thetaL", "thetaL"};

/* Index of x in the ascending node list, appending it when new; -1 when the list is full. */
static int node_index(double *nodes, int *n, int max, double x)
{
    for (int i = 0; i < *n; i++)
        if (fabs(nodes[i] - x) < 1e-9 * fmax(1.0, fabs(x)))
            return i;
    if (*n == max)
        return -1;
    nodes[(*n)++] = x;
    return *n - 1;
}

static int ascending(const double *v, int n)
{
    for (int i = 1; i < n; i++)
        if (!(v[i] > v[i - 1]))
            return 0;
    return 1;
}

/* The largest value of each (group, thickness) fit over the cells the simulator sampled (depths j t / 10, the
 * angle nodes, azimuths 0..180 every 45 deg), leaving out the structural zeros the fitter leaves out too (no diffuse
 * light going down at d = 0 or up at d = t). Between and beyond those cells eq. 3.32 is unconstrained and its
 * parameters can make it spike far above any simulated value (sizes in tools/slab/README.md, "How the renderer uses
 * the fit"); log_bound = log(2 x that maximum) caps it. */
static double node_value(const cu_slab_model *m, int g, int k, int iv, int il, double d, double log_p);
static void bound_groups(cu_slab_model *m)
{
    for (int g = 0; g < CU_SLAB_GROUPS; g++)
        for (int k = 0; k < m->nt; k++) {
            m->log_bound[g][k] = 1e30;
            double best = 0;
            for (int j = 0; j <= 10; j++)
                for (int iv = 0; iv < m->nv; iv++)
                    for (int il = 0; il < m->nl; il++)
                        for (int ph = 0; ph <= 180; ph += 45) {
                            if ((j == 0 && m->thv[iv] < 90) || (j == 10 && m->thv[iv] > 90))
                                continue;
                            double tv = m->thv[iv] * CU_PI / 180, tl = m->thl[il] * CU_PI / 180;
                            double ct = cos(tl) * cos(tv) + sin(tl) * sin(tv) * cos(ph * CU_PI / 180);
                            double th = acos(fmax(-1.0, fmin(1.0, ct))) * 180 / CU_PI, w;
                            int ip = 0;
                            while (ip < m->np - 2 && th > m->th[ip + 1])
                                ip++;
                            w = (th - m->th[ip]) / (m->th[ip + 1] - m->th[ip]);
                            w = fmax(0.0, fmin(1.0, w));
                            double lp = (1 - w) * log(m->p[g][k][ip]) + w * log(m->p[g][k][ip + 1]);
                            best = fmax(best, node_value(m, g, k, iv, il, j * m->t[k] / 10, lp));
                        }
            m->log_bound[g][k] = log(2 * fmax(best, 1e-30));
        }
}

static double hg(double g, double mu)
{
    double d = 1 + g * g - 2 * g * mu;
    return (1 - g * g) / (4 * CU_PI * d * sqrt(d));
}

/* Energy: a non-absorbing slab of optical thickness tau lit at mu0 sends out exactly what it receives, so its
 * multiply scattered flux is 1 - e^(-tau/mu0) - (R1 + T1), single scattering by its closed forms, for the transport
 * the tables were simulated with (tr: HG, or a chopped Mie table as delta-M: tau' = (1 - f) tau, g' = (g - f)/(1 - f),
 * single scattering approximated by HG(g')). The fitted orders
 * 2..16+, integrated over the hemispheres at d = 0 (up) and d = t (down), give more than that for thick slabs and
 * less for thin ones (by how much: tools/slab/README.md, "How the renderer uses the fit"). Where they give more,
 * kappa scales them down to the flux available; where less, they are left alone (kappa <= 1: the model is capped,
 * never inflated). */
static void conserve_energy(cu_slab_model *m, cu_slab_transport tr)
{
    enum { NV = 36, NP = 24 };
    for (int k = 0; k < m->nt; k++)
        for (int il = 0; il < m->nl; il++)
            m->kappa[k][il] = 1;
    for (int k = 0; k < m->nt; k++)
        for (int il = 0; il < m->nl; il++) {
            double t = m->t[k], tau = t * CU_SLAB_KE_REF * tr.tau_scale, thl = m->thl[il];
            double mu0 = cos(thl * CU_PI / 180);
            double ms = 0, ss = 0, ms_up = 0;
            for (int i = 0; i < NV; i++)
                for (int j = 0; j < NP; j++) {
                    double thv = (i + 0.5) * 180.0 / NV, ph = (j + 0.5) * 180.0 / NP; /* phi symmetric */
                    double tv = thv * CU_PI / 180, tl = thl * CU_PI / 180;
                    double ct = cos(tl) * cos(tv) + sin(tl) * sin(tv) * cos(ph * CU_PI / 180);
                    double th = acos(fmax(-1.0, fmin(1.0, ct))) * 180 / CU_PI;
                    double mu = fabs(cos(tv)), dw = sin(tv) * (CU_PI / NV) * (2 * CU_PI / NP);
                    int up = thv > 90;
                    double c = cu_slab_model_eval(m, 1, t, up ? 0 : t, thv, thl, th) * mu * dw / mu0;
                    ms += c;
                    ms_up += up ? c : 0;
                    /* single scattering out of the top (up) or bottom, I / F per Chandrasekhar, flux / (mu0 F) */
                    double p = hg(tr.g, ct);
                    double s1 = up ? p * mu0 / (mu + mu0) * (1 - exp(-tau * (1 / mu + 1 / mu0)))
                                   : (fabs(mu - mu0) < 1e-9 ? p * tau / mu0 * exp(-tau / mu0)
                                                            : p * mu0 / (mu0 - mu) * (exp(-tau / mu0) - exp(-tau / mu)));
                    ss += s1 * mu * dw / mu0;
                }
            double avail = 1 - exp(-tau / mu0) - ss;
            if (ms > avail && avail > 0)
                m->kappa[k][il] = avail / ms;
            m->ms_up[k][il] = m->kappa[k][il] * ms_up;
            m->ms_down[k][il] = m->kappa[k][il] * (ms - ms_up);
        }
}

/* Storage for one parsed value: which field, group, thickness node and angle node. */
typedef struct { int field, group, it, in; double value; int line; } entry;

static int read_model(cu_slab_model *m, cu_textfile tf, cu_slab_transport tr, cu_error *err);

int cu_slab_model_load(cu_slab_model *m, const char *path, cu_slab_transport tr, cu_error *err)
{
    memset(m, 0, sizeof *m);
    cu_textfile tf;
    if (cu_textfile_open(&tf, path, "the slab model table", "tools/slab/gen_tables.sh makes it", err))
        return 1;
    return read_model(m, tf, tr, err);
}

int cu_slab_model_parse(cu_slab_model *m, const char *name, const char *text, size_t len, cu_slab_transport tr,
                        cu_error *err)
{
    memset(m, 0, sizeof *m);
    cu_textfile tf;
    if (cu_textfile_open_mem(&tf, name, text, len, err))
        return 1;
    return read_model(m, tf, tr, err);
}

/* The table from tf, an open reader that this closes. */
static int read_model(cu_slab_model *m, cu_textfile tf, cu_slab_transport tr, cu_error *err)
{
    const char *path = tf.path;
    size_t cap = 4096, n = 0;
    entry *e = malloc(cap * sizeof *e);
    int rc = 1, r;
    unsigned char (*seen)[CU_SLAB_GROUPS][CU_SLAB_MAX_T][CU_SLAB_MAX_V] = NULL; /* each value exactly once */
    /* node grids are collected in file order, then checked ascending */
    int nn[F_COUNT] = {0};
    double nodes[F_COUNT][CU_SLAB_MAX_V];
    while (e && (r = cu_textfile_next(&tf, err)) != 0) {
        int ln = tf.line;
        if (r < 0)
            goto out;
        if (tf.ntok != 5) {
            cu_fail(err, "%s:%d: expected 'name group t_m node value', got %s fields", path, ln,
                    tf.ntok > 5 ? "more" : "fewer");
            goto out;
        }
        const char *name = tf.tok[0], *group = tf.tok[1], *tstr = tf.tok[2], *node = tf.tok[3], *val = tf.tok[4];
        entry x = {.line = ln, .field = -1, .group = -1};
        for (int k = 0; k < F_COUNT; k++)
            if (!strcmp(name, field_names[k]))
                x.field = k;
        if (x.field < 0) {
            cu_fail(err, "%s:%d: field 'name': unknown function '%.31s' (P, A1, B1, C, D, A2, B2)", path, ln, name);
            goto out;
        }
        for (int g = 0; g < CU_SLAB_GROUPS; g++)
            if (!strcmp(group, group_names[g]))
                x.group = g;
        if (x.group < 0) {
            cu_fail(err, "%s:%d: field 'group': unknown group '%.31s' (1 2 3 4 5-6 7-9 10-15 16+)", path, ln, group);
            goto out;
        }
        double t;
        cu_num_status s = cu_text_number(tstr, &t);
        if (s == CU_NUM_NOT_FLOAT) {
            cu_text_fail_float(&tf, err, "t_m", tstr);
            goto out;
        }
        if (s != CU_NUM_OK || t <= 0) {
            cu_fail(err, "%s:%d: field 't_m': '%.63s' is not a positive number", path, ln, tstr);
            goto out;
        }
        x.it = node_index(m->t, &m->nt, CU_SLAB_MAX_T, t);
        if (x.it < 0) {
            cu_fail(err, "%s:%d: field 't_m': more than %d thickness nodes", path, ln, CU_SLAB_MAX_T);
            goto out;
        }
        const char *key = node_keys[x.field];
        size_t kl = strlen(key);
        double a;
        if (strncmp(node, key, kl) || node[kl] != '=' || cu_text_number(node + kl + 1, &a) != CU_NUM_OK || a < 0 ||
            a > 180) {
            cu_fail(err, "%s:%d: field 'node': expected %s=<degrees in [0, 180]>", path, ln, key);
            goto out;
        }
        int max = x.field == F_P ? CU_SLAB_MAX_P : x.field >= F_A2 ? CU_SLAB_MAX_L : CU_SLAB_MAX_V;
        int slot = x.field == F_P ? 0 : x.field >= F_A2 ? 2 : 1;
        x.in = node_index(nodes[slot], &nn[slot], max, a);
        if (x.in < 0) {
            cu_fail(err, "%s:%d: field 'node': too many %s nodes", path, ln, key);
            goto out;
        }
        s = cu_text_number(val, &x.value);
        if (s == CU_NUM_NOT_FLOAT) {
            cu_text_fail_float(&tf, err, "value", val);
            goto out;
        }
        if (s != CU_NUM_OK) {
            cu_fail(err, "%s:%d: field 'value': '%.63s' is not a finite number", path, ln, val);
            goto out;
        }
        /* the model takes logarithms of P, A1, A2 (and exponentiates C, D in the fit): they must be positive */
        int positive = x.field != F_B1 && x.field != F_B2;
        if (positive && !(x.value > 0)) {
            cu_fail(err, "%s:%d: field 'value': %s must be positive", path, ln, name);
            goto out;
        }
        if (n == cap) {
            entry *ne = realloc(e, 2 * cap * sizeof *e);
            if (!ne) {
                cu_fail(err, "%s:%d: out of memory", path, ln);
                goto out;
            }
            e = ne;
            cap *= 2;
        }
        e[n++] = x;
    }
    int ln = tf.line;
    if (!e) {
        cu_fail(err, "%s: out of memory", path);
        goto out;
    }
    m->np = nn[0];
    m->nv = nn[1];
    m->nl = nn[2];
    memcpy(m->th, nodes[0], sizeof(double) * (size_t)m->np);
    memcpy(m->thv, nodes[1], sizeof(double) * (size_t)m->nv);
    memcpy(m->thl, nodes[2], sizeof(double) * (size_t)m->nl);
    if (m->nt < 1 || m->np < 2 || m->nv < 2 || m->nl < 1) {
        cu_fail(err, "%s:%d: table incomplete: %d thickness, %d Theta, %d thetaV, %d thetaL nodes", path, ln, m->nt,
                m->np, m->nv, m->nl);
        goto out;
    }
    if (!ascending(m->t, m->nt) || !ascending(m->th, m->np) || !ascending(m->thv, m->nv) ||
        !ascending(m->thl, m->nl)) {
        cu_fail(err, "%s: node grids must be listed in ascending order (thickness and each angle)", path);
        goto out;
    }
    /* every value exactly once */
    seen = calloc(1, sizeof *seen * F_COUNT);
    if (!seen) {
        cu_fail(err, "%s: out of memory", path);
        goto out;
    }
    for (size_t i = 0; i < n; i++) {
        entry *x = &e[i];
        if (seen[x->field][x->group][x->it][x->in]++) {
            cu_fail(err, "%s:%d: duplicate entry for %s", path, x->line, field_names[x->field]);
            goto out;
        }
        double *dst = NULL;
        switch (x->field) {
        case F_P: dst = &m->p[x->group][x->it][x->in]; break;
        case F_A1: dst = &m->a1[x->group][x->it][x->in]; break;
        case F_B1: dst = &m->b1[x->group][x->it][x->in]; break;
        case F_C: dst = &m->c[x->group][x->it][x->in]; break;
        case F_D: dst = &m->d[x->group][x->it][x->in]; break;
        case F_A2: dst = &m->a2[x->group][x->it][x->in]; break;
        default: dst = &m->b2[x->group][x->it][x->in]; break;
        }
        *dst = x->value;
    }
    for (int f = 0; f < F_COUNT; f++) {
        int cnt = f == F_P ? m->np : f >= F_A2 ? m->nl : m->nv;
        for (int g = 0; g < CU_SLAB_GROUPS; g++)
            for (int it = 0; it < m->nt; it++)
                for (int in = 0; in < cnt; in++)
                    if (!seen[f][g][it][in]) {
                        cu_fail(err, "%s:%d: missing %s for group %s, t = %g m, node %d", path, ln, field_names[f],
                                group_names[g], m->t[it], in);
                        goto out;
                    }
    }
    for (int k = 0; k < m->nt; k++)
        for (int il = 0; il < m->nl; il++)
            m->kappa[k][il] = 1;
    bound_groups(m);
    conserve_energy(m, tr);
    rc = 0;
out:
    free(seen);
    free(e);
    cu_textfile_close(&tf);
    return rc;
}

/* Bracketing node and weight of x on an ascending grid, clamped to its ends. */
static int bracket(const double *v, int n, double x, double *w)
{
    if (n == 1 || x <= v[0]) {
        *w = 0;
        return 0;
    }
    if (x >= v[n - 1]) {
        *w = 1;
        return n - 2;
    }
    int i = 0;
    while (x > v[i + 1])
        i++;
    *w = (x - v[i]) / (v[i + 1] - v[i]);
    return i;
}

/* Eq. 3.32 at one (thV, thL) node pair, without the cos thL factor, given log P*. Evaluated in log space: the fit
 * can leave compensating parameters (a huge A1* against a tiny log^2 ratio) whose product overflows fp32 in the
 * shader, so the texture holds log A1*, log A2*, log P*. The log^2 guards are the fitter's (tools/slab). */
static double node_value(const cu_slab_model *m, int g, int k, int iv, int il, double d, double log_p)
{
    double B = m->b1[g][k][iv] - m->b2[g][k][il];
    double Cs = m->c[g][k][iv], D = m->d[g][k][iv];
    double num = log(d + D), den = log(fmax(B + D, 1e-9));
    den = fmax(den * den, 1e-8);
    double l = log_p + log(m->a1[g][k][iv]) + log(m->a2[g][k][il]) + log(fmax(num * num, 1e-30)) - log(den) -
               (d - B) * (d - B) / fmax(2 * Cs * Cs, 1e-12);
    /* the fit is trusted up to twice the largest value it takes where it was fitted (see bound_groups), and scaled
     * so that a slab never returns more than it receives (see conserve_energy) */
    return exp(fmin(l, m->log_bound[g][k])) * m->kappa[k][il];
}

/* One group at thickness node k, depth d (m, at that node's thickness). */
static double group_at_node(const cu_slab_model *m, int g, int k, double d, double thv, double thl, double theta)
{
    double wp, wv, wl;
    int ip = bracket(m->th, m->np, theta, &wp);
    /* P* log-linear between its nodes (as the fitter interpolates it) */
    double p = (1 - wp) * log(m->p[g][k][ip]) + wp * log(m->p[g][k][ip + 1]);
    int iv = bracket(m->thv, m->nv, thv, &wv);
    int il = bracket(m->thl, m->nl, thl, &wl);
    int il1 = m->nl > 1 ? il + 1 : il;
    double v00 = node_value(m, g, k, iv, il, d, p), v10 = node_value(m, g, k, iv + 1, il, d, p);
    double v01 = node_value(m, g, k, iv, il1, d, p), v11 = node_value(m, g, k, iv + 1, il1, d, p);
    return (1 - wl) * ((1 - wv) * v00 + wv * v10) + wl * ((1 - wv) * v01 + wv * v11);
}

void cu_slab_model_ms_budget(const cu_slab_model *m, double t, double thl, double *up, double *down)
{
    *up = *down = 0;
    if (!(t > 0) || m->nt < 1 || m->nl < 1)
        return;
    /* thickness as in cu_slab_model_eval: linear in log t between nodes; t^2 below the first, constant above */
    int k = 0, k1 = 0;
    double wt = 0, wl, s = 1;
    if (t <= m->t[0]) {
        s = (t / m->t[0]) * (t / m->t[0]);
    } else if (t >= m->t[m->nt - 1]) {
        k = k1 = m->nt - 1;
    } else {
        k = bracket(m->t, m->nt, t, &wt);
        k1 = k + 1;
        wt = log(t / m->t[k]) / log(m->t[k1] / m->t[k]);
    }
    int il = bracket(m->thl, m->nl, thl, &wl), il1 = m->nl > 1 ? il + 1 : il;
#define LERP2(a) (((1 - wt) * ((1 - wl) * a[k][il] + wl * a[k][il1]) + wt * ((1 - wl) * a[k1][il] + wl * a[k1][il1])) * s)
    *up = LERP2(m->ms_up);
    *down = LERP2(m->ms_down);
#undef LERP2
}

double cu_slab_model_eval(const cu_slab_model *m, int first_group, double t, double d, double thv, double thl,
                          double theta)
{
    if (!(t > 0))
        return 0;
    d = fmin(fmax(d, 0.0), t);
    double rel = d / t, sum = 0;
    double cos_l = cos(fmin(fmax(thl, 0.0), 90.0) * CU_PI / 180.0);
    for (int g = first_group; g < CU_SLAB_GROUPS; g++) {
        double c;
        double t0 = m->t[0], t1 = m->t[m->nt - 1];
        if (t <= t0) {
            /* thinner than the tables: group n grows like tau^n from the thinnest node (same relative depth) */
            c = group_at_node(m, g, 0, rel * t0, thv, thl, theta) * pow(t / t0, group_min_order[g]);
        } else if (t >= t1) {
            /* thicker: the thickest node at the same relative depth; the diffuse field of a thick slab falls
             * linearly with depth, so the transmitted side scales like t1 / t (diffusion: T ~ 1 / t) */
            c = group_at_node(m, g, m->nt - 1, rel * t1, thv, thl, theta) * ((1 - rel) + rel * t1 / t);
        } else {
            double w;
            int k = bracket(m->t, m->nt, t, &w);
            w = log(t / m->t[k]) / log(m->t[k + 1] / m->t[k]); /* linear in log thickness */
            c = (1 - w) * group_at_node(m, g, k, rel * m->t[k], thv, thl, theta) +
                w * group_at_node(m, g, k + 1, rel * m->t[k + 1], thv, thl, theta);
        }
        sum += c;
    }
    return sum * cos_l;
}

int cu_slab_model_tex_width(const cu_slab_model *m)
{
    return m->nv + m->nl + m->np;
}

int cu_slab_model_tex_height(const cu_slab_model *m)
{
    return (CU_SLAB_GROUPS - 1) * m->nt;
}

void cu_slab_model_pack(const cu_slab_model *m, float *rgba)
{
    int w = cu_slab_model_tex_width(m);
    for (int g = 1; g < CU_SLAB_GROUPS; g++)
        for (int k = 0; k < m->nt; k++) {
            float *row = rgba + 4 * (size_t)w * (size_t)((g - 1) * m->nt + k);
            memset(row, 0, sizeof(float) * 4 * (size_t)w);
            for (int i = 0; i < m->nv; i++) {
                row[4 * i + 0] = (float)log(m->a1[g][k][i]);
                row[4 * i + 1] = (float)m->b1[g][k][i];
                row[4 * i + 2] = (float)m->c[g][k][i];
                row[4 * i + 3] = (float)m->d[g][k][i];
            }
            for (int i = 0; i < m->nl; i++) {
                row[4 * (m->nv + i) + 0] = (float)log(m->a2[g][k][i]);
                row[4 * (m->nv + i) + 1] = (float)m->b2[g][k][i];
                row[4 * (m->nv + i) + 2] = (float)m->kappa[k][i];
            }
            for (int i = 0; i < m->np; i++)
                row[4 * (m->nv + m->nl + i)] = (float)log(m->p[g][k][i]);
            row[4 * (m->nv + m->nl) + 1] = (float)m->log_bound[g][k];
        }
}

int cu_slab_committed_transport(const char *data_dir, cu_slab_transport *tr, cu_error *err)
{
#if CU_SLAB_TABLES_MIE
    /* the committed tables: tools/slab/gen_tables.sh with the chopped green channel of data/mie_cloud.tbl */
    char path[1024];
    snprintf(path, sizeof path, "%s/mie_cloud.tbl", data_dir);
    cu_phase_table t;
    if (cu_phase_table_load_mie(&t, path, err))
        return 1;
    double f = t.f[1], g = t.g_full[1];
    cu_phase_table_free(&t);
    tr->tau_scale = 1 - f;
    tr->g = (g - f) / (1 - f);
#else
    (void)data_dir;
    (void)err;
    tr->g = 0.85; /* the committed tables: HG g = 0.85 (data/slab_MANIFEST.txt) */
    tr->tau_scale = 1;
#endif
    return 0;
}
