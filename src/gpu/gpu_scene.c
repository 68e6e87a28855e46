/* src/gpu/gpu_scene.c: the frame context's helpers: logging, the sun's frame, and the uniforms every pass shares
 * (density.glsl, the sun's frame), each set in one place from cached locations. */
#include "gpu_scene.h"
#include "sunmap.h"
#include <stdarg.h>
#include <stdio.h>

void cu_gpu_log(const cu_gpu_scene *ctx, cu_log_level level, const char *fmt, ...)
{
    if (!ctx->log)
        return;
    char buf[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    ctx->log(ctx->log_user, level, buf);
}

void cu_gpu_scene_set_sun(cu_gpu_scene *ctx)
{
    ctx->sun_dir = ctx->sky->sun_dir;
    cu_sun_basis(ctx->sun_dir, &ctx->sun_right, &ctx->sun_up);
    ctx->sun_R = cu_sun_radius(ctx->cloud);
}

GLint cu_gpu_loc(const cu_gl *gl, GLuint p, const char *name)
{
    return gl->GetUniformLocation(p, name);
}

void cu_gpu_unit(const cu_gl *gl, GLuint p, const char *name, int unit)
{
    GLint l = gl->GetUniformLocation(p, name);
    if (l >= 0) {
        gl->UseProgram(p);
        gl->Uniform1i(l, unit);
    }
}

void cu_density_locs_get(const cu_gl *gl, GLuint p, cu_density_locs *l)
{
#define LOC(f) l->f = cu_gpu_loc(gl, p, "u_" #f)
    LOC(ell_c); LOC(ell_ir); LOC(ke); LOC(h); LOC(noise_freq); LOC(noise_offset); LOC(noise_mean);
#undef LOC
    cu_gpu_unit(gl, p, "u_noise", CU_UNIT_NOISE);
}

void cu_density_uniforms(const cu_gpu_scene *ctx, const cu_density_locs *l)
{
    const cu_gl *gl = ctx->gl;
    const cu_cloud *cl = ctx->cloud;
    float c[CU_MAX_ELLIPSOIDS * 4], ir[CU_MAX_ELLIPSOIDS * 4];
    for (int i = 0; i < cl->n; i++) {
        c[4 * i] = (float)cl->c[i].x;
        c[4 * i + 1] = (float)cl->c[i].y;
        c[4 * i + 2] = (float)cl->c[i].z;
        c[4 * i + 3] = 0;
        ir[4 * i] = (float)(1.0 / cl->r[i].x);
        ir[4 * i + 1] = (float)(1.0 / cl->r[i].y);
        ir[4 * i + 2] = (float)(1.0 / cl->r[i].z);
        ir[4 * i + 3] = 0;
    }
    /* The program is built for the scene's largest cloud (NUM_ELL); a smaller one fills the rest with an ellipsoid
     * of 1 m far below every ray's reach (cast_ray finds no chord through it). */
    int n = ctx->num_ell > cl->n ? ctx->num_ell : cl->n;
    for (int i = cl->n; i < n && i < CU_MAX_ELLIPSOIDS; i++) {
        c[4 * i] = 0;
        c[4 * i + 1] = -1e7f;
        c[4 * i + 2] = 0;
        c[4 * i + 3] = 0;
        ir[4 * i] = ir[4 * i + 1] = ir[4 * i + 2] = 1;
        ir[4 * i + 3] = 0;
    }
    gl->Uniform4fv(l->ell_c, n, c);
    gl->Uniform4fv(l->ell_ir, n, ir);
    gl->Uniform1f(l->ke, (float)(cl->ke * ctx->ke_scale));
    gl->Uniform1f(l->h, (float)(cl->h > 1e-6 ? cl->h : 1e-6));
    gl->Uniform1f(l->noise_freq, (float)cl->noise_freq);
    gl->Uniform3f(l->noise_offset, (float)cl->noise_offset.x, (float)cl->noise_offset.y, (float)cl->noise_offset.z);
    float means[5];
    for (int i = 0; i < 5; i++)
        means[i] = (float)ctx->noise->level_mean[i];
    gl->Uniform1fv(l->noise_mean, 5, means);
}

double cu_shadow_g(const cu_gpu_scene *ctx)
{
    /* No g in the Mie table's header: the [cloud] g key's default is the table's value (phase.c) for 6 um. */
    double g = ctx->scene->phase_g;
    return g > 0.99 ? 0.99 : g < 0 ? 0 : g;
}

void cu_sun_locs_get(const cu_gl *gl, GLuint p, cu_sun_locs *l)
{
#define LOC(f) l->f = cu_gpu_loc(gl, p, "u_sun_" #f)
    LOC(dir); LOC(right); LOC(up); LOC(R); LOC(size); LOC(intervals); LOC(tau_scale);
#undef LOC
    cu_gpu_unit(gl, p, "u_sun_layers", CU_UNIT_SUN_MAP);
    cu_gpu_unit(gl, p, "u_sun_tau", CU_UNIT_SUN_TAU);
    cu_gpu_unit(gl, p, "u_sun_depth", CU_UNIT_SUN_MAP);
    cu_gpu_unit(gl, p, "u_sun_map", CU_UNIT_SUN_MAP);
}

void cu_sun_uniforms(const cu_gpu_scene *ctx, const cu_sun_locs *l)
{
    const cu_gl *gl = ctx->gl;
    vec3 d = ctx->sun_dir, r = ctx->sun_right, u = ctx->sun_up;
    gl->Uniform3f(l->dir, (float)d.x, (float)d.y, (float)d.z);
    gl->Uniform3f(l->right, (float)r.x, (float)r.y, (float)r.z);
    gl->Uniform3f(l->up, (float)u.x, (float)u.y, (float)u.z);
    gl->Uniform1f(l->R, (float)ctx->sun_R);
    gl->Uniform1i(l->size, ctx->sun_size);
    gl->Uniform1i(l->intervals, ctx->sun.intervals);
    gl->Uniform1f(l->tau_scale, (float)ctx->ke_scale);
}

/* The tone-mapped frame's HDR target (RGBA16F, or RGBA8 on GLES 3.0 without EXT_color_buffer_*float) stores
 * exposed, white-balanced values and the tone mapper gets 1 and 1: RGBA8 holds only 0..1 (storing radiance would
 * clip the whole sky to 1; this way highlights beyond the display's white clip, the rest is as with a float
 * target), and fp16's 65504 would overflow on legal bright scenes. Linear output (RGBA32F) stores radiance. */
void cu_out_scale(const cu_gpu_scene *ctx, float s[3])
{
    for (int c = 0; c < 3; c++)
        s[c] = ctx->hdr_format != GL_RGBA32F ? (float)(ctx->scene->exposure / ctx->white[c]) : 1.0f;
}

/* The largest value a pass may store: with fp16 two passes' sum (sky + premultiplied cloud) must stay below
 * 65504, or the target holds Inf and the tone curve makes it NaN (Inf / Inf). Exposed values past 7.3 are white
 * already, so the cap changes no pixel. RGBA8 clamps by itself; RGBA32F holds every legal scene (scene_keys.c). */
float cu_out_max(const cu_gpu_scene *ctx)
{
    return ctx->hdr_format == GL_RGBA16F ? 30000.0f : ctx->hdr_format == GL_RGBA8 ? 1.0f : 3.0e38f;
}
