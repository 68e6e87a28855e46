/* tests/core/test_math.c: geometry and noise maths against closed forms: ray-ellipsoid chords (tangent, inside, far),
 * Kol's radial distance vs the exact Euclidean distance, sigmoid, log spacing, noise range/tiling/determinism,
 * neighbour lists vs the full maximum, and hull containment. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "density.h"

/* Deterministic test randomness (xorshift64*), so failures reproduce. */
static uint64_t rng_state = 0x9e3779b97f4a7c15ULL;
static double urand(void)
{
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    return (double)((rng_state * 2685821657736338717ULL) >> 11) / 9007199254740992.0;
}

static void test_ray_ellipsoid_chords(void **st)
{
    (void)st;
    double t0, t1;
    vec3 c = v3(1, 2, 3), r = v3(4, 2, 1);
    /* along x through the centre: enters at x = -3, leaves at x = 5 */
    assert_int_equal(cu_ray_ellipsoid(v3(-10, 2, 3), v3(1, 0, 0), c, r, &t0, &t1), 1);
    assert_true(fabs(t0 - 7) < 1e-12 && fabs(t1 - 15) < 1e-12);
    /* non-unit direction: t scales */
    assert_int_equal(cu_ray_ellipsoid(v3(-10, 2, 3), v3(2, 0, 0), c, r, &t0, &t1), 1);
    assert_true(fabs(t0 - 3.5) < 1e-12 && fabs(t1 - 7.5) < 1e-12);
    /* origin inside: t0 < 0 < t1 */
    assert_int_equal(cu_ray_ellipsoid(c, v3(0, 1, 0), c, r, &t0, &t1), 1);
    assert_true(fabs(t0 + 2) < 1e-12 && fabs(t1 - 2) < 1e-12);
    /* tangent: touches the top (y = 4) in one point */
    assert_int_equal(cu_ray_ellipsoid(v3(-10, 4, 3), v3(1, 0, 0), c, r, &t0, &t1), 1);
    assert_true(fabs(t1 - t0) < 1e-6 && fabs(t0 - 11) < 1e-6);
    /* just above: miss */
    assert_int_equal(cu_ray_ellipsoid(v3(-10, 4 + 1e-9, 3), v3(1, 0, 0), c, r, &t0, &t1), 0);
    /* behind the origin: both t negative (the caller clips) */
    assert_int_equal(cu_ray_ellipsoid(v3(10, 2, 3), v3(1, 0, 0), c, r, &t0, &t1), 1);
    assert_true(t0 < 0 && t1 < 0);
    /* a camera 100 km away: the cancellation-free form keeps the chord to 1e-9 relative */
    vec3 o = v3(-1e5, 2.5, 3);
    assert_int_equal(cu_ray_ellipsoid(o, v3(1, 0, 0), c, r, &t0, &t1), 1);
    double chord = 2 * 4 * sqrt(1 - 0.25 * 0.25); /* x half-width at y offset 0.5 of radius 2 */
    assert_true(fabs((t1 - t0) - chord) < 1e-9 * 1e5);
    /* random rays: the general chord formula from VALIDATION.md */
    for (int i = 0; i < 1000; i++) {
        vec3 oo = v3(urand() * 20 - 10, urand() * 20 - 10, urand() * 20 - 10);
        vec3 d = v3_norm(v3(urand() - 0.5, urand() - 0.5, urand() - 0.5));
        if (!cu_ray_ellipsoid(oo, d, c, r, &t0, &t1))
            continue;
        double A = 0, B = 0, C = -1;
        double od[3] = {oo.x - c.x, oo.y - c.y, oo.z - c.z}, dd[3] = {d.x, d.y, d.z}, rr[3] = {r.x, r.y, r.z};
        for (int k = 0; k < 3; k++) {
            A += dd[k] * dd[k] / (rr[k] * rr[k]);
            B += 2 * od[k] * dd[k] / (rr[k] * rr[k]);
            C += od[k] * od[k] / (rr[k] * rr[k]);
        }
        assert_true(fabs((t1 - t0) - sqrt(B * B - 4 * A * C) / A) < 1e-9);
    }
}

