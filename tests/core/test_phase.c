/* tests/core/test_phase.c: the engine's phase tables: analytic ones against closed forms (normalisation, mean cosine,
 * VALIDATION.md values), the committed Mie table as loaded and chopped (eqs. 3.64-3.68), and the table parser on
 * hostile files with exact messages. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "phase.h"
#include "vecmath.h"

static void test_closed_forms(void **st)
{
    (void)st;
    /* VALIDATION.md: HG g = 0.85: p(0) = 6.54304, p(pi) = 0.003488 */
    assert_true(fabs(cu_phase_hg(0.85, 1.0) - 6.54304) < 1e-5);
    assert_true(fabs(cu_phase_hg(0.85, -1.0) - 0.003488) < 1e-6);
    cu_scene s;
    cu_scene_defaults(&s);
    cu_error e;
    const double gs[] = {0.0, 0.5, 0.86};
    for (int i = 0; i < 3; i++) {
        for (int m = 0; m < 2; m++) {
            s.phase = m ? CU_PHASE_HG : CU_PHASE_CORNETTE_SHANKS;
            s.phase_g = gs[i];
            cu_phase_table t;
            assert_int_equal(cu_phase_table_build(&t, &s, "data", &e), 0);
            double g = gs[i];
            double expect = m ? g : 3 * g * (4 + g * g) / (5 * (2 + g * g)); /* CS mean cosine, VALIDATION.md */
            printf("%s g=%.2f: integral %.6f, mean cosine %.6f (closed form %.6f)\n", m ? "HG" : "CS", g,
                   t.integral[1], t.mean_cos[1], expect);
            assert_true(fabs(t.integral[1] - 1.0) < 1e-4); /* trapezoid on 2048 angles */
            assert_true(fabs(t.mean_cos[1] - expect) < 1e-4);
            assert_null(t.peak);
            cu_phase_table_free(&t);
        }
    }
}

static void test_committed_mie_table(void **st)
{
    (void)st;
    cu_phase_table t;
    cu_error e;
    if (cu_phase_table_load_mie(&t, "data/mie_cloud.tbl", &e))
        fail_msg("%s", e.msg);
    for (int c = 0; c < 3; c++) {
        /* the chopped function integrates to 1 - f and the peak to f (eqs. 3.64-3.68) */
        printf("channel %d: integral(P~) = %.5f, f = %.5f, sum %.5f, g = %.5f, sigma_ext = %.2f um^2\n", c,
               t.integral[c], t.f[c], t.integral[c] + t.f[c], t.g_full[c], t.sigma_ext_um2[c]);
        assert_true(fabs(t.integral[c] + t.f[c] - 1.0) < 2e-3);
        assert_true(t.f[c] > 0.3 && t.f[c] < 0.6);
        assert_true(t.g_full[c] > 0.8 && t.g_full[c] < 0.9);
        for (int i = 0; i < t.n; i++) {
            assert_true(t.peak[3 * i + c] >= 0.0f && t.rgb[3 * i + c] > 0.0f);
            if (i * 180.0 / (t.n - 1) >= 8.0 + 0.1)
                assert_true(t.peak[3 * i + c] == 0.0f);
        }
        /* P~ is flat below the chop angle */
        assert_true(t.rgb[c] == t.rgb[3 * 50 + c]);
    }
    cu_phase_table_free(&t);
}

typedef struct bad_table {
    const char *text;
    const char *message;
} bad_table;

#define HEAD "channels 3\nlambda_nm 600 540 450\nsigma_ext_um2 173 173 172\ng 0.85 0.85 0.86\nchop_deg 8\nf 0.44 0.45 0.46\n"

static const bad_table bad[] = {
    {"", "t.tbl:0: incomplete table: needs lambda_nm, sigma_ext_um2, g, chop_deg, f and angles"},
    {HEAD "angles 3\n0 1 1 1\n90 1 1 1\n", "t.tbl:9: fewer angle rows than 'angles' says (truncated file?)"},
    {HEAD "angles 2\n0 1 1 1\n90 1 1 1\n", "t.tbl:9: the last angle row must be 180 degrees"},
    {HEAD "angles 2\n0 nan 1 1\n180 1 1 1\n", "t.tbl:8: angle row needs 4 finite numbers: theta_deg P_r P_g P_b"},
    {HEAD "angles 2\n0 1 1\n180 1 1 1\n", "t.tbl:8: angle row needs 4 finite numbers: theta_deg P_r P_g P_b"},
    {HEAD "angles 3\n0 1 1 1\n90 1 1 1\n45 1 1 1\n", "t.tbl:10: angles must rise from 0 to 180 degrees and P must be >= 0"},
    {HEAD "angles 2\n0 1 -1 1\n180 1 1 1\n", "t.tbl:8: angles must rise from 0 to 180 degrees and P must be >= 0"},
    {HEAD "angles 2\n0 1 1 1\n180 1 1 1\n180 1 1 1\n", "t.tbl:10: more angle rows than 'angles' says"},
    {"channels 4\n", "t.tbl:1: 'channels' must be 3"},
    {"colour 1 2 3\n", "t.tbl:1: unknown key 'colour'"},
    {"sigma_ext_um2 1 0 1\n", "t.tbl:1: 'sigma_ext_um2' needs 3 positive numbers"},
    {"chop_deg 95\n", "t.tbl:1: 'chop_deg' must be in (0, 90)"},
    {"angles 1e9\n", "t.tbl:1: 'angles' must be a count from 2 to 1000000"},
    {"g 0.8 0.8\n", "t.tbl:1: 'g' needs 3 numbers"},
    /* finite as doubles, inf once stored in the float tables */
    {HEAD "angles 2\n0 1 1e39 1\n180 1 1 1\n", "t.tbl:8: field 'P_g': '1e39' does not fit in a float (|x| <= 3.403e+38)"},
    {"sigma_ext_um2 1 1e300 1\n", "t.tbl:1: field 'sigma_ext_um2': '1e300' does not fit in a float (|x| <= 3.403e+38)"},
    {"# comment\n\n  \t\nchop_deg 1e39\n", "t.tbl:4: field 'chop_deg': '1e39' does not fit in a float (|x| <= 3.403e+38)"},
    /* a control byte is never part of a table, and quoting it back would drive the terminal (ESC [2J clears it) */
    {"channels 3\n\x1b[2Jcolour 1 2 3\n", "t.tbl:2: not a text file (byte 0x1b)"},
    {"# \x07 in a comment\n", "t.tbl:1: not a text file (byte 0x07)"},
};

