/* tests/core/test_layer.c: src/core/layer.c, generated cumulus layers: type names, hostile specs, coverage against the
 * target over types, seeds and extents, bit-for-bit determinism, no overlap under the periodic distance, flat bases,
 * heights and ellipsoid counts per type, the size power law's exponent by maximum likelihood, coverage 1 and timing. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "layer.h"

/* The renderer's default boundary h = 62 m passes h/2. */
#define MARGIN 31.0

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static cu_layer_spec spec_of(cu_cumulus_type t, double coverage, double extent, uint64_t seed)
{
    cu_layer_spec s = {t, 800.0, 3000.0, coverage, extent, MARGIN, seed};
    return s;
}

static void generate(const cu_layer_spec *s, cu_layer *l)
{
    cu_error e = {{0}};
    int rc = cu_layer_generate(s, l, &e);
    if (rc)
        print_error("cu_layer_generate: %s\n", e.msg);
    assert_int_equal(rc, 0);
}

/* A raster of about 12 m cells: fine against the smallest visible footprints (radius 100 - 31 m). */
static int grid_for(double extent)
{
    int g = (int)(extent / 12.0);
    return g < 64 ? 64 : g > 4096 ? 4096 : g;
}

static double wrapped(double d, double L) { return d - L * floor(d / L + 0.5); }

/* Everything a layer promises about its geometry, checked cloud by cloud and over all pairs of footprints. */
static void check_layer(const cu_layer *l, const cu_layer_spec *s)
{
    const cu_cumulus_info *ti = cu_cumulus_type_info(s->type);
    double L = s->extent;
    int next = 0;
    for (int i = 0; i < l->n_clouds; i++) {
        const cu_layer_cloud *c = &l->clouds[i];
        assert_true(c->center[0] >= -0.5 * L && c->center[0] < 0.5 * L);
        assert_true(c->center[2] >= -0.5 * L && c->center[2] < 0.5 * L);
        assert_true(c->center[1] == s->base);
        assert_true(c->height > 0 && c->height <= s->thickness);
        assert_true(2.0 * c->radius >= ti->d_min - 1e-9 && 2.0 * c->radius <= ti->d_max + 1e-9);
        /* contiguous runs in order, count within the type's range (and never past 16) */
        assert_int_equal(c->first, next);
        assert_true(c->count >= ti->ell_min && c->count <= ti->ell_max && c->count <= CU_LAYER_MAX_PER_CLOUD);
        next += c->count;
        double top = 0;
        for (int k = c->first; k < c->first + c->count; k++) {
            const cu_layer_ellipsoid *e = &l->ell[k];
            for (int a = 0; a < 3; a++)
                assert_true(e->radii[a] >= CU_LAYER_MIN_RADIUS);
            double dx = e->center[0] - c->center[0], dz = e->center[2] - c->center[2];
            assert_true(sqrt(dx * dx + dz * dz) + fmax(e->radii[0], e->radii[2]) <= c->radius * (1 + 1e-12) + 1e-6);
            assert_true(e->center[1] - e->radii[1] >= s->base - 1e-6);
            assert_true(e->center[1] + e->radii[1] <= s->base + c->height + 1e-6);
            top = fmax(top, e->center[1] + e->radii[1] - s->base);
        }
        assert_true(fabs(top - c->height) < 1e-6);
    }
    assert_int_equal(next, l->n_ell);
    /* all pairs, wrapped: the clouds can drift together by any wind and wrap without touching */
    for (int i = 0; i < l->n_clouds; i++)
        for (int j = i + 1; j < l->n_clouds; j++) {
            const cu_layer_cloud *a = &l->clouds[i], *b = &l->clouds[j];
            double dx = wrapped(a->center[0] - b->center[0], L), dz = wrapped(a->center[2] - b->center[2], L);
            if (sqrt(dx * dx + dz * dz) < a->radius + b->radius)
                fail_msg("clouds %d and %d overlap: distance %.6f m < %.6f + %.6f m", i, j, sqrt(dx * dx + dz * dz),
                         a->radius, b->radius);
        }
}

