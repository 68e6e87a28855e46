/* tests/gpu/test_fallback.c: the GLES 3.0 floor. A context without float or half-float colour targets (Mesa told to
 * hide EXT_color_buffer_float and _half_float, as a GLES 3.0 driver without them) must fall back with a warning:
 * light.shadow peel -> front (no opacity map), ms.mode slab -> octaves (no slab maps), an RGBA8 HDR target whose
 * highlights clip, quality.edge_refine off, and still draw the same picture where nothing clips. Each render runs in
 * a child process: Mesa reads MESA_EXTENSION_OVERRIDE when it creates the context. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>
#include "renderer.h"
#include "target.h"
#include "render_util.h"

#define W 160
#define H 120

typedef struct result {
    int float_rt, half_rt, shadow, ms_mode, rgba8;
    uint8_t px[4 * W * H];
} result;

static int read_all(int fd, void *buf, size_t n)
{
    size_t got = 0;
    while (got < n) {
        ssize_t r = read(fd, (char *)buf + got, n - got);
        if (r <= 0)
            return 1;
        got += (size_t)r;
    }
    return 0;
}

/* Renders `scene` with `sets` in a child whose Mesa hides `hide` (NULL: nothing). */
static void render_child(const char *hide, const char *scene, const char *const *sets, result *out)
{
    int p[2];
    assert_int_equal(pipe(p), 0);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        close(p[0]);
        if (hide)
            setenv("MESA_EXTENSION_OVERRIDE", hide, 1);
        else
            unsetenv("MESA_EXTENSION_OVERRIDE");
        static result r;
        tr_ctx c;
        if (tr_open(&c, &cu_display_egl, W, H, 0) || tr_render(&c, scene, sets)) {
            fprintf(stderr, "child: %s\n", c.err);
            _exit(1);
        }
        r.float_rt = c.r->ctx.float_rt;
        r.half_rt = c.r->ctx.half_rt;
        r.shadow = c.r->ctx.shadow;
        r.ms_mode = c.r->ctx.ms_mode;
        r.rgba8 = c.r->ctx.hdr_format == GL_RGBA8;
        tr_read_rgba8(&c, r.px);
        tr_close(&c);
        _exit(write(p[1], &r, sizeof r) == (ssize_t)sizeof r ? 0 : 1);
    }
    close(p[1]);
    int rc = read_all(p[0], out, sizeof *out);
    close(p[0]);
    int st;
    waitpid(pid, &st, 0);
    assert_int_equal(rc, 0);
    assert_true(WIFEXITED(st) && WEXITSTATUS(st) == 0);
}

/* Neither float nor half-float targets: both fallbacks, no cloud shadows and the RGBA8 target. Against a full context
 * rendering the fallbacks' settings: alike except where the RGBA8 target clips (the sky around the sun, whose colour shifts where
 * one channel clips before the others). Measured (2026-11-22): PSNR 36.5 dB, max 15/255, 29 % of pixels off by more
 * than 6/255. Before the fix (out_scale in renderer.c) the RGBA8 picture was one flat grey: about 10 dB. */
static void test_no_float_targets(void **st)
{
    (void)st;
    static result got, ref;
    render_child("-GL_EXT_color_buffer_float -GL_EXT_color_buffer_half_float", "scenes/cumulus.scene", NULL, &got);
    assert_int_equal(got.float_rt, 0);
    assert_int_equal(got.half_rt, 0);
    assert_int_equal(got.rgba8, 1);
    assert_int_equal(got.shadow, CU_SHADOW_FRONT);
    assert_int_equal(got.ms_mode, CU_MS_OCTAVES);
    const char *sets[] = {"light.shadow=front", "ms.mode=octaves", "quality.cloud_shadows=off", NULL};
    render_child(NULL, "scenes/cumulus.scene", sets, &ref);
    assert_int_equal(ref.rgba8, 0);
    tr_diff d = tr_compare_rgba8(got.px, ref.px, W, H, 6);
    printf("no float targets: PSNR %.1f dB, %.1f %% of pixels off by more than 6, max %d\n", d.psnr,
           100 * d.frac_over, d.max_diff);
    if (d.psnr < 33 || d.max_diff > 24)
        tr_save_failure("fallback-rgba8", got.px, ref.px, W, H);
    assert_true(d.psnr >= 33);
    assert_true(d.max_diff <= 24);
}

