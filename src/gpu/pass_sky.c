/* src/gpu/pass_sky.c: the sky pass (see pass_sky.h). */
#include "pass_sky.h"
#include "error.h"
#include <stdio.h>
#include <math.h>
#include <string.h>

static void locs_get(const cu_gl *gl, GLuint prog, cu_sky_locs *l)
{
    cu_sun_locs_get(gl, prog, &l->sun);
#define LOC(f) l->f = cu_gpu_loc(gl, prog, "u_" #f)
    LOC(inv_viewproj); LOC(sun_irr); LOC(out_max); LOC(ground); LOC(out_scale); LOC(sky_color);
    LOC(ground_sun); LOC(eye); LOC(gmap); LOC(gmap2); LOC(shadow_g); LOC(cloud_factor);
#undef LOC
    cu_gpu_unit(gl, prog, "u_clouds", CU_UNIT_CLOUDS);
    cu_gpu_unit(gl, prog, "u_ground_tau", CU_UNIT_SHADOW);
    cu_gpu_unit(gl, prog, "u_ground_tau2", CU_UNIT_GROUND2);
    cu_gpu_unit(gl, prog, "u_sky_tables", CU_UNIT_SKY);
}

/* Makes the program of a kind, part and count of ground maps, once. */
static int program(cu_pass_sky *p, const cu_gl *gl, int kind, int part, int maps, cu_error *err)
{
    static const char *const kinds[CU_SKY_KINDS] = {"", "#define SKY_TONEMAP 1\n",
                                                    "#define SKY_TONEMAP 1\n#define SKY_COMPOSITE 1\n"};
    if (p->prog[kind][part][maps])
        return 0;
    char defs[2200];
    if (snprintf(defs, sizeof defs, "%s%s#define SKY_PART %d\n#define GROUND_MAPS %d\n", p->defines, kinds[kind],
                 part, maps) >= (int)sizeof defs)
        return cu_fail(err, "sky: shader defines too long");
    if (!(p->prog[kind][part][maps] = cu_gl_program(gl, "sky.vert", "sky.frag", defs, err)))
        return 1;
    locs_get(gl, p->prog[kind][part][maps], &p->loc[kind][part][maps]);
    return 0;
}

int cu_pass_sky_create(cu_pass_sky *p, const cu_gpu_scene *ctx, const char *defines, cu_error *err)
{
    const cu_gl *gl = ctx->gl;
    memset(p, 0, sizeof *p);
    if (snprintf(p->defines, sizeof p->defines, "%s#define SKY_TABLE %d\n", defines, CU_SKY_TABLE) >=
        (int)sizeof p->defines)
        return cu_fail(err, "sky: shader defines too long");
    for (int kind = 0; kind < CU_SKY_KINDS; kind++)
        if (program(p, gl, kind, CU_SKY_BOTH, 0, err))
            return 1;
    gl->GenTextures(1, &p->tables);
    gl->BindTexture(GL_TEXTURE_2D, p->tables);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return 0;
}

/* The Perez tables for this sky, rebuilt only when its coefficients changed (the sun moved, the turbidity changed):
 * 2 x 256 entries on the CPU and an 8 KiB upload. RGBA32F, read with texelFetch and interpolated in sky.frag. */
static void tables_update(cu_pass_sky *p, const cu_gl *gl, const cu_sky *sky)
{
    double of[21];
    memcpy(of, sky->perez, sizeof sky->perez);
    memcpy(of + 15, sky->zenith, sizeof sky->zenith);
    memcpy(of + 18, sky->norm, sizeof sky->norm);
    if (p->tables_built && !memcmp(of, p->tables_of, sizeof of))
        return;
    float t[2 * 4 * CU_SKY_TABLE];
    cu_sky_tables(sky, t, t + 4 * CU_SKY_TABLE);
    gl->BindTexture(GL_TEXTURE_2D, p->tables);
    gl->TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, CU_SKY_TABLE, 2, 0, GL_RGBA, GL_FLOAT, t);
    memcpy(p->tables_of, of, sizeof of);
    p->tables_built = 1;
}

void cu_pass_sky_destroy(cu_pass_sky *p, const cu_gl *gl)
{
    for (int kind = 0; kind < CU_SKY_KINDS; kind++)
        for (int part = 0; part < CU_SKY_PARTS; part++)
            for (int maps = 0; maps <= CU_GROUND_MAPS; maps++)
                if (p->prog[kind][part][maps])
                    gl->DeleteProgram(p->prog[kind][part][maps]);
    if (p->tables)
        gl->DeleteTextures(1, &p->tables);
    memset(p, 0, sizeof *p);
}

