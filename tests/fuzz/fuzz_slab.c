/* tests/fuzz/fuzz_slab.c: libFuzzer target for the slab model table loader (data/slab_fit_bouthors.txt's format). */
#include "fuzz.h"
#include "slabmodel.h"
#include <math.h>

static void check_nodes(const double *v, int n, int max, const char *what)
{
    FUZZ_CHECK(n >= 1 && n <= max, "%d %s nodes", n, what);
    for (int i = 0; i < n; i++) {
        FUZZ_CHECK(isfinite(v[i]), "%s node %d = %g", what, i, v[i]);
        FUZZ_CHECK(i == 0 || v[i] > v[i - 1], "%s nodes not ascending at %d", what, i);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static cu_slab_model m; /* 150 kB: not on the stack */
    /* the transport of the committed tables (cu_slab_committed_transport: data/mie_cloud.tbl's chopped green) */
    const cu_slab_transport tr = {0.734, 0.55};
    cu_error err;
    memset(&err, 0x55, sizeof err);
    if (cu_slab_model_parse(&m, "fuzz.txt", (const char *)data, size, tr, &err)) {
        FUZZ_CHECK_MESSAGE(err.msg, "fuzz.txt");
        return 0;
    }
    check_nodes(m.t, m.nt, CU_SLAB_MAX_T, "thickness");
    check_nodes(m.thv, m.nv, CU_SLAB_MAX_V, "thetaV");
    check_nodes(m.thl, m.nl, CU_SLAB_MAX_L, "thetaL");
    check_nodes(m.th, m.np, CU_SLAB_MAX_P, "Theta");
    for (int g = 0; g < CU_SLAB_GROUPS; g++)
        for (int k = 0; k < m.nt; k++) {
            for (int i = 0; i < m.nv; i++)
                FUZZ_CHECK(m.a1[g][k][i] > 0 && isfinite(m.a1[g][k][i] + m.b1[g][k][i] + m.c[g][k][i] + m.d[g][k][i]),
                           "A1/B1/C/D at group %d, t %d, v %d", g, k, i);
            for (int i = 0; i < m.nl; i++)
                FUZZ_CHECK(m.a2[g][k][i] > 0 && isfinite(m.b2[g][k][i]), "A2/B2 at group %d, t %d, l %d", g, k, i);
            for (int i = 0; i < m.np; i++)
                FUZZ_CHECK(m.p[g][k][i] > 0 && isfinite(m.p[g][k][i]), "P at group %d, t %d, p %d", g, k, i);
        }
    for (int k = 0; k < m.nt; k++)
        for (int i = 0; i < m.nl; i++)
            FUZZ_CHECK(isfinite(m.kappa[k][i]) && m.kappa[k][i] >= 0 && m.kappa[k][i] <= 1 && isfinite(m.ms_up[k][i]) &&
                           isfinite(m.ms_down[k][i]),
                       "kappa %g, ms up %g down %g at t %d, l %d", m.kappa[k][i], m.ms_up[k][i], m.ms_down[k][i], k, i);
    /* the texture the shader samples: every texel finite */
    int w = cu_slab_model_tex_width(&m), h = cu_slab_model_tex_height(&m);
    float *tex = calloc((size_t)w * h * 4, sizeof *tex);
    FUZZ_CHECK(tex, "out of memory");
    cu_slab_model_pack(&m, tex);
    for (int i = 0; i < w * h * 4; i++)
        FUZZ_CHECK(isfinite(tex[i]), "texel %d of %dx%d = %g", i / 4, w, h, tex[i]);
    free(tex);
    /* the CPU twin of the shader at the first and last nodes and between them: finite, never negative */
    double up, down;
    for (int q = 0; q < 3; q++) {
        double t = q == 0 ? m.t[0] : q == 1 ? m.t[m.nt - 1] : 0.5 * (m.t[0] + m.t[m.nt - 1]);
        double v = cu_slab_model_eval(&m, 1, t, 0.5 * t, q == 1 ? m.thv[m.nv - 1] : m.thv[0],
                                      q == 1 ? m.thl[m.nl - 1] : m.thl[0], q == 1 ? m.th[m.np - 1] : m.th[0]);
        FUZZ_CHECK(isfinite(v) && v >= 0, "eval at t %g = %g", t, v);
        cu_slab_model_ms_budget(&m, t, m.thl[0], &up, &down);
        FUZZ_CHECK(isfinite(up) && isfinite(down), "budget at t %g: up %g down %g", t, up, down);
    }
    return 0;
}