/* quality.edge_refine's target marks the pixels it leaves alone with an alpha of 2, which RGBA8 clamps to 1 (they
 * would turn black): without half-float targets it is off, and the frame is low's without it, pixel for pixel. */
static void test_no_float_targets_edge_refine(void **st)
{
    (void)st;
    static result got, ref;
    const char *hide = "-GL_EXT_color_buffer_float -GL_EXT_color_buffer_half_float";
    const char *refine[] = {"quality.preset=low", "quality.edge_refine=0.3", NULL};
    const char *plain[] = {"quality.preset=low", NULL};
    render_child(hide, "scenes/sweep_silver_lining_hg.scene", refine, &got);
    render_child(hide, "scenes/sweep_silver_lining_hg.scene", plain, &ref);
    assert_int_equal(got.rgba8, 1);
    tr_diff d = tr_compare_rgba8(got.px, ref.px, W, H, 0);
    printf("no float targets, edge_refine 0.3: max %d/255 from low without it\n", d.max_diff);
    if (d.max_diff > 0)
        tr_save_failure("fallback-edge-refine", got.px, ref.px, W, H);
    assert_int_equal(d.max_diff, 0);
}

/* Half-float but no float targets: the opacity map falls back to the front depth; the slab model stays (its maps
 * are RGBA16F). Against a full context with light.shadow=front: the same picture. */
static void test_half_float_only(void **st)
{
    (void)st;
    static result got, ref;
    render_child("-GL_EXT_color_buffer_float", "scenes/cumulus.scene", NULL, &got);
    assert_int_equal(got.float_rt, 0);
    assert_int_equal(got.half_rt, 1);
    assert_int_equal(got.rgba8, 0);
    assert_int_equal(got.shadow, CU_SHADOW_FRONT);
    assert_int_equal(got.ms_mode, CU_MS_SLAB);
    const char *sets[] = {"light.shadow=front", NULL};
    render_child(NULL, "scenes/cumulus.scene", sets, &ref);
    tr_diff d = tr_compare_rgba8(got.px, ref.px, W, H, 2);
    printf("half-float only: PSNR %.1f dB, max %d\n", d.psnr, d.max_diff);
    if (d.max_diff > 2)
        tr_save_failure("fallback-half", got.px, ref.px, W, H);
    assert_true(d.max_diff <= 2);
}

/* A target larger than the GPU allows fails before anything is allocated, naming the size and the limits, instead
 * of as an incomplete framebuffer (status 0x8cd6) that does not say why. */
static void test_target_over_limit(void **st)
{
    (void)st;
    tr_ctx c;
    if (tr_open(&c, &cu_display_egl, 8, 8, 0))
        fail_msg("%s", c.err);
    const cu_gl *gl = &c.r->gl;
    GLint tex = 0, rb = 0, vp[2] = {0, 0};
    gl->GetIntegerv(GL_MAX_TEXTURE_SIZE, &tex);
    gl->GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &rb);
    gl->GetIntegerv(GL_MAX_VIEWPORT_DIMS, vp);
    int lim = tex < rb ? tex : rb;
    lim = lim < vp[0] ? lim : vp[0];
    cu_target t;
    cu_error e;
    cu_target_desc ok = {"small", 8, 8, GL_RGBA8, 1, 0, 1};
    assert_int_equal(cu_target_create(&t, gl, &ok, &e), 0);
    cu_target_delete(&t, gl);
    cu_target_desc big = {"HDR target", lim + 1, 1, GL_RGBA8, 1, 0, 1};
    assert_int_not_equal(cu_target_create(&t, gl, &big, &e), 0);
    char want[300];
    snprintf(want, sizeof want, "HDR target: framebuffer %dx1 exceeds this GPU's limit (GL_MAX_TEXTURE_SIZE %d, "
             "GL_MAX_RENDERBUFFER_SIZE %d, GL_MAX_VIEWPORT_DIMS %dx%d)", lim + 1, tex, rb, vp[0], vp[1]);
    assert_string_equal(e.msg, want);
    assert_int_equal(gl->GetError(), GL_NO_ERROR);
    tr_close(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_no_float_targets),
        cmocka_unit_test(test_no_float_targets_edge_refine),
        cmocka_unit_test(test_half_float_only),
        cmocka_unit_test(test_target_over_limit),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