static void uniforms(cu_pass_sky *pass, const cu_gpu_scene *ctx, GLuint prog, const cu_sky_locs *p, int factor)
{
    const cu_gl *gl = ctx->gl;
    const cu_sky *sky = ctx->sky;
    const cu_scene *s = ctx->scene;
    gl->UseProgram(prog);
    gl->UniformMatrix4fv(p->inv_viewproj, 1, GL_FALSE, ctx->camera.inv_rot);
    cu_sun_uniforms(ctx, &p->sun);
    gl->Uniform3f(p->sun_irr, (float)sky->sun_irradiance[0], (float)sky->sun_irradiance[1],
                  (float)sky->sun_irradiance[2]);
    gl->Uniform1f(p->out_max, cu_out_max(ctx)); /* the disk capped below what the target holds */
    gl->Uniform3f(p->ground, (float)sky->ground[0], (float)sky->ground[1], (float)sky->ground[2]);
    gl->Uniform3f(p->ground_sun, (float)sky->ground_sun[0], (float)sky->ground_sun[1], (float)sky->ground_sun[2]);
    gl->Uniform3f(p->eye, (float)ctx->camera.pos.x, (float)ctx->camera.pos.y, (float)ctx->camera.pos.z);
    gl->Uniform3f(p->gmap, (float)ctx->ground_map[0].x, (float)ctx->ground_map[0].y, (float)ctx->ground_map[0].z);
    gl->Uniform3f(p->gmap2, (float)ctx->ground_map[1].x, (float)ctx->ground_map[1].y, (float)ctx->ground_map[1].z);
    gl->Uniform1f(p->shadow_g, (float)cu_shadow_g(ctx));
    gl->Uniform1f(p->cloud_factor, (float)factor); /* -1 (no composite): ignored */
    float os[3];
    cu_out_scale(ctx, os);
    gl->Uniform3f(p->out_scale, os[0], os[1], os[2]);
    if (s->sky_model == CU_SKY_CONSTANT)
        gl->Uniform3f(p->sky_color, (float)s->sky_color[0], (float)s->sky_color[1], (float)s->sky_color[2]);
    else
        tables_update(pass, gl, sky);
}

/* The height of the view direction at the viewport's NDC (x, y), over its length, through the sky's matrix as
 * sky.vert and sky.frag make it (column-major, clip -> direction). Affine in the screen up to a positive factor
 * (sign(d.y) is that of the far point's y), so over a rectangle its sign is settled at the corners. */
