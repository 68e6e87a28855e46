/* tests/core/test_precision.c: a C twin of the cloud shader's per-sample maths (cloud.frag), instantiated in double,
 * float (highp on every GLES 3 GPU) and _Float16 (mediump on Mali/V3D/Adreno), run over the extremes of issue 7.
 * It prints where each precision breaks and asserts the design claims: fp32 in cloud-local coordinates is enough
 * everywhere in the matrix, and fp16 is not (positions, distances and optical depths must be highp). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <float.h>
#include <math.h>
#include <stdio.h>

/* One body per precision. Every intermediate is assigned to a variable of type T, so with _Float16 each operation
 * is rounded to half precision as a mediump GPU ALU would; sqrt/exp/pow are evaluated in float and rounded. */
#define TWIN(T, S)                                                                                                   \
    static T sq_##S(T x) { return (T)sqrtf((float)x); }                                                             \
    /* ray o + t d (d unit) against an axis-aligned ellipsoid at c with inverse radii ir: chord length, or -1 */    \
    static T chord_##S(const double o_[3], const double d_[3], const double c_[3], const double ir_[3])            \
    {                                                                                                              \
        T q[3], ds[3];                                                                                             \
        for (int k = 0; k < 3; k++) {                                                                              \
            T o = (T)o_[k], c = (T)c_[k], ir = (T)ir_[k], d = (T)d_[k];                                            \
            T diff = o - c;                                                                                        \
            q[k] = diff * ir;                                                                                      \
            ds[k] = d * ir;                                                                                        \
        }                                                                                                          \
        T A = ds[0] * ds[0] + ds[1] * ds[1] + ds[2] * ds[2];                                                       \
        T B = (T)2 * (q[0] * ds[0] + q[1] * ds[1] + q[2] * ds[2]);                                                 \
        T C = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] - (T)1;                                                      \
        T disc = B * B - (T)4 * A * C;                                                                             \
        if (!(disc > (T)0))                                                                                        \
            return (T)-1;                                                                                          \
        T s = sq_##S(disc);                                                                                        \
        T qq = (T)-0.5 * (B + (B >= (T)0 ? s : -s));                                                               \
        T ta = qq / A, tb = C / qq;                                                                                \
        return ta > tb ? ta - tb : tb - ta;                                                                        \
    }                                                                                                              \
    /* as cloud.frag does it: first move the ray origin along the ray to near the cloud (t_base = d . (c - o) - R),  \
     * so the quadratic sees small numbers; the chord is a difference and does not care where t starts */           \
    static T chord_shifted_##S(const double o_[3], const double d_[3], const double c_[3], const double ir_[3],     \
                               double R_)                                                                          \
    {                                                                                                              \
        T o[3], d[3], dot = 0;                                                                                     \
        for (int k = 0; k < 3; k++) {                                                                              \
            o[k] = (T)o_[k];                                                                                       \
            d[k] = (T)d_[k];                                                                                       \
            T rel = (T)c_[k] - o[k];                                                                               \
            dot = dot + rel * d[k];                                                                                \
        }                                                                                                          \
        T tb = dot - (T)R_;                                                                                        \
        if (tb < (T)0)                                                                                             \
            tb = 0;                                                                                                \
        double os[3];                                                                                              \
        for (int k = 0; k < 3; k++) {                                                                              \
            T v = o[k] + d[k] * tb;                                                                                \
            os[k] = (double)v;                                                                                     \
        }                                                                                                          \
        return chord_##S(os, d_, c_, ir_);                                                                         \
    }                                                                                                              \
    /* Kol's radial distance |q|(1/s - 1) */                                                                       \
    static T radial_##S(const double p_[3], const double c_[3], const double ir_[3])                               \
    {                                                                                                              \
        T l2 = 0, s2 = 0;                                                                                          \
        for (int k = 0; k < 3; k++) {                                                                              \
            T q = (T)p_[k] - (T)c_[k];                                                                             \
            T qs = q * (T)ir_[k];                                                                                  \
            l2 = l2 + q * q;                                                                                       \
            s2 = s2 + qs * qs;                                                                                     \
        }                                                                                                          \
        T len = sq_##S(l2), s = sq_##S(s2);                                                                        \
        return len / s - len;                                                                                      \
    }                                                                                                              \
    /* transmittance of a chord of length L at constant k_e by N geometric segments (eq. 3.22's running sum) */    \
    static T march_##S(double L_, double ke_, int n, double r_)                                                    \
    {                                                                                                              \
        T L = (T)L_, ke = (T)ke_, r = (T)r_;                                                                       \
        T rn = (T)powf((float)r, (float)n) - (T)1;                                                                 \
        T seg = L * (r - (T)1) / rn, t = 0, tau = 0;                                                               \
        for (int i = 0; i < n; i++) {                                                                              \
            T x = (i == n - 1) ? L - t : seg;                                                                      \
            t = t + x;                                                                                             \
            tau = tau + x * ke;                                                                                    \
            seg = seg * r;                                                                                         \
        }                                                                                                          \
        return (T)expf(-(float)tau);                                                                               \
    }                                                                                                              \
    /* noise texture coordinate p * freq + offset, then its fractional part (what the 64^3 tile sees) */           \
    static T noise_coord_##S(double p_, double freq_, double off_)                                                 \
    {                                                                                                              \
        T p = (T)p_, f = (T)freq_, o = (T)off_;                                                                    \
        T t = p * f + o;                                                                                           \
        T e = (T)8 * t; /* the 8x layer */                                                                         \
        return e - (T)floorf((float)e);                                                                            \
    }

