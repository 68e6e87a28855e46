/* src/gpu/pass_sky.c: the sky pass (see pass_sky.h). */
#include "pass_sky.h"
#include "error.h"
#include <stdio.h>
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

int cu_pass_sky_create(cu_pass_sky *p, const cu_gpu_scene *ctx, const char *defines, cu_error *err)
{
    const cu_gl *gl = ctx->gl;
    memset(p, 0, sizeof *p);
    char defs[2048], out_defs[2048], over_defs[2048];
    if (snprintf(defs, sizeof defs, "%s#define SKY_TABLE %d\n", defines, CU_SKY_TABLE) >= (int)sizeof defs ||
        snprintf(out_defs, sizeof out_defs, "%s#define SKY_TONEMAP 1\n", defs) >= (int)sizeof out_defs ||
        snprintf(over_defs, sizeof over_defs, "%s#define SKY_COMPOSITE 1\n", out_defs) >= (int)sizeof over_defs)
        return cu_fail(err, "sky: shader defines too long");
    if (!(p->prog = cu_gl_program(gl, "sky.vert", "sky.frag", defs, err)) ||
        !(p->prog_out = cu_gl_program(gl, "sky.vert", "sky.frag", out_defs, err)) ||
        !(p->prog_over = cu_gl_program(gl, "sky.vert", "sky.frag", over_defs, err)))
        return 1;
    locs_get(gl, p->prog, &p->hdr);
    locs_get(gl, p->prog_out, &p->out);
    locs_get(gl, p->prog_over, &p->over);
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
    if (p->prog)
        gl->DeleteProgram(p->prog);
    if (p->prog_out)
        gl->DeleteProgram(p->prog_out);
    if (p->prog_over)
        gl->DeleteProgram(p->prog_over);
    if (p->tables)
        gl->DeleteTextures(1, &p->tables);
    p->prog = p->prog_out = p->prog_over = p->tables = 0;
    p->tables_built = 0;
}

static void draw(cu_pass_sky *pass, const cu_gpu_scene *ctx, GLuint prog, const cu_sky_locs *p)
{
    const cu_gl *gl = ctx->gl;
    const cu_sky *sky = ctx->sky;
    const cu_scene *s = ctx->scene;
    gl->Disable(GL_DEPTH_TEST);
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
    gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_SHADOW);
    gl->BindTexture(GL_TEXTURE_2D, ctx->ground_tau[0]);
    gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_GROUND2);
    gl->BindTexture(GL_TEXTURE_2D, ctx->ground_tau[1]);
    gl->ActiveTexture(GL_TEXTURE0);
    float os[3];
    cu_out_scale(ctx, os);
    gl->Uniform3f(p->out_scale, os[0], os[1], os[2]);
    if (s->sky_model == CU_SKY_CONSTANT) {
        gl->Uniform3f(p->sky_color, (float)s->sky_color[0], (float)s->sky_color[1], (float)s->sky_color[2]);
    } else {
        tables_update(pass, gl, sky);
        gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_SKY);
        gl->BindTexture(GL_TEXTURE_2D, pass->tables);
        gl->ActiveTexture(GL_TEXTURE0);
    }
    gl->BindVertexArray(ctx->empty_vao);
    gl->DrawArrays(GL_TRIANGLES, 0, 3);
}

void cu_pass_sky_draw(cu_pass_sky *pass, const cu_gpu_scene *ctx, int to_output)
{
    draw(pass, ctx, to_output ? pass->prog_out : pass->prog, to_output ? &pass->out : &pass->hdr);
}

void cu_pass_sky_draw_over(cu_pass_sky *pass, const cu_gpu_scene *ctx, GLuint clouds, int factor)
{
    const cu_gl *gl = ctx->gl;
    gl->UseProgram(pass->prog_over);
    gl->Uniform1f(pass->over.cloud_factor, (float)factor);
    gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_CLOUDS);
    gl->BindTexture(GL_TEXTURE_2D, clouds);
    gl->ActiveTexture(GL_TEXTURE0);
    draw(pass, ctx, pass->prog_over, &pass->over);
}