static void test_type_names(void **st)
{
    (void)st;
    const char *names[] = {"cumulus-humilis", "cumulus-mediocris", "cumulus-congestus"};
    for (int i = 0; i < CU_CUMULUS_TYPES; i++) {
        cu_cumulus_type t = CU_CUMULUS_CONGESTUS;
        assert_int_equal(cu_cumulus_type_parse(names[i], &t), 0);
        assert_int_equal((int)t, i);
        assert_string_equal(cu_cumulus_type_name(t), names[i]);
        assert_string_equal(cu_cumulus_type_info(t)->name, names[i]);
    }
    const char *bad[] = {"", "cumulus", "Cumulus-humilis", "cumulus-humilis ", "cumulonimbus", "stratus"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        cu_cumulus_type t = CU_CUMULUS_MEDIOCRIS;
        assert_int_not_equal(cu_cumulus_type_parse(bad[i], &t), 0);
        assert_int_equal((int)t, CU_CUMULUS_MEDIOCRIS); /* untouched */
    }
    cu_cumulus_type t = CU_CUMULUS_HUMILIS;
    assert_int_not_equal(cu_cumulus_type_parse(NULL, &t), 0);
    assert_string_equal(cu_cumulus_type_name((cu_cumulus_type)3), "unknown");
    assert_null(cu_cumulus_type_info((cu_cumulus_type)-1));
}

static void expect_rejected(cu_layer_spec s, const char *field)
{
    cu_layer l = {(cu_layer_cloud *)&l, 5, (cu_layer_ellipsoid *)&l, 7}; /* garbage that must be emptied */
    cu_error e = {{0}};
    assert_int_not_equal(cu_layer_generate(&s, &l, &e), 0);
    if (!strstr(e.msg, field))
        fail_msg("message for a bad %s does not name it: %s", field, e.msg);
    assert_null(l.clouds);
    assert_null(l.ell);
    assert_int_equal(l.n_clouds, 0);
    assert_int_equal(l.n_ell, 0);
    cu_layer_free(&l);
}

static void test_hostile_specs(void **st)
{
    (void)st;
    const cu_layer_spec ok = spec_of(CU_CUMULUS_MEDIOCRIS, 0.3, 5000, 1);
    cu_layer l;
    generate(&ok, &l);
    assert_true(l.n_clouds > 0);
    cu_layer_free(&l);
    cu_layer_free(&l); /* twice, and NULL: harmless */
    cu_layer_free(NULL);

    const double bad_base[] = {-1, -1e-9, 20000.001, 1e300, NAN, INFINITY, -INFINITY};
    const double bad_thick[] = {49.99, 0, -100, 15000.5, NAN, INFINITY};
    const double bad_cov[] = {-0.001, 1.0001, 2, NAN, INFINITY, -INFINITY};
    const double bad_ext[] = {99.9, 0, -5000, 500001, NAN, INFINITY};
    const double bad_margin[] = {-0.001, -31, NAN, INFINITY};
    cu_layer_spec s;
    for (size_t i = 0; i < sizeof bad_base / sizeof bad_base[0]; i++)
        s = ok, s.base = bad_base[i], expect_rejected(s, "base");
    for (size_t i = 0; i < sizeof bad_thick / sizeof bad_thick[0]; i++)
        s = ok, s.thickness = bad_thick[i], expect_rejected(s, "thickness");
    for (size_t i = 0; i < sizeof bad_cov / sizeof bad_cov[0]; i++)
        s = ok, s.coverage = bad_cov[i], expect_rejected(s, "coverage");
    for (size_t i = 0; i < sizeof bad_ext / sizeof bad_ext[0]; i++)
        s = ok, s.extent = bad_ext[i], expect_rejected(s, "extent");
    for (size_t i = 0; i < sizeof bad_margin / sizeof bad_margin[0]; i++)
        s = ok, s.margin = bad_margin[i], expect_rejected(s, "margin");
    s = ok, s.type = (cu_cumulus_type)3, expect_rejected(s, "type");
    s = ok, s.type = (cu_cumulus_type)-1, expect_rejected(s, "type");
    /* valid fields, impossible together: a square narrower than two of the type's smallest clouds, a margin that
     * hides the largest, more clouds than the limit */
    s = spec_of(CU_CUMULUS_CONGESTUS, 0.3, 999, 1), expect_rejected(s, "extent");
    s = spec_of(CU_CUMULUS_HUMILIS, 0.3, 5000, 1), s.margin = 750, expect_rejected(s, "margin");
    s = spec_of(CU_CUMULUS_HUMILIS, 0.3, 500000, 1), expect_rejected(s, "20000 clouds");
    /* the edges of each range are accepted */
    s = spec_of(CU_CUMULUS_HUMILIS, 0.2, 5000, 1);
    s.base = 0, s.thickness = 50;
    generate(&s, &l), check_layer(&l, &s), cu_layer_free(&l);
    s.base = 20000, s.thickness = 15000, s.margin = 0;
    generate(&s, &l), check_layer(&l, &s), cu_layer_free(&l);
    s = spec_of(CU_CUMULUS_CONGESTUS, 0.02, 500000, 1);
    generate(&s, &l), check_layer(&l, &s), cu_layer_free(&l);
    s = spec_of(CU_CUMULUS_HUMILIS, 0.5, 400, 1); /* one 200 m cloud fits a 400 m square */
    generate(&s, &l), check_layer(&l, &s), cu_layer_free(&l);
}

