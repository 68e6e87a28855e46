/* tests/core/test_tonemap.c: src/core/tonemap.c, the CPU twin of the display curve (shaders_gles/tonecurve.glsl, which
 * tonemap.frag and sky.frag apply): the shaders' source carries the same formula and constants, the curve matches
 * values worked out by hand from the shader's formula, and the 8-bit output agrees with the formula evaluated in
 * single precision (GLSL highp) over a range of radiances. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "tonemap.h"

#define STR_(x) #x
#define STR(x) STR_(x)

static char *read_text(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *b = calloc(1, 65537);
    size_t n = b ? fread(b, 1, 65536, f) : 0;
    fclose(f);
    if (b)
        b[n] = 0;
    return b;
}

/* The shader (run from the source tree, as every test) writes exactly the formula tonemap.h names. */
/* Each file must hold each of its strings: the curve in tonecurve.glsl, and the two shaders that apply it. */
static void expect_in(const char *path, const char *const *want, size_t n)
{
    char *src = read_text(path);
    assert_non_null(src);
    for (size_t i = 0; i < n; i++) {
        if (!strstr(src, want[i]))
            print_error("%s lacks: %s\n", path, want[i]);
        assert_non_null(strstr(src, want[i]));
    }
    free(src);
}

static void test_shader_has_the_same_curve(void **st)
{
    (void)st;
    const char *curve[] = {
        "x = max(x, vec3(0.0));",
        "clamp(x * (" STR(CU_TONEMAP_A) " * x + " STR(CU_TONEMAP_B) ") / (x * (" STR(CU_TONEMAP_C) " * x + " STR(
            CU_TONEMAP_D) ") + " STR(CU_TONEMAP_E) "), 0.0, 1.0)",
        "vec3 s1 = sqrt(c), s2 = sqrt(s1), s3 = sqrt(s2);",
        "mix(" STR(CU_SRGB_LINEAR) " * c, " STR(CU_SRGB_R1) " * s1 + " STR(CU_SRGB_R2) " * s2 - " STR(CU_SRGB_R3)
        " * s3 - " STR(CU_SRGB_R4) " * c,",
        "step(vec3(" STR(CU_SRGB_KNEE) "), c));",
        "return srgb(clamp(",
    };
    const char *tonemap[] = {"#include \"tonecurve.glsl\"",
                             "o_color = vec4(tone_curve(c.rgb * u_exposure / u_white), 1.0);"};
    const char *sky[] = {"#include \"tonecurve.glsl\"", "o_color = vec4(tone_curve(o_color.rgb), 1.0);"};
    expect_in("shaders_gles/tonecurve.glsl", curve, sizeof curve / sizeof curve[0]);
    expect_in("shaders_gles/tonemap.frag", tonemap, 2);
    expect_in("shaders_gles/sky.frag", sky, 2);
}

