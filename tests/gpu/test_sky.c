/* tests/gpu/test_sky.c: the sky pass against the CPU's Preetham model (sky.c: cu_sky_radiance, in double precision):
 * every pixel of the analytic sky, through both headless back ends, over sun elevations from the horizon to high noon,
 * a clear and a hazy sky, and views toward the sun, the zenith and the horizon. The pass reads the Perez function as
 * the product of two tables (cu_sky_tables); this is what says the tables, their spacing, their storage and the
 * shader's lookup reproduce the model. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "render_util.h"
#include "scene.h"
#include "sky.h"

static const cu_display_backend *const backends[] = {&cu_display_egl, &cu_display_osmesa};
static const char *const backend_names[] = {"egl", "osmesa"};

#define W 96
#define H 72

/* One sky: renders it (linear output: radiance itself) and compares each pixel above the horizon and away from the
 * sun's disk with the CPU. Returns the largest relative error of any channel brighter than 2 % of the pixel's
 * brightest; *median gets the median of the pixels' largest errors. */
static double sky_error(tr_ctx *c, const char *const *sets, double *median)
{
    if (tr_render(c, "scenes/cumulus.scene", sets))
        fail_msg("%s", c->err);
    float *px = malloc(sizeof(float) * 3 * W * H);
    double *errs = malloc(sizeof(double) * W * H);
    assert_non_null(px);
    assert_non_null(errs);
    tr_read_rgbf(c, px);
    cu_scene *s;
    cu_error e;
    assert_int_equal(cu_scene_load(&s, "scenes/cumulus.scene", &e), 0);
    for (int i = 0; sets[i]; i++)
        assert_int_equal(cu_scene_set(s, sets[i], &e), 0);
    cu_sky sky;
    cu_sky_compute(&sky, s);
    double worst = 0;
    int n = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            vec3 d = tr_pixel_dir(s, W, H, x, y);
            if (d.y < 1e-3 || v3_dot(d, sky.sun_dir) > cos(1.0 * CU_PI / 180.0))
                continue;
            double want[3], peak = 0, err = 0;
            cu_sky_radiance(&sky, s, d, want);
            for (int k = 0; k < 3; k++)
                peak = want[k] > peak ? want[k] : peak;
            for (int k = 0; k < 3; k++) {
                const float got = px[3 * (y * W + x) + k];
                assert_false(isnan(got) || isinf(got));
                if (want[k] > 0.02 * peak) {
                    double r = fabs(got - want[k]) / want[k];
                    err = r > err ? r : err;
                }
            }
            errs[n++] = err;
            worst = err > worst ? err : worst;
        }
    assert_true(n > W * H / 8); /* the view holds sky to judge */
    for (int i = 1; i < n; i++) /* insertion sort: a few thousand values */
        for (int j = i; j > 0 && errs[j - 1] > errs[j]; j--) {
            double t = errs[j];
            errs[j] = errs[j - 1];
            errs[j - 1] = t;
        }
    *median = errs[n / 2];
    free(px);
    free(errs);
    cu_scene_free(s);
    return worst;
}

static void test_sky_is_preetham(void **st)
{
    (void)st;
    static const char *const elevations[] = {"sun.elevation=0.5", "sun.elevation=4", "sun.elevation=25",
                                             "sun.elevation=70"};
    static const char *const turbidities[] = {"sun.turbidity=2", "sun.turbidity=8"};
    /* toward the sun (its azimuth in cumulus.scene) low and high, straight up, and away from it along the horizon */
    static const char *const views[] = {"camera.look_at=0 160 -900", "camera.look_at=0 900 -900",
                                        "camera.look_at=1 5000 -1", "camera.look_at=0 160 900"};
    for (int b = 0; b < 2; b++) {
        tr_ctx c;
        if (tr_open(&c, backends[b], W, H, 1))
            fail_msg("%s", c.err);
        double worst = 0, worst_median = 0;
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 2; j++)
                for (int v = 0; v < 4; v++) {
                    const char *sets[] = {"cloud.density=0", "sky.model=preetham", elevations[i], turbidities[j],
                                          views[v], "camera.fov=70", NULL};
                    double median, err = sky_error(&c, sets, &median);
                    if (err > worst || getenv("CUMULO_TEST_DEBUG"))
                        printf("%s: %s %s %s: max %.5f median %.5f\n", backend_names[b], elevations[i],
                               turbidities[j], views[v], err, median);
                    worst = err > worst ? err : worst;
                    worst_median = median > worst_median ? median : worst_median;
                }
        printf("%s: the sky against cu_sky_radiance: max relative error %.5f, worst median %.5f\n", backend_names[b],
               worst, worst_median);
        /* Measured: 0.0006 and 0.00003. The same tables in fp16 give 0.029 and 0.0038 (xyY -> RGB amplifies their
         * rounding), read through a lowp sampler (GLES's default in a fragment shader) 0.08 and 0.004. */
        assert_true(worst < 0.002);
        assert_true(worst_median < 0.0002);
        tr_close(&c);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_sky_is_preetham)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