static double height_at(const float *m, double x, double y)
{
    double n[4], f[4];
    for (int r = 0; r < 4; r++) {
        n[r] = m[r] * x + m[4 + r] * y - m[8 + r] + m[12 + r];
        f[r] = m[r] * x + m[4 + r] * y + m[8 + r] + m[12 + r];
    }
    double d[3] = {f[0] / f[3] - n[0] / n[3], f[1] / f[3] - n[1] / n[3], f[2] / f[3] - n[2] / n[3]};
    return d[1] / sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

/* What the rows between NDC y0 and y1 hold: sky alone, ground alone, or both. A margin far above fp32's rounding of
 * the direction in the shader keeps the rows near the horizon with the branch; NaN (a degenerate camera) too. */
static int rows_part(const float *m, double y0, double y1)
{
    const double margin = 1e-4;
    double h[4] = {height_at(m, -1, y0), height_at(m, 1, y0), height_at(m, -1, y1), height_at(m, 1, y1)};
    int above = 1, below = 1;
    for (int k = 0; k < 4; k++) {
        above = above && h[k] > margin;
        below = below && h[k] < -margin;
    }
    return above ? CU_SKY_ABOVE : below ? CU_SKY_BELOW : CU_SKY_BOTH;
}

/* Rows row .. end - 1, columns x0 .. x1 - 1 with the program of kind k, part and maps. */
static int piece(cu_pass_sky *pass, const cu_gpu_scene *ctx, int k, int part, int maps, int factor, const int box[4],
                 cu_error *err)
{
    const cu_gl *gl = ctx->gl;
    if (box[2] <= box[0] || box[3] <= box[1])
        return 0;
    if (program(pass, gl, k, part, maps, err))
        return 1;
    uniforms(pass, ctx, pass->prog[k][part][maps], &pass->loc[k][part][maps], factor);
    gl->Scissor(box[0], box[1], box[2] - box[0], box[3] - box[1]);
    gl->DrawArrays(GL_TRIANGLES, 0, 3);
    return 0;
}

/* The full-screen triangle, a run of rows at a time with the program of what they hold: sky rows without the
 * ground's shadow maps, ground rows without the Perez tables (a constant sky has no branch), reading only the maps
 * that hold shadows; with kind CU_SKY_OVER, outside rect (x0, y0, x1, y1: pixels, half-open) without the cloud
 * image (CU_SKY_OUT: the same colours where the image is empty). */
static int draw(cu_pass_sky *pass, const cu_gpu_scene *ctx, int kind, int factor, const int rect[4], cu_error *err)
{
    const cu_gl *gl = ctx->gl;
    gl->Disable(GL_DEPTH_TEST);
    gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_SHADOW);
    gl->BindTexture(GL_TEXTURE_2D, ctx->ground_tau[0]);
    gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_GROUND2);
    gl->BindTexture(GL_TEXTURE_2D, ctx->ground_tau[1]);
    gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_SKY);
    gl->BindTexture(GL_TEXTURE_2D, pass->tables);
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindVertexArray(ctx->empty_vao);
    int w = ctx->width, h = ctx->height > 0 ? ctx->height : 1, split = ctx->scene->sky_model != CU_SKY_CONSTANT;
    int maps = ctx->ground_maps >= 0 && ctx->ground_maps <= CU_GROUND_MAPS ? ctx->ground_maps : CU_GROUND_MAPS;
    int x0 = rect[0] < 0 ? 0 : rect[0] > w ? w : rect[0], x1 = rect[2] < x0 ? x0 : rect[2] > w ? w : rect[2];
    const float *m = ctx->camera.inv_rot;
    int rc = 0, part = split ? rows_part(m, -1.0, -1.0 + 2.0 / h) : CU_SKY_BOTH;
    gl->Enable(GL_SCISSOR_TEST);
    for (int row = 0; row < h && !rc;) {
        /* a run: rows holding the same part, all on the same side of the cloud image's rows */
        int in = row >= rect[1] && row < rect[3], end = row + 1, next = part;
        while (end < h) {
            next = split ? rows_part(m, -1.0 + 2.0 * end / h, -1.0 + 2.0 * (end + 1) / h) : CU_SKY_BOTH;
            if (next != part || (end >= rect[1] && end < rect[3]) != in)
                break;
            end++;
        }
        if (kind == CU_SKY_OVER && in) { /* the image's columns with it, the others without */
            const int left[4] = {0, row, x0, end}, mid[4] = {x0, row, x1, end}, right[4] = {x1, row, w, end};
            rc = piece(pass, ctx, CU_SKY_OUT, part, maps, factor, left, err) ||
                 piece(pass, ctx, CU_SKY_OVER, part, maps, factor, mid, err) ||
                 piece(pass, ctx, CU_SKY_OUT, part, maps, factor, right, err);
        } else {
            const int all[4] = {0, row, w, end};
            rc = piece(pass, ctx, kind == CU_SKY_OVER ? CU_SKY_OUT : kind, part, maps, factor, all, err);
        }
        row = end;
        part = next;
    }
    gl->Disable(GL_SCISSOR_TEST);
    return rc;
}

int cu_pass_sky_draw(cu_pass_sky *pass, const cu_gpu_scene *ctx, int to_output, cu_error *err)
{
    static const int everywhere[4] = {0, 0, 1 << 30, 1 << 30};
    return draw(pass, ctx, to_output ? CU_SKY_OUT : CU_SKY_HDR, 1, everywhere, err);
}

int cu_pass_sky_draw_over(cu_pass_sky *pass, const cu_gpu_scene *ctx, GLuint clouds, int factor, const int rect[4],
                          cu_error *err)
{
    const cu_gl *gl = ctx->gl;
    gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_CLOUDS);
    gl->BindTexture(GL_TEXTURE_2D, clouds);
    gl->ActiveTexture(GL_TEXTURE0);
    return draw(pass, ctx, CU_SKY_OVER, factor, rect, err);
}