static void test_hostile_tables(void **st)
{
    (void)st;
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        FILE *f = fopen("build/test-output/t.tbl", "w");
        assert_non_null(f);
        fputs(bad[i].text, f);
        fclose(f);
        cu_phase_table t;
        cu_error e;
        memset(&e, 0, sizeof e);
        int rc = cu_phase_table_load_mie(&t, "build/test-output/t.tbl", &e);
        const char *msg = strstr(e.msg, "t.tbl:");
        if (rc == 0 || !msg || strcmp(msg, bad[i].message) != 0)
            fail_msg("case %zu: rc %d\n got      '%s'\n expected '%s'", i, rc, e.msg, bad[i].message);
    }
    /* the line reader's own limits */
    FILE *f = fopen("build/test-output/t.tbl", "w");
    assert_non_null(f);
    fputs("channels 3\n", f);
    for (int i = 0; i < 600; i++)
        fputc('x', f);
    fputs("\n", f);
    fclose(f);
    cu_phase_table t;
    cu_error e;
    assert_int_not_equal(cu_phase_table_load_mie(&t, "build/test-output/t.tbl", &e), 0);
    assert_non_null(strstr(e.msg, "t.tbl:2: line longer than 510 characters"));
    f = fopen("build/test-output/t.tbl", "wb");
    assert_non_null(f);
    fwrite("channels 3\nchannels\0 3\n", 1, 23, f);
    fclose(f);
    assert_int_not_equal(cu_phase_table_load_mie(&t, "build/test-output/t.tbl", &e), 0);
    assert_non_null(strstr(e.msg, "t.tbl:2: NUL byte in the line"));
    assert_int_not_equal(cu_phase_table_load_mie(&t, "build/test-output/none.tbl", &e), 0);
    assert_non_null(strstr(e.msg, "cannot open the Mie table"));
}

/* Writes an HG-free test table: HEAD's keys with g given, then 181 rows (1 degree apart) of P = p0 + p1 cos(theta),
 * behind an optional UTF-8 byte-order mark. */
static void write_table(const char *bom, const char *g, double p0, double p1)
{
    FILE *f = fopen("build/test-output/t.tbl", "w");
    assert_non_null(f);
    fprintf(f, "%schannels 3\nlambda_nm 600 540 450\nsigma_ext_um2 173 173 172\ng %s\nchop_deg 8\nf 0 0 0\n"
               "angles 181\n", bom, g);
    for (int i = 0; i <= 180; i++) {
        double p = p0 + p1 * cos(i * CU_PI / 180);
        fprintf(f, "%d %.9g %.9g %.9g\n", i, p, p, p);
    }
    assert_int_equal(fclose(f), 0);
}

/* A table must integrate to what it claims: 2 pi int P dmu = 1, and the g it states. */
static void test_table_integrals(void **st)
{
    (void)st;
    cu_phase_table t;
    cu_error e;
    const double iso = 1 / (4 * CU_PI);
    /* isotropic, and P = (1 + 3 g mu) / 4 pi, whose g is g: both load, the second one behind a BOM */
    write_table("", "0 0 0", iso, 0);
    assert_int_equal(cu_phase_table_load_mie(&t, "build/test-output/t.tbl", &e), 0);
    assert_true(fabs(t.g_full[1]) < 1e-6);
    cu_phase_table_free(&t);
    write_table("\xef\xbb\xbf", "0.2 0.2 0.2", iso, 3 * 0.2 * iso);
    if (cu_phase_table_load_mie(&t, "build/test-output/t.tbl", &e))
        fail_msg("%s", e.msg);
    assert_true(fabs(t.g_full[1] - 0.2) < 1e-4);
    cu_phase_table_free(&t);
    static const struct { const char *g; double p0, p1; const char *message; } bad[] = {
        {"0 0 0", 0, 0, "t.tbl:7: field 'P_r': 2 pi int P dmu is 0, not 1"},
        {"0 0 0", 1, 0, "t.tbl:7: field 'P_r': 2 pi int P dmu is 12.566"},
        {"0.85 0 0", 1 / (4 * CU_PI), 0, "t.tbl:4: field 'g': 0.85, but P gives "},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        write_table("", bad[i].g, bad[i].p0, bad[i].p1);
        memset(&e, 0, sizeof e);
        int rc = cu_phase_table_load_mie(&t, "build/test-output/t.tbl", &e);
        const char *msg = strstr(e.msg, "t.tbl:");
        if (rc == 0 || !msg || strncmp(msg, bad[i].message, strlen(bad[i].message)) != 0)
            fail_msg("case %zu: rc %d\n got      '%s'\n expected '%s...'", i, rc, e.msg, bad[i].message);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_closed_forms),
        cmocka_unit_test(test_committed_mie_table),
        cmocka_unit_test(test_hostile_tables),
        cmocka_unit_test(test_table_integrals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