/* Exact Euclidean distance from an interior point to the ellipsoid surface (Eberly): the closest point is
 * x_i = r_i^2 y_i / (t + r_i^2) with t the root of sum (r_i y_i / (t + r_i^2))^2 = 1 in (-r_min^2, 0]. */
static double exact_distance_inside(vec3 y, vec3 r)
{
    double yy[3] = {fabs(y.x), fabs(y.y), fabs(y.z)}, rr[3] = {r.x, r.y, r.z};
    double rmin2 = fmin(rr[0] * rr[0], fmin(rr[1] * rr[1], rr[2] * rr[2]));
    double lo = -rmin2 + 1e-15 * rmin2, hi = 0;
    for (int it = 0; it < 200; it++) {
        double t = 0.5 * (lo + hi), f = -1;
        for (int k = 0; k < 3; k++) {
            double q = rr[k] * yy[k] / (t + rr[k] * rr[k]);
            f += q * q;
        }
        if (f > 0) lo = t; else hi = t;
    }
    double t = 0.5 * (lo + hi), d2 = 0;
    for (int k = 0; k < 3; k++) {
        double x = rr[k] * rr[k] * yy[k] / (t + rr[k] * rr[k]);
        d2 += (x - yy[k]) * (x - yy[k]);
    }
    return sqrt(d2);
}

static void test_radial_distance_vs_exact(void **st)
{
    (void)st;
    /* Sphere: the radial distance is exact. */
    for (int i = 0; i < 200; i++) {
        vec3 p = v3(urand() - 0.5, urand() - 0.5, urand() - 0.5);
        double d = cu_radial_distance(p, v3(0, 0, 0), v3(1, 1, 1));
        assert_true(fabs(d - (1 - v3_len(p))) < 1e-12);
    }
    /* Finite at the centre: the smallest radius. */
    assert_true(cu_radial_distance(v3(0, 250, 0), v3(0, 250, 0), v3(200, 120, 160)) == 120.0);
    /* Ellipsoids: the radial distance reaches one surface point, so it is never below the true (minimum) distance.
     * Report how much larger it is within the boundary layer (d_exact < h), where it shapes the density. */
    const vec3 shapes[] = {v3(200, 120, 160), v3(140, 100, 120), v3(300, 150, 250), v3(150, 60, 110)};
    const double h = 62;
    for (int s = 0; s < 4; s++) {
        vec3 r = shapes[s];
        double worst_abs = 0, sum_abs = 0;
        int n = 0;
        while (n < 20000) {
            vec3 p = v3((urand() * 2 - 1) * r.x, (urand() * 2 - 1) * r.y, (urand() * 2 - 1) * r.z);
            double sn = v3_len(v3(p.x / r.x, p.y / r.y, p.z / r.z));
            if (sn >= 1 || sn < 1e-3)
                continue;
            double de = exact_distance_inside(p, r), dr = cu_radial_distance(p, v3(0, 0, 0), r);
            assert_true(dr >= de - 1e-6 * r.x);
            if (de < h) {
                double e = dr - de;
                worst_abs = fmax(worst_abs, e);
                sum_abs += e;
                n++;
            }
        }
        printf("radial vs exact distance, radii %g %g %g, boundary h = %g m: mean excess %.2f m (%.1f%% of h), "
               "max %.2f m\n", r.x, r.y, r.z, h, sum_abs / n, 100 * sum_abs / n / h, worst_abs);
    }
}

static void test_sigmoid(void **st)
{
    (void)st;
    assert_true(cu_sigmoid(0) == 0 && cu_sigmoid(1) == 1 && cu_sigmoid(-3) == 0 && cu_sigmoid(7) == 1);
    assert_true(fabs(cu_sigmoid(0.5) - 0.5) < 1e-15);
    double e = 1e-5;
    /* s'(0) = s'(1) = 0 and s''(0) = s''(1) = 0 (Kol eq. 3.2) */
    assert_true(fabs((cu_sigmoid(e) - cu_sigmoid(0)) / e) < 1e-8);
    assert_true(fabs((cu_sigmoid(1) - cu_sigmoid(1 - e)) / e) < 1e-8);
    double prev = 0;
    for (int i = 1; i <= 1000; i++) {
        double v = cu_sigmoid(i / 1000.0);
        assert_true(v >= prev);
        prev = v;
    }
}