static void test_coverage_zero(void **st)
{
    (void)st;
    for (int t = 0; t < CU_CUMULUS_TYPES; t++) {
        /* coverage 0 needs no clouds, so even a square too small for the type is fine */
        const double extents[] = {100, 5000, 500000};
        for (int x = 0; x < 3; x++) {
            cu_layer_spec s = spec_of((cu_cumulus_type)t, 0.0, extents[x], 9);
            cu_layer l;
            generate(&s, &l);
            assert_int_equal(l.n_clouds, 0);
            assert_int_equal(l.n_ell, 0);
            assert_true(cu_layer_coverage(&l, &s, 64) == 0.0);
            cu_layer_free(&l);
        }
    }
}

/* The raster against closed forms: one ellipse straddling the square's corner is counted whole, wrapped. */
static void test_coverage_raster(void **st)
{
    (void)st;
    const double L = 1000;
    cu_layer_cloud c = {{490, 0, -495}, 100, 50, 0, 1, 1};
    cu_layer_ellipsoid e = {{490, 25, -495}, {80, 25, 60}};
    cu_layer l = {&c, 1, &e, 1};
    cu_layer_spec s = spec_of(CU_CUMULUS_HUMILIS, 0.1, L, 1);
    s.margin = 10;
    double want = 3.14159265358979 * 70 * 50 / (L * L), got = cu_layer_coverage(&l, &s, 2000);
    printf("raster: one wrapped ellipse covers %.6f, closed form %.6f\n", got, want);
    assert_true(fabs(got - want) < 0.01 * want);
    s.margin = 60; /* shrunk to nothing along z */
    assert_true(cu_layer_coverage(&l, &s, 500) == 0.0);
    s.margin = 0;
    assert_true(cu_layer_coverage(&l, &s, 0) == -1.0);
    assert_true(cu_layer_coverage(&l, &s, 8193) == -1.0);
    assert_true(cu_layer_coverage(NULL, &s, 100) == -1.0);
}