TWIN(double, d)
TWIN(float, f)
#ifdef __FLT16_MAX__
TWIN(_Float16, h)
#define HAVE_F16 1
#else
#define HAVE_F16 0
#endif

static double rel(double a, double b) { return fabs(a - b) / fmax(fabs(b), 1e-300); }

static void test_chords_by_distance(void **st)
{
    (void)st;
    /* A 200 x 120 x 160 m ellipsoid seen from D metres, in cloud-local coordinates (origin at the cloud centre,
     * as the renderer passes them) and, for contrast, in world coordinates with the cloud at D. */
    const double c[3] = {0, 0, 0}, ir[3] = {1 / 200.0, 1 / 120.0, 1 / 160.0};
    const double Ds[] = {10, 300, 1e3, 1e4, 1e5};
    (void)chord_shifted_d;
    printf("chord through 200x120x160 m at distance D (relative error vs double):\n");
    printf("%10s %12s %12s %14s %14s %14s\n", "D (m)", "fp32 naive", "fp16 naive", "fp32 world", "fp32 shifted",
           "fp16 shifted");
    for (int i = 0; i < 5; i++) {
        double D = Ds[i];
        double o[3] = {0, 37.0, -(D + 200)}, d[3];
        double tgt[3] = {23.0, -11.0, 0}; /* an off-axis ray */
        double n = 0;
        for (int k = 0; k < 3; k++) {
            d[k] = tgt[k] - o[k];
            n += d[k] * d[k];
        }
        for (int k = 0; k < 3; k++)
            d[k] /= sqrt(n);
        double ref = chord_d(o, d, c, ir);
        double ef = rel(chord_f(o, d, c, ir), ref);
        /* world coordinates: the same geometry shifted by a large offset before the subtraction */
        double ow[3] = {o[0] + 1e5, o[1] + 1e3, o[2] + 3e5}, cw[3] = {1e5, 1e3, 3e5};
        double ew = rel(chord_f(ow, d, cw, ir), ref);
        double es = rel(chord_shifted_f(o, d, c, ir, 250.0), ref);
#if HAVE_F16
        double hh = (double)chord_h(o, d, c, ir), hs = (double)chord_shifted_h(o, d, c, ir, 250.0);
        double eh = hh < 0 || !isfinite(hh) ? INFINITY : rel(hh, ref);
        double ehs = hs < 0 || !isfinite(hs) ? INFINITY : rel(hs, ref);
#else
        double eh = NAN, ehs = NAN;
#endif
        printf("%10.0f %12.2e %12.2e %14.2e %14.2e %14.2e\n", D, ef, eh, ew, es, ehs);
        /* The naive fp32 chord loses digits as D grows (the quadratic's terms grow like D^2); moving the origin
         * first keeps it at rounding level to 100 km. 1e-5 of a 300 m chord is 3 mm, 2e-4 optical depth. */
        assert_true(es < 1e-5);
        if (D >= 1e4)
            assert_true(ef > 1e-5); /* and the naive form really does break: the shift is needed */
#if HAVE_F16
        if (D >= 1e3)
            assert_true(eh > 1e-2 && ehs > 1e-3); /* fp16 cannot even hold the positions: they must be highp */
#endif
    }
}

