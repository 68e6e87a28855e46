/* tests/gpu/test_composite.c: the one-pass composite (pass_sky.c: cu_pass_sky_draw_over): with the clouds drawn at
 * a lower resolution (quality.cloud_downsample) or on the temporal grid, tone-mapped output has the sky pass bring
 * them up over the sky and tone-map in one pass. Linear output still takes the separate passes (the HDR target, the
 * upsampling pass, a copy); tone-mapping that linear frame on the CPU (tonemap.c, the curve the shaders share) must
 * give the one-pass frame, pixel for pixel. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "render_util.h"
#include "scene.h"
#include "sky.h"
#include "tonemap.h"

#define W 160
#define H 120

static void check(const char *const *sets)
{
    tr_ctx c;
    float *lin = malloc(sizeof(float) * 3 * W * H);
    uint8_t *got = malloc((size_t)W * H * 4);
    assert_non_null(lin);
    assert_non_null(got);
    if (tr_open(&c, &cu_display_egl, W, H, 1) || tr_render(&c, "scenes/cumulus.scene", sets))
        fail_msg("%s", c.err);
    tr_read_rgbf(&c, lin);
    tr_close(&c);
    if (tr_open(&c, &cu_display_egl, W, H, 0) || tr_render(&c, "scenes/cumulus.scene", sets))
        fail_msg("%s", c.err);
    tr_read_rgba8(&c, got);
    tr_close(&c);
    cu_scene *s;
    cu_error e;
    assert_int_equal(cu_scene_load(&s, "scenes/cumulus.scene", &e), 0);
    for (int i = 0; sets[i]; i++)
        assert_int_equal(cu_scene_set(s, sets[i], &e), 0);
    double white[3];
    cu_sky_white_balance(s, white);
    int worst = 0, over = 0;
    for (int i = 0; i < W * H; i++) {
        unsigned char want[3];
        cu_tonemap_rgb8(lin + 3 * i, s->exposure, white, want);
        for (int k = 0; k < 3; k++) {
            int d = abs((int)want[k] - (int)got[4 * i + k]);
            worst = d > worst ? d : worst;
            over += d > 1;
        }
    }
    printf("%s %s: one pass against the separate passes tone-mapped on the CPU: max %d/255, %d values over 1\n",
           sets[0], sets[1], worst, over);
    /* the cloud image is RGBA16F in the one-pass frame, RGBA32F in the linear one: rounding, no more (measured:
     * 1/255 at most in all four) */
    assert_true(worst <= 1);
    assert_int_equal(over, 0);
    cu_scene_free(s);
    free(lin);
    free(got);
}

static void test_downsampled_clouds_in_one_pass(void **st)
{
    (void)st;
    const char *two[] = {"quality.cloud_downsample=2", "quality.temporal_grid=1", NULL};
    const char *four[] = {"quality.cloud_downsample=4", "quality.temporal_grid=1", NULL};
    check(two);
    check(four);
}

static void test_temporal_grid_in_one_pass(void **st)
{
    (void)st;
    const char *grid[] = {"quality.cloud_downsample=1", "quality.temporal_grid=2", NULL};
    const char *both[] = {"quality.cloud_downsample=2", "quality.temporal_grid=3", NULL};
    check(grid);
    check(both);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_downsampled_clouds_in_one_pass),
                                       cmocka_unit_test(test_temporal_grid_in_one_pass)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