static void test_coverage_accuracy(void **st)
{
    (void)st;
    const double covs[] = {0.05, 0.1, 0.3, 0.6}, extents[] = {5000, 20000, 50000};
    double worst = 0;
    printf("coverage error (measured - target), worst of seeds 1-3, margin %g m:\n", MARGIN);
    printf("%-18s %6s %8s %8s %8s %8s\n", "type", "km", "0.05", "0.1", "0.3", "0.6");
    for (int t = 0; t < CU_CUMULUS_TYPES; t++)
        for (int x = 0; x < 3; x++) {
            printf("%-18s %6.0f", cu_cumulus_type_name((cu_cumulus_type)t), extents[x] / 1000);
            for (int c = 0; c < 4; c++) {
                double w = 0;
                for (uint64_t seed = 1; seed <= 3; seed++) {
                    cu_layer_spec s = spec_of((cu_cumulus_type)t, covs[c], extents[x], seed);
                    cu_layer l;
                    generate(&s, &l);
                    double e = cu_layer_coverage(&l, &s, grid_for(s.extent)) - covs[c];
                    if (fabs(e) > fabs(w))
                        w = e;
                    cu_layer_free(&l);
                }
                printf(" %+8.4f", w);
                worst = fmax(worst, fabs(w));
            }
            printf("\n");
        }
    printf("worst |error| %.4f (tolerance 0.02)\n", worst);
    assert_true(worst <= 0.02);
}

/* FNV-1a over the arrays: one number to compare across machines. */
static uint64_t layer_hash(const cu_layer *l)
{
    uint64_t h = 0xcbf29ce484222325ULL;
    const unsigned char *p[2] = {(const unsigned char *)l->clouds, (const unsigned char *)l->ell};
    size_t n[2] = {sizeof *l->clouds * (size_t)l->n_clouds, sizeof *l->ell * (size_t)l->n_ell};
    for (int k = 0; k < 2; k++)
        for (size_t i = 0; i < n[k]; i++)
            h = (h ^ p[k][i]) * 0x100000001b3ULL;
    return h;
}

static void test_deterministic(void **st)
{
    (void)st;
    for (int t = 0; t < CU_CUMULUS_TYPES; t++) {
        cu_layer_spec s = spec_of((cu_cumulus_type)t, 0.6, 20000, 12345);
        cu_layer a, b, c;
        generate(&s, &a);
        generate(&s, &b);
        assert_int_equal(a.n_clouds, b.n_clouds);
        assert_int_equal(a.n_ell, b.n_ell);
        assert_memory_equal(a.clouds, b.clouds, sizeof *a.clouds * (size_t)a.n_clouds);
        assert_memory_equal(a.ell, b.ell, sizeof *a.ell * (size_t)a.n_ell);
        s.seed = 12346;
        generate(&s, &c);
        assert_true(a.n_clouds != c.n_clouds ||
                    memcmp(a.clouds, c.clouds, sizeof *a.clouds * (size_t)a.n_clouds) != 0);
        cu_layer_free(&a);
        cu_layer_free(&b);
        cu_layer_free(&c);
    }
    /* Across machines: these layers hashed to this value where the test was written (x86-64, GCC 12, glibc 2.36).
     * Another value means the arithmetic differs there (an FMA contraction, another pow), so the layers would too.
     * After a deliberate change to the generator, update it to the printed value. */
    uint64_t h = 0;
    for (int t = 0; t < CU_CUMULUS_TYPES; t++) {
        cu_layer_spec s = spec_of((cu_cumulus_type)t, 0.4, 10000, 7);
        cu_layer l;
        generate(&s, &l);
        h = h * 31 + layer_hash(&l);
        cu_layer_free(&l);
    }
    printf("hash of the three types at coverage 0.4 over 10 km, seed 7: 0x%016llx\n", (unsigned long long)h);
    assert_true(h == 0xc126585a266336d7ULL);
}

static void test_geometry_and_no_overlap(void **st)
{
    (void)st;
    const double covs[] = {0.1, 0.6}, extents[] = {5000, 20000};
    for (int t = 0; t < CU_CUMULUS_TYPES; t++)
        for (int c = 0; c < 2; c++)
            for (int x = 0; x < 2; x++)
                for (uint64_t seed = 1; seed <= 2; seed++) {
                    cu_layer_spec s = spec_of((cu_cumulus_type)t, covs[c], extents[x], seed);
                    cu_layer l;
                    generate(&s, &l);
                    check_layer(&l, &s);
                    cu_layer_free(&l);
                }
    /* a thin layer clips every type's heights, congestus most */
    for (int t = 0; t < CU_CUMULUS_TYPES; t++) {
        cu_layer_spec s = spec_of((cu_cumulus_type)t, 0.4, 20000, 3);
        s.thickness = 120;
        cu_layer l;
        generate(&s, &l);
        check_layer(&l, &s);
        cu_layer_free(&l);
    }
}