static void test_radial_distance_near_surface(void **st)
{
    (void)st;
    /* d/h decides the density in the boundary; h = 62 m. Points 1 m inside the surface of the default ellipsoid. */
    const double c[3] = {0, 0, 0}, ir[3] = {1 / 200.0, 1 / 120.0, 1 / 160.0};
    double worst_f = 0, worst_h = 0;
    for (int i = 0; i < 200; i++) {
        double a = i * 0.0314159, b = i * 0.0121;
        double u[3] = {cos(a) * cos(b), sin(b), sin(a) * cos(b)};
        double s = sqrt(pow(u[0] * ir[0], 2) + pow(u[1] * ir[1], 2) + pow(u[2] * ir[2], 2));
        double R = 1 / s, p[3];
        for (int k = 0; k < 3; k++)
            p[k] = u[k] * (R - 1.0);
        double ref = radial_d(p, c, ir);
        worst_f = fmax(worst_f, fabs(radial_f(p, c, ir) - ref) / 62.0);
#if HAVE_F16
        worst_h = fmax(worst_h, fabs((double)radial_h(p, c, ir) - ref) / 62.0);
#endif
    }
    printf("radial distance 1 m inside the surface: worst |error| / h: fp32 %.2e, fp16 %.2e\n", worst_f, worst_h);
    assert_true(worst_f < 1e-4);
#if HAVE_F16
    assert_true(worst_h > 1e-3); /* fp16: the boundary position moves by a visible fraction of h */
#endif
}

static void test_optical_depth(void **st)
{
    (void)st;
    /* Long chords through dense cloud: k_e = 0.0693 m^-1 (400 cm^-3, Mie) over 10 m .. 5 km, 5 and 64 segments. */
    const double Ls[] = {10, 100, 1000, 5000};
    for (int i = 0; i < 4; i++)
        for (int n = 5; n <= 64; n += 59) {
            double ref = march_d(Ls[i], 0.0693, n, 1.6);
            double ef = fabs(march_f(Ls[i], 0.0693, n, 1.6) - ref);
#if HAVE_F16
            double eh = fabs((double)march_h(Ls[i], 0.0693, n, 1.6) - ref);
#else
            double eh = NAN;
#endif
            printf("transmittance over %5.0f m, %2d segments: %.3e; abs error fp32 %.1e, fp16 %.1e\n", Ls[i], n, ref,
                   ef, eh);
            assert_true(ef < 1e-5);
        }
#if HAVE_F16
    /* fp16: 1.6^64 overflows 65504, the segment length underflows to 0 and the chord ends in one huge last step;
     * the result stays finite only by luck of the clamping. Assert the overflow is real. */
    assert_true(!isfinite((double)(_Float16)powf(1.6f, 64.0f)));
#endif
}

static void test_noise_coordinates(void **st)
{
    (void)st;
    /* The 8x noise layer at positions up to 50 km from the cloud centre (radii up to 50 km are allowed). The tile
     * coordinate's fractional part must be accurate to a small fraction of a texel (1/64 of the 125 m tile). */
    const double ps[] = {100, 1000, 10000, 50000};
    for (int i = 0; i < 4; i++) {
        double ref = noise_coord_d(ps[i] + 0.37, 1e-3, 0.123);
        double ef = fabs(noise_coord_f(ps[i] + 0.37, 1e-3, 0.123) - ref);
#if HAVE_F16
        double eh = fabs((double)noise_coord_h(ps[i] + 0.37, 1e-3, 0.123) - ref);
#else
        double eh = NAN;
#endif
        printf("noise coordinate at %6.0f m: error in texels of the 8x layer: fp32 %.2e, fp16 %.2e\n", ps[i],
               ef * 64, eh * 64);
        if (ps[i] <= 10000)
            assert_true(ef * 64 < 0.01);
    }
}

int main(void)
{
    printf("_Float16 available: %s\n", HAVE_F16 ? "yes" : "no (fp16 columns are NaN)");
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_chords_by_distance),
        cmocka_unit_test(test_radial_distance_near_surface),
        cmocka_unit_test(test_optical_depth),
        cmocka_unit_test(test_noise_coordinates),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