static void test_log_spacing(void **st)
{
    (void)st;
    double x[65];
    cu_log_spacing(5, 2.0, x);
    /* x_i = (2^i - 1) / 31 */
    for (int i = 0; i <= 5; i++)
        assert_true(fabs(x[i] - (pow(2, i) - 1) / 31.0) < 1e-15);
    for (int i = 1; i < 5; i++)
        assert_true(fabs((x[i + 1] - x[i]) / (x[i] - x[i - 1]) - 2.0) < 1e-12);
    cu_log_spacing(4, 1.0, x);
    for (int i = 0; i <= 4; i++)
        assert_true(fabs(x[i] - i / 4.0) < 1e-15);
    cu_log_spacing(64, 10.0, x);
    assert_true(x[0] == 0 && x[64] == 1 && x[1] > 0);
}

static uint64_t fnv1a(const uint8_t *p, size_t n)
{
    uint64_t h = 1469598103934665603ULL;
    for (size_t i = 0; i < n; i++) {
        h ^= p[i];
        h *= 1099511628211ULL;
    }
    return h;
}

static void test_noise(void **st)
{
    (void)st;
    cu_noise a, b;
    assert_int_equal(cu_noise_create(&a, 20130612u), 0);
    assert_int_equal(cu_noise_create(&b, 20130612u), 0);
    /* deterministic: the same bytes twice, and the same bytes as on the machine that made this checksum (integer
     * hash + IEEE double Perlin without FMA contraction, -std=c99): a compiler or CPU that changes the texture
     * changes every picture, and this says so first. */
    for (int L = 0; L < CU_NOISE_LEVELS; L++) {
        size_t n = (size_t)(64 >> L) * (64 >> L) * (64 >> L);
        assert_memory_equal(a.level[L], b.level[L], n);
    }
    uint64_t h = fnv1a(a.level[0], 64 * 64 * 64);
    printf("noise level 0 FNV-1a: %016llx\n", (unsigned long long)h);
    assert_true(h == 0x4bdf73edd9574a8cULL);
    /* different seeds differ */
    cu_noise c;
    assert_int_equal(cu_noise_create(&c, 7u), 0);
    assert_memory_not_equal(a.level[0], c.level[0], 64 * 64 * 64);
    /* mip levels are the rounded box filter of the level above */
    assert_int_equal(a.level[1][0], (a.level[0][0] + a.level[0][1] + a.level[0][64] + a.level[0][65] +
                                     a.level[0][4096] + a.level[0][4097] + a.level[0][4160] + a.level[0][4161] + 4) / 8);
    /* coarse levels keep variation, so eq. 3.74's 1.5 weight at LOD 4 has something to weigh */
    assert_true(a.level_std[4] > 0.08);
    /* range and tiling */
    double lo = 1, hi = -1;
    for (int i = 0; i < 20000; i++) {
        double p[3] = {urand() * 3, urand() * 3, urand() * 3};
        double v = cu_noise_fractal(&a, p, 5);
        assert_true(v >= -1 && v <= 1);
        lo = fmin(lo, v);
        hi = fmax(hi, v);
        double q[3] = {p[0] + 1, p[1] - 2, p[2] + 5};
        assert_true(fabs(cu_noise_fractal(&a, q, 5) - v) < 1e-12);
        for (int L = 0; L < 5; L++)
            assert_true(fabs(cu_noise_sample(&a, L, p[0], p[1], p[2]) - cu_noise_sample(&a, L, q[0], q[1], q[2])) <
                        1e-12);
    }
    printf("fractal noise range over 20000 samples: [%.3f, %.3f]\n", lo, hi);
    assert_true(lo < -0.8 && hi > 0.8); /* uses the whole [-1, 1] range */
    /* texel centres return the stored byte exactly */
    assert_true(fabs(cu_noise_sample(&a, 0, 0.5 / 64, 0.5 / 64, 0.5 / 64) - a.level[0][0] / 255.0) < 1e-12);
    cu_noise_destroy(&a);
    cu_noise_destroy(&b);
    cu_noise_destroy(&c);
}