static void test_flat_base_and_heights(void **st)
{
    (void)st;
    for (int t = 0; t < CU_CUMULUS_TYPES; t++) {
        const cu_cumulus_info *ti = cu_cumulus_type_info((cu_cumulus_type)t);
        for (int thin = 0; thin < 2; thin++) {
            cu_layer_spec s = spec_of((cu_cumulus_type)t, 0.3, 20000, 77);
            s.base = 1234.5;
            s.thickness = thin ? 300 : 15000;
            cu_layer l;
            generate(&s, &l);
            int clipped = 0;
            for (int i = 0; i < l.n_clouds; i++) {
                const cu_layer_cloud *c = &l.clouds[i];
                double lowest = 1e300;
                int bottoms = 0;
                for (int k = c->first; k < c->first + c->count; k++) {
                    const cu_layer_ellipsoid *e = &l.ell[k];
                    double b = e->center[1] - e->radii[1];
                    lowest = fmin(lowest, b);
                    if (b < s.base + 1.0) {
                        /* a bottom ellipsoid: exactly on the base, and flat */
                        assert_true(fabs(b - s.base) < 1e-6);
                        assert_true(e->radii[1] <= fmin(e->radii[0], e->radii[2]));
                        bottoms++;
                    }
                }
                assert_true(fabs(lowest - s.base) < 1e-6);
                assert_true(bottoms >= 2); /* a base row, not a point */
                assert_true(l.ell[c->first].center[1] - l.ell[c->first].radii[1] < s.base + 1.0);
                /* height: the type's aspect ratio of D, or the layer thickness where that is lower */
                double D = 2 * c->radius, ratio = c->height / D;
                assert_true(c->height <= s.thickness + 1e-9);
                if (c->height >= s.thickness - 1e-6)
                    clipped++;
                else
                    assert_true(ratio >= ti->aspect_min - 1e-9 && ratio <= ti->aspect_max + 1e-9);
                if (t == CU_CUMULUS_CONGESTUS) /* tall: height >= width unless the layer stops it */
                    assert_true(c->height >= fmin(D, s.thickness) - 1e-6);
            }
            printf("%s, thickness %g m: %d of %d clouds reach it\n", ti->name, s.thickness, clipped, l.n_clouds);
            if (thin)
                assert_true(clipped > 0);
            else
                assert_int_equal(clipped, 0);
            cu_layer_free(&l);
        }
    }
}

static void test_ellipsoid_counts(void **st)
{
    (void)st;
    for (int t = 0; t < CU_CUMULUS_TYPES; t++) {
        const cu_cumulus_info *ti = cu_cumulus_type_info((cu_cumulus_type)t);
        cu_layer_spec s = spec_of((cu_cumulus_type)t, 0.3, 50000, 5);
        cu_layer l;
        generate(&s, &l);
        int seen[CU_LAYER_MAX_PER_CLOUD + 1] = {0};
        for (int i = 0; i < l.n_clouds; i++) {
            assert_true(l.clouds[i].count >= ti->ell_min && l.clouds[i].count <= ti->ell_max);
            seen[l.clouds[i].count]++;
        }
        printf("%s: ellipsoids per cloud", ti->name);
        for (int n = ti->ell_min; n <= ti->ell_max; n++) {
            printf(" %d:%d", n, seen[n]);
            assert_true(seen[n] > 0); /* every count of the range occurs */
        }
        printf("\n");
        cu_layer_free(&l);
    }
}

/* Mean of log D under N(D) ~ D^-b on [a, c]: with e = 1 - b, (c^e ln c - a^e ln a) / (c^e - a^e) - 1/e. */
static double mean_log(double b, double a, double c)
{
    double e = 1.0 - b, ca = pow(c, e), aa = pow(a, e);
    return (ca * log(c) - aa * log(a)) / (ca - aa) - 1.0 / e;
}

