/* tests/platform/test_drm_mode.c: `--mode` parsing and the DRM mode choice (preferred, largest, exact size and
 * refresh). */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <string.h>
#include <cmocka.h>
#include "drm_mode.h"

/* A typical HDMI monitor's list (as drmModeGetConnector reports it: preferred first, then by size). */
static const cu_mode_info monitor[] = {
    { 1920, 1080, 60.00, 1, 0 }, { 1920, 1080, 59.94, 0, 0 }, { 1920, 1080, 50.00, 0, 0 },
    { 1920, 1080, 60.00, 0, 1 }, { 1280, 720, 60.00, 0, 0 }, { 1280, 720, 50.00, 0, 0 },
    { 2560, 1440, 30.00, 0, 0 }, { 720, 576, 50.00, 0, 0 },
};
#define N ((int)(sizeof monitor / sizeof monitor[0]))

static void test_parse(void **state)
{
    (void)state;
    int w, h;
    double hz;
    char err[256];
    assert_int_equal(cu_drm_parse_mode("1920x1080", &w, &h, &hz, err, sizeof err), 0);
    assert_true(w == 1920 && h == 1080 && hz == 0.0);
    assert_int_equal(cu_drm_parse_mode("1280x720@59.94", &w, &h, &hz, err, sizeof err), 0);
    assert_true(w == 1280 && h == 720 && hz > 59.93 && hz < 59.95);
    static const char *bad[] = { "", "1920", "1920x", "x1080", "1920x1080@", "1920x1080@0", "1920*1080",
                                 "0x10", "1920x1080@60Hz", "99999x1" };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        err[0] = '\0';
        assert_int_not_equal(cu_drm_parse_mode(bad[i], &w, &h, &hz, err, sizeof err), 0);
        assert_non_null(strstr(err, "--mode"));
    }
}

static void test_pick(void **state)
{
    (void)state;
    assert_int_equal(cu_drm_pick_mode(monitor, N, 0, 0, 0), 0);           /* preferred */
    assert_int_equal(cu_drm_pick_mode(monitor, N, 1920, 1080, 0), 0);     /* highest refresh, progressive */
    assert_int_equal(cu_drm_pick_mode(monitor, N, 1920, 1080, 59.94), 1);
    assert_int_equal(cu_drm_pick_mode(monitor, N, 1920, 1080, 50), 2);
    assert_int_equal(cu_drm_pick_mode(monitor, N, 1280, 720, 0), 4);
    assert_int_equal(cu_drm_pick_mode(monitor, N, 1280, 720, 50.2), 5);
    assert_int_equal(cu_drm_pick_mode(monitor, N, 1280, 720, 75), -1);    /* no such refresh */
    assert_int_equal(cu_drm_pick_mode(monitor, N, 1024, 768, 0), -1);     /* no such size */
    /* No preferred mode: the largest progressive one. */
    assert_int_equal(cu_drm_pick_mode(monitor + 1, N - 1, 0, 0, 0), 5);   /* 2560x1440 */
    assert_int_equal(cu_drm_pick_mode(monitor, 0, 0, 0, 0), -1);
    char list[256];
    cu_drm_list_modes(monitor + 3, 2, list, sizeof list);
    assert_string_equal(list, "1920x1080@60.00i 1280x720@60.00");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_parse),
        cmocka_unit_test(test_pick),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
