/* tests/fuzz/fuzz_mie.c: libFuzzer target for the Mie phase table loader (data/mie_cloud.tbl's format). */
#include "fuzz.h"
#include "phase.h"
#include <math.h>

static int float_ok(float v)
{
    return isfinite(v) && v >= 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    cu_phase_table t;
    cu_error err;
    memset(&err, 0x55, sizeof err);
    if (cu_phase_table_parse_mie(&t, "fuzz.tbl", (const char *)data, size, &err)) {
        FUZZ_CHECK_MESSAGE(err.msg, "fuzz.tbl");
        FUZZ_CHECK(!t.rgb && !t.peak, "a failed load kept its arrays");
        return 0;
    }
    FUZZ_CHECK(t.n == CU_PHASE_N && t.rgb && t.peak, "n = %d", t.n);
    /* what the shader samples: finite, non-negative floats */
    for (int i = 0; i < 3 * t.n; i++) {
        FUZZ_CHECK(float_ok(t.rgb[i]), "rgb[%d] = %g", i, t.rgb[i]);
        FUZZ_CHECK(float_ok(t.peak[i]), "peak[%d] = %g", i, t.peak[i]);
    }
    for (int c = 0; c < 3; c++) {
        FUZZ_CHECK(isfinite(t.sigma_ext_um2[c]) && t.sigma_ext_um2[c] > 0, "sigma_ext[%d] = %g", c, t.sigma_ext_um2[c]);
        FUZZ_CHECK(isfinite(t.integral[c]) && t.integral[c] >= 0, "integral[%d] = %g", c, t.integral[c]);
        FUZZ_CHECK(isfinite(t.mean_cos[c]) && fabs(t.mean_cos[c]) <= 1 + 1e-9, "mean_cos[%d] = %g", c, t.mean_cos[c]);
        FUZZ_CHECK(isfinite(t.f[c]) && t.f[c] >= 0, "f[%d] = %g", c, t.f[c]);
        /* a phase function integrates to 1 over the sphere (the loader checks it on the table's rows; this is the
         * engine's resampled grid), so its g and peak weight are in range */
        FUZZ_CHECK(fabs(t.integral[c] + t.f[c] - 1) < 0.05, "integral[%d] %g + f %g is not 1", c,
                           t.integral[c], t.f[c]);
        FUZZ_CHECK(isfinite(t.g_full[c]) && fabs(t.g_full[c]) <= 1, "g_full[%d] = %g", c, t.g_full[c]);
        FUZZ_CHECK(t.f[c] <= 1, "f[%d] = %g", c, t.f[c]);
    }
    cu_phase_table_free(&t);
    return 0;
}