/* The maximum-likelihood exponent of a power law truncated to [a, c] solves E_b[ln D] = mean(ln D); E_b falls
 * with b, so bisection. Its standard error is 1 / sqrt(n Var(ln D)) (the Fisher information of the family). */
static void test_size_distribution(void **st)
{
    (void)st;
    const double documented = 1.7; /* layer.c: Neggers, Jonker & Siebesma 2003 */
    assert_true(CU_LAYER_SIZE_EXPONENT == documented);
    for (int t = 0; t < CU_CUMULUS_TYPES; t++) {
        const cu_cumulus_info *ti = cu_cumulus_type_info((cu_cumulus_type)t);
        double sum = 0, sum2 = 0;
        long n = 0;
        for (uint64_t seed = 1; seed <= 3; seed++) {
            cu_layer_spec s = spec_of((cu_cumulus_type)t, 0.3, 50000, seed);
            cu_layer l;
            generate(&s, &l);
            for (int i = 0; i < l.n_clouds; i++) {
                double v = log(2.0 * l.clouds[i].radius);
                sum += v;
                sum2 += v * v;
                n++;
            }
            cu_layer_free(&l);
        }
        double m = sum / n, var = sum2 / n - m * m, lo = 1.0001, hi = 6.0;
        for (int it = 0; it < 100; it++) {
            double mid = 0.5 * (lo + hi);
            if (mean_log(mid, ti->d_min, ti->d_max) > m)
                lo = mid;
            else
                hi = mid;
        }
        double b = 0.5 * (lo + hi), se = 1.0 / sqrt(n * var);
        printf("%s: %ld clouds, fitted b = %.3f +- %.3f (documented %.2f; tolerance 4 se)\n", ti->name, n, b, se,
               documented);
        assert_true(fabs(b - documented) <= 4.0 * se);
        assert_true(se < 0.1); /* enough clouds for the check to mean something */
    }
}

/* Coverage 1 cannot be packed: the layer stops at what random packing of its footprints reaches. */
static void test_coverage_one(void **st)
{
    (void)st;
    for (int t = 0; t < CU_CUMULUS_TYPES; t++) {
        cu_layer_spec s = spec_of((cu_cumulus_type)t, 1.0, 20000, 4);
        cu_layer l;
        double t0 = now_s();
        generate(&s, &l);
        double dt = now_s() - t0, cov = cu_layer_coverage(&l, &s, grid_for(s.extent));
        printf("%s, coverage 1 over 20 km: reaches %.3f with %d clouds in %.3f s\n",
               cu_cumulus_type_name((cu_cumulus_type)t), cov, l.n_clouds, dt);
        assert_true(cov >= 0.7 && cov < 1.0);
        assert_true(dt < 30.0);
        check_layer(&l, &s);
        cu_layer_free(&l);
    }
}

static void test_timing(void **st)
{
    (void)st;
    for (int t = 0; t < CU_CUMULUS_TYPES; t++) {
        cu_layer_spec s = spec_of((cu_cumulus_type)t, 0.6, 50000, 8);
        cu_layer l;
        double t0 = now_s();
        generate(&s, &l);
        double dt = now_s() - t0;
        printf("%s, coverage 0.6 over 50 km: %d clouds, %d ellipsoids in %.3f s\n",
               cu_cumulus_type_name((cu_cumulus_type)t), l.n_clouds, l.n_ell, dt);
        assert_true(dt < 10.0);
        cu_layer_free(&l);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_type_names),         cmocka_unit_test(test_hostile_specs),
        cmocka_unit_test(test_coverage_zero),      cmocka_unit_test(test_coverage_raster),
        cmocka_unit_test(test_coverage_accuracy),  cmocka_unit_test(test_deterministic),
        cmocka_unit_test(test_geometry_and_no_overlap), cmocka_unit_test(test_flat_base_and_heights),
        cmocka_unit_test(test_ellipsoid_counts),   cmocka_unit_test(test_size_distribution),
        cmocka_unit_test(test_coverage_one),       cmocka_unit_test(test_timing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
