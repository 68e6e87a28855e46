/* tests/fuzz/fuzz_collector.c: libFuzzer target for the collector table loader (data/slab_collector.txt's format). */
#include "fuzz.h"
#include "collector.h"
#include <math.h>

static void check_nodes(const double *v, int n, int max, int min, const char *what)
{
    FUZZ_CHECK(n >= min && n <= max, "%d %s nodes", n, what);
    for (int i = 0; i < n; i++) {
        FUZZ_CHECK(isfinite(v[i]), "%s node %d = %g", what, i, v[i]);
        FUZZ_CHECK(i == 0 || v[i] > v[i - 1], "%s nodes not ascending at %d", what, i);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    cu_collector c;
    cu_error err;
    memset(&err, 0x55, sizeof err);
    if (cu_collector_parse(&c, "fuzz.txt", (const char *)data, size, &err)) {
        FUZZ_CHECK_MESSAGE(err.msg, "fuzz.txt");
        FUZZ_CHECK(!c.cell, "a failed load kept its cells");
        return 0;
    }
    check_nodes(c.t, c.nt, CU_COLL_MAX_T, 1, "thickness");
    check_nodes(c.thl, c.nl, CU_COLL_MAX_L, 1, "thetaL");
    check_nodes(c.thv, c.nv, CU_COLL_MAX_V, 2, "thetaV");
    check_nodes(c.phi, c.np, CU_COLL_MAX_P, 1, "phi");
    size_t cells = (size_t)c.nt * c.nl * CU_COLL_ND * c.nv * c.np;
    FUZZ_CHECK(c.cell, "no cells");
    for (size_t i = 0; i < cells; i++) {
        FUZZ_CHECK(isfinite(c.cell[3 * i]) && isfinite(c.cell[3 * i + 1]), "cell %zu: c = %g %g", i, c.cell[3 * i],
                   c.cell[3 * i + 1]);
        FUZZ_CHECK(isfinite(c.cell[3 * i + 2]) && c.cell[3 * i + 2] >= 0, "cell %zu: sigma = %g", i, c.cell[3 * i + 2]);
    }
    float *tex = malloc(sizeof(float) * 4 * cells);
    FUZZ_CHECK(tex, "out of memory");
    cu_collector_pack(&c, tex);
    for (size_t i = 0; i < 4 * cells; i++)
        FUZZ_CHECK(isfinite(tex[i]), "texel %zu = %g", i / 4, tex[i]);
    free(tex);
    cu_collector_free(&c);
    return 0;
}