/* Points worked out from the shader's formula (in double precision, independently of tonemap.c). */
static void test_curve_at_points(void **st)
{
    (void)st;
    static const struct {
        double x, aces, srgb;
        int q;
    } pts[] = {
        {0.001, 0.0002312357784839482, 0.0029875662580126105, 1},
        {0.01, 0.003770279794447903, 0.049009185371460304, 12},
        {0.1, 0.1258396775638155, 0.3897383854058176, 99},
        {0.6, 0.6732904734073641, 0.8397562584407025, 214},
        {1.0, 0.8037974683544302, 0.9082985458276363, 232},
        {2.0, 0.914855072463768, 0.9616368963692226, 245},
        {4.0, 0.9734171097148379, 0.9882363862874952, 252},
        {7.0, 0.9988649262202043, 0.9995014865257776, 255},
        {16.0, 1.0, 0.999999999, 255},
    };
    for (size_t i = 0; i < sizeof pts / sizeof pts[0]; i++) {
        assert_true(fabs(cu_tonemap_aces(pts[i].x) - pts[i].aces) < 1e-12);
        assert_true(fabs(cu_tonemap_srgb(pts[i].aces) - pts[i].srgb) < 1e-12);
        /* exposure 0.06 and a white of 0.5: radiance x * 0.5 / 0.06 gives the exposed value x */
        double L = pts[i].x * 0.5 / 0.06;
        assert_true(fabs(cu_tonemap_channel(L, 0.06, 0.5) - pts[i].srgb) < 1e-12);
        assert_int_equal(cu_tonemap8(L, 0.06, 0.5), pts[i].q);
    }
    /* ends: black, negative and NaN radiance are black; the curve saturates to 255 */
    assert_int_equal(cu_tonemap8(0.0, 0.06, 1.0), 0);
    assert_int_equal(cu_tonemap8(-5.0, 0.06, 1.0), 0);
    assert_int_equal(cu_tonemap8(nan(""), 0.06, 1.0), 0);
    assert_int_equal(cu_tonemap8(1e9, 0.06, 1.0), 255);
    assert_true(fabs(cu_tonemap_srgb(1.0) - 1.0) < 1e-8);
    /* the sRGB knee is continuous to 1e-7 */
    double k = CU_SRGB_KNEE;
    assert_true(fabs(CU_SRGB_LINEAR * k - (CU_SRGB_SCALE * pow(k, 1.0 / CU_SRGB_GAMMA) - CU_SRGB_OFFSET)) < 1e-6);
    /* the roots' form: within 0.25/255 of the power from the knee to 1 (measured 0.247/255, at the knee, where it
     * steps up by that much), and rising */
    double worst = 0, last = CU_SRGB_LINEAR * k;
    for (int i = 0; i <= 1000000; i++) {
        double c = k + (1.0 - k) * i / 1e6, v = cu_tonemap_srgb(c);
        worst = fmax(worst, fabs(v - (CU_SRGB_SCALE * pow(c, 1.0 / CU_SRGB_GAMMA) - CU_SRGB_OFFSET)));
        assert_true(v >= last);
        last = v;
    }
    assert_true(worst < 0.25 / 255);
    unsigned char px[3];
    const float rgb[3] = {1.0f / 0.06f, 2.0f / 0.06f, 0.0f};
    const double white[3] = {1.0, 1.0, 1.0};
    cu_tonemap_rgb8(rgb, 0.06, white, px);
    assert_int_equal(px[0], 232);
    assert_int_equal(px[1], 245);
    assert_int_equal(px[2], 0);
}

/* The shader's maths in single precision, as a GLES highp float evaluates it, quantised like the RGBA8 target. */
static int shader8(float L, float exposure, float white)
{
    float x = L * exposure / white;
    x = x > 0.0f ? x : 0.0f;
    float t = x * (2.51f * x + 0.03f) / (x * (2.43f * x + 0.59f) + 0.14f);
    t = t < 0.0f ? 0.0f : t > 1.0f ? 1.0f : t;
    float s1 = sqrtf(t), s2 = sqrtf(s1), s3 = sqrtf(s2);
    float s = t < 0.0031308f ? 12.92f * t : 0.662002687f * s1 + 0.68412206f * s2 - 0.323583601f * s3 - 0.022541147f * t;
    int q = (int)floorf(s * 255.0f + 0.5f);
    return q < 0 ? 0 : q > 255 ? 255 : q;
}

static void test_matches_single_precision_shader(void **st)
{
    (void)st;
    int differ = 0, worst = 0;
    for (int i = 0; i <= 4000; i++) {
        double L = 1e-4 * pow(10.0, i / 500.0); /* 1e-4 .. 1e4 kcd/m^2 */
        for (int w = 0; w < 3; w++) {
            double white = 0.8 + 0.2 * w;
            int a = cu_tonemap8(L, 0.06, white), b = shader8((float)L, 0.06f, (float)white);
            int d = abs(a - b);
            differ += d != 0;
            worst = d > worst ? d : worst;
        }
    }
    /* float rounding may move a value across a level boundary, never further */
    assert_true(worst <= 1);
    assert_true(differ < 40);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_shader_has_the_same_curve),
        cmocka_unit_test(test_curve_at_points),
        cmocka_unit_test(test_matches_single_precision_shader),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
