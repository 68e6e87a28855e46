/* tests/gpu/render_util.c: headless rendering and image comparison helpers for the tests (see render_util.h). */
#include "render_util.h"
#include "image.h"
#include "scene.h"
#include <GLES3/gl3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int tr_open(tr_ctx *c, const cu_display_backend *be, int w, int h, int linear)
{
    memset(c, 0, sizeof *c);
    c->w = w;
    c->h = h;
    c->linear = linear;
    /* The same opening as every cumulo subcommand (app/session.c); tables as the program finds them. */
    cu_display_opts o = {0};
    o.width = w;
    o.height = h;
    o.float_target = linear;
    if (cli_session_attach(&c->s, be, &o, getenv("CUMULO_DATA_DIR"), 0, c->err, sizeof c->err))
        return 1;
    c->be = c->s.be;
    c->disp = c->s.disp;
    c->r = c->s.r;
    return 0;
}

int tr_render_scene(tr_ctx *c, const cu_scene *s)
{
    cu_error e;
    if (cu_renderer_set_scene(c->r, s, &e)) {
        snprintf(c->err, sizeof c->err, "%s", e.msg);
        return 1;
    }
    return tr_render_again(c);
}

int tr_render_again(tr_ctx *c)
{
    cu_error e;
    unsigned fbo;
    int w, h;
    c->be->frame(c->disp, &fbo, &w, &h);
    cu_frame f = {.fbo = fbo, .width = w, .height = h, .linear = c->linear};
    if (cu_render(c->r, &f, &e)) {
        snprintf(c->err, sizeof c->err, "%s", e.msg);
        return 1;
    }
    return 0;
}

int tr_render_from(tr_ctx *c, const char *scene, const char *pos, const char *look)
{
    cu_scene *s;
    cu_error e;
    char p[128], l[128];
    snprintf(p, sizeof p, "camera.position=%s", pos);
    snprintf(l, sizeof l, "camera.look_at=%s", look);
    float view[16], proj[16];
    int rc = cu_scene_load(&s, scene, &e);
    if (!rc) {
        rc = cu_scene_set(s, p, &e) || cu_scene_set(s, l, &e) ||
             cu_scene_camera_matrices(s, (double)c->w / c->h, 1.0, 2.0, view, proj, &e);
        cu_scene_free(s);
    }
    if (rc) {
        snprintf(c->err, sizeof c->err, "%s", e.msg);
        return 1;
    }
    unsigned fbo;
    int w, h;
    c->be->frame(c->disp, &fbo, &w, &h);
    cu_frame f = {.fbo = fbo, .width = w, .height = h, .linear = c->linear, .view = view, .projection = proj};
    if (cu_render(c->r, &f, &e)) {
        snprintf(c->err, sizeof c->err, "%s", e.msg);
        return 1;
    }
    return 0;
}

int tr_render(tr_ctx *c, const char *scene, const char *const *sets)
{
    cu_scene *s;
    cu_error e;
    int rc = scene[0] == '[' ? cu_scene_parse(&s, "inline.scene", scene, strlen(scene), &e)
                             : cu_scene_load(&s, scene, &e);
    if (rc) {
        snprintf(c->err, sizeof c->err, "%s", e.msg);
        return 1;
    }
    for (int i = 0; sets && sets[i]; i++)
        if (cu_scene_set(s, sets[i], &e)) {
            snprintf(c->err, sizeof c->err, "%s", e.msg);
            cu_scene_free(s);
            return 1;
        }
    rc = tr_render_scene(c, s);
    cu_scene_free(s);
    return rc;
}

double tr_rel_diff(const float *a, const float *b, size_t n)
{
    double d = 0, top = 0;
    for (size_t i = 0; i < n; i++) {
        d = fmax(d, fabs(a[i] - b[i]));
        top = fmax(top, b[i]);
    }
    return d / top;
}

int tr_read_rgbf(tr_ctx *c, float *rgb)
{
    return cli_session_read_rgbf(&c->s, rgb);
}

int tr_read_rgba8(tr_ctx *c, uint8_t *rgba)
{
    return cli_session_read_rgba8(&c->s, rgba);
}

void tr_close(tr_ctx *c)
{
    cli_session_close(&c->s);
    memset(c, 0, sizeof *c);
}

tr_diff tr_compare_rgba8(const uint8_t *a, const uint8_t *b, int w, int h, int threshold)
{
    tr_diff d = {0, 0, 0};
    double se = 0;
    long over = 0;
    for (long i = 0; i < (long)w * h; i++) {
        int worst = 0;
        for (int k = 0; k < 3; k++) {
            int e = abs((int)a[4 * i + k] - (int)b[4 * i + k]);
            se += (double)e * e;
            if (e > worst)
                worst = e;
        }
        if (worst > d.max_diff)
            d.max_diff = worst;
        if (worst > threshold)
            over++;
    }
    d.frac_over = (double)over / ((double)w * h);
    double mse = se / (3.0 * w * h);
    d.psnr = mse > 0 ? 10 * log10(255.0 * 255.0 / mse) : 99.0;
    return d;
}

void tr_save_failure(const char *name, const uint8_t *got, const uint8_t *ref, int w, int h)
{
    mkdir("build", 0755);
    mkdir("build/test-output", 0755);
    char path[512];
    cu_error err;
    uint8_t *diff = malloc(4 * (size_t)w * h);
    for (long i = 0; i < (long)w * h; i++) {
        for (int k = 0; k < 3; k++) {
            int e = abs((int)got[4 * i + k] - (int)ref[4 * i + k]) * 8;
            diff[4 * i + k] = (uint8_t)(e > 255 ? 255 : e);
        }
        diff[4 * i + 3] = 255;
    }
    const char *kinds[3] = {"result", "reference", "diff-x8"};
    const uint8_t *imgs[3] = {got, ref, diff};
    for (int k = 0; k < 3; k++) {
        snprintf(path, sizeof path, "build/test-output/%s-%s.png", name, kinds[k]);
        if (cu_write_png(path, imgs[k], w, h, &err))
            fprintf(stderr, "tr_save_failure: %s\n", err.msg); /* the test fails anyway; say why the picture is missing */
    }
    free(diff);
}

/* Direction through the centre of pixel (x, y) (y = 0 at the top), as the renderer's camera defines it. */
vec3 tr_pixel_dir(const cu_scene *s, int w, int h, int x, int y)
{
    vec3 dir = v3_norm(v3_sub(v3_from(s->cam_look), v3_from(s->cam_pos)));
    mat4 view = m4_look_dir(v3(0, 0, 0), dir, v3(0, 1, 0));
    mat4 proj = m4_perspective(s->cam_fov * CU_PI / 180.0, (double)w / h, 1.0, 1000.0);
    mat4 inv = m4_inverse(m4_mul(proj, view));
    double nx = (x + 0.5) / w * 2 - 1, ny = 1 - (y + 0.5) / h * 2;
    double c[4] = {nx, ny, 1, 1}, o[4] = {0, 0, 0, 0};
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 4; k++)
            o[i] += inv.m[k * 4 + i] * c[k];
    return v3_norm(v3(o[0] / o[3], o[1] / o[3], o[2] / o[3]));
}