static void random_cloud(cu_scene *s, int n, double spread)
{
    cu_scene_defaults(s);
    s->n_ellipsoids = n;
    for (int i = 0; i < n; i++) {
        for (int k = 0; k < 3; k++) {
            s->ell[i].center[k] = (urand() * 2 - 1) * spread;
            s->ell[i].radii[k] = 20 + urand() * 150;
        }
    }
}

static void test_neighbour_lists_identical(void **st)
{
    (void)st;
    cu_noise nz;
    assert_int_equal(cu_noise_create(&nz, 20130612u), 0);
    const int counts[] = {8, 32, 64};
    for (int ci = 0; ci < 3; ci++) {
        cu_scene s;
        random_cloud(&s, counts[ci], 150.0 * cbrt(counts[ci] / 8.0));
        cu_cloud cl;
        cu_cloud_build(&cl, &s, &nz);
        int inside = 0, pairs = 0;
        for (int i = 0; i < cl.n; i++)
            for (int j = 0; j < cl.n; j++)
                pairs += (int)((cl.neighbours[i] >> j) & 1);
        for (int k = 0; k < 20000; k++) {
            vec3 p = v3(cl.bounds_min.x + urand() * (cl.bounds_max.x - cl.bounds_min.x),
                        cl.bounds_min.y + urand() * (cl.bounds_max.y - cl.bounds_min.y),
                        cl.bounds_min.z + urand() * (cl.bounds_max.z - cl.bounds_min.z));
            double a = cu_cloud_distance(&cl, p, 1), b = cu_cloud_distance(&cl, p, 0);
            assert_true(a == b);
            inside += a >= 0;
        }
        printf("%d ellipsoids: %d of %d ordered pairs are neighbours, %d/20000 samples inside, identical\n", cl.n,
               pairs, cl.n * cl.n, inside);
        assert_true(inside > 1000);
    }
    cu_noise_destroy(&nz);
}

static void test_hull_contains_ellipsoid(void **st)
{
    (void)st;
    for (int tess = 3; tess <= 24; tess++) {
        int nv, ni;
        cu_hull_mesh(tess, NULL, NULL, &nv, &ni);
        float *v = malloc(sizeof(float) * 3 * (size_t)nv);
        uint16_t *idx = malloc(sizeof(uint16_t) * (size_t)ni);
        cu_hull_mesh(tess, v, idx, &nv, &ni);
        double worst = 1e9;
        for (int t = 0; t < ni; t += 3) {
            vec3 a = v3(v[3 * idx[t]], v[3 * idx[t] + 1], v[3 * idx[t] + 2]);
            vec3 b = v3(v[3 * idx[t + 1]], v[3 * idx[t + 1] + 1], v[3 * idx[t + 1] + 2]);
            vec3 c = v3(v[3 * idx[t + 2]], v[3 * idx[t + 2] + 1], v[3 * idx[t + 2] + 2]);
            vec3 nrm = v3_cross(v3_sub(b, a), v3_sub(c, a));
            if (v3_len(nrm) < 1e-12)
                continue; /* degenerate pole triangles */
            nrm = v3_norm(nrm);
            worst = fmin(worst, fabs(v3_dot(nrm, a))); /* plane distance from the centre */
        }
        assert_true(worst >= 1.0);
        free(v);
        free(idx);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ray_ellipsoid_chords), cmocka_unit_test(test_radial_distance_vs_exact),
        cmocka_unit_test(test_sigmoid),              cmocka_unit_test(test_log_spacing),
        cmocka_unit_test(test_noise),                cmocka_unit_test(test_neighbour_lists_identical),
        cmocka_unit_test(test_hull_contains_ellipsoid),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
