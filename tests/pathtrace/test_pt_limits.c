/* tests/pathtrace/test_pt_limits.c: the path tracer cannot hang: ray/ellipsoid chords never come back NaN, however
 * small or large the radii (the library's range aside), and a path stops after max_steps tracking steps, counted. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "ellipsoid.h"
#include "pt.h"
#include "scene.h"

/* Radii far outside the scene's range (1e-100 overflowed the textbook quadratic into a NaN interval that delta
 * tracking never left): a hit has finite, ordered ends that contain the centre's parameter, or it is a miss. */
static void test_chord_never_nan(void **st)
{
    (void)st;
    const double radii[] = {1e-300, 1e-100, 1e-20, 0.1, 1, 1e5, 1e20, 1e100, 1e300};
    const vec3 origins[] = {v3(0, 0, -1e6), v3(0, 0, -1), v3(1e-3, 0, 0), v3(0.3, -0.2, -5e5)};
    for (size_t i = 0; i < sizeof radii / sizeof radii[0]; i++)
        for (size_t j = 0; j < sizeof origins / sizeof origins[0]; j++) {
            double r = radii[i], t0, t1;
            vec3 o = origins[j], d = v3_norm(v3_sub(v3(0, 0, 0), o));
            if (!cu_ray_ellipsoid(o, d, v3(0, 0, 0), v3(r, r, r), &t0, &t1))
                continue;
            if (!isfinite(t0) || !isfinite(t1) || !(t0 <= t1))
                fail_msg("radii %g from (%g %g %g): chord [%g, %g]", r, o.x, o.y, o.z, t0, t1);
            double tc = v3_len(o); /* the ray points at the centre */
            if (!(t0 <= tc * (1 + 1e-12) && t1 >= tc * (1 - 1e-12)))
                fail_msg("radii %g from (%g %g %g): chord [%g, %g] misses the centre at %g", r, o.x, o.y, o.z, t0,
                         t1, tc);
        }
}

/* The legal extremes of optical thickness (radii 1e5 m, k_e 6e7 m^-1: tau 1e13, every step a collision): each path
 * is cut at max_steps, counted, and the image stays finite. */
static void test_steps_bounded(void **st)
{
    (void)st;
    static const char text[] = "[camera]\nposition = 0 0 0\nlook_at = 0 0 1\n[sun]\nelevation = 30\n"
                               "[cloud]\ndensity = 1e7\ndroplet_radius = 1000\n"
                               "[ellipsoid]\ncenter = 0 0 0\nradii = 1e5 1e5 1e5\n";
    cu_scene *s;
    cu_error e;
    if (cu_scene_parse(&s, "limits.scene", text, strlen(text), &e))
        fail_msg("%s", e.msg);
    s->width = 4;
    s->height = 3;
    pt_ctx *c = malloc(sizeof *c);
    assert_non_null(c);
    if (pt_ctx_init(c, s, "data", &e))
        fail_msg("%s", e.msg);
    assert_true(c->max_steps == PT_MAX_STEPS);
    c->max_steps = 5000;
    pt_render_opts o = {4, 3, 2, 1, 3, 0, PT_MODE_RADIANCE, 0};
    float mean[3 * 12];
    pt_counters k;
    assert_int_equal(pt_render(c, &o, mean, NULL, &k, &e), 0);
    assert_int_equal(k.paths, 24);
    assert_int_equal(k.step_capped, 24);
    assert_true(k.density_evals <= 24 * 5000);
    for (int i = 0; i < 3 * 12; i++)
        assert_true(isfinite(mean[i]) && mean[i] >= 0);
    /* a transmittance ray alone is bounded too (it starts its own count) */
    pt_rng rng;
    pt_rng_seed(&rng, 1, 0);
    assert_true(pt_transmittance(c, v3(0, 0, 0), v3(0, 1, 0), &rng, &k) == 0.0);
    pt_ctx_free(c);
    free(c);
    cu_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_chord_never_nan),
        cmocka_unit_test(test_steps_bounded),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
