/* src/gpu/pass_shadow.c: the shadow pass (see pass_shadow.h). */
#include "pass_shadow.h"
#include "error.h"
#include <stdio.h>
#include <string.h>

int cu_pass_shadow_create(cu_pass_shadow *p, const cu_gpu_scene *ctx, const char *fs_defs, cu_error *err)
{
    const cu_gl *gl = ctx->gl;
    memset(p, 0, sizeof *p);
    /* The scene's defines with the noise switched off: a shadow cast hundreds of metres blurs the boundary's noise
     * away, and a noise-free integral is several times cheaper. */
    char defs[2048];
    snprintf(defs, sizeof defs, "%s", fs_defs);
    char *n = strstr(defs, "#define NOISE ");
    if (n && (n[14] == '0' || n[14] == '1'))
        n[14] = '0';
    if (!(p->prog = cu_gl_program(gl, "fullscreen.vert", "sun_shadow.frag", defs, err)))
        return 1;
    cu_density_locs_get(gl, p->prog, &p->density);
#define LOC(f) p->f = cu_gpu_loc(gl, p->prog, "u_" #f)
    LOC(origin); LOC(ax); LOC(ay); LOC(dir); LOC(size);
#undef LOC
    const float zero[4] = {0, 0, 0, 0};
    gl->GenTextures(1, &p->zero_tex);
    gl->BindTexture(GL_TEXTURE_2D, p->zero_tex);
    gl->TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, 1, 1, 0, GL_RGBA, GL_FLOAT, zero);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return 0;
}

void cu_pass_shadow_destroy(cu_pass_shadow *p, const cu_gl *gl)
{
    if (p->prog)
        gl->DeleteProgram(p->prog);
    if (p->zero_tex)
        gl->DeleteTextures(1, &p->zero_tex);
    memset(p, 0, sizeof *p);
}

int cu_pass_shadow_target(const cu_gl *gl, int size, cu_target *t, cu_error *err)
{
    cu_target_desc d = {.name = "shadow map", .width = size, .height = size, .format = GL_RGBA16F, .colors = 1};
    if (cu_target_create(t, gl, &d, err))
        return 1;
    gl->BindTexture(GL_TEXTURE_2D, t->tex[0]); /* read bilinearly: a soft, smooth shadow (fp16 filters in GLES 3.0) */
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return 0;
}

void cu_pass_shadow_begin(const cu_pass_shadow *p, const cu_gpu_scene *ctx, const cu_target *t, int size,
                          const int reg[4])
{
    const cu_gl *gl = ctx->gl;
    gl->BindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    gl->Viewport(0, 0, size, size);
    gl->Disable(GL_DEPTH_TEST);
    gl->Enable(GL_SCISSOR_TEST);
    gl->Scissor(reg[0], reg[1], reg[2] - reg[0], reg[3] - reg[1]);
    gl->ClearColor(0, 0, 0, 0);
    gl->Clear(GL_COLOR_BUFFER_BIT);
    gl->Enable(GL_BLEND);
    gl->BlendFunc(GL_ONE, GL_ONE); /* optical depths of the casters add up */
    gl->UseProgram(p->prog);
    gl->Uniform2f(p->size, (float)size, (float)size);
    gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_NOISE);
    gl->BindTexture(GL_TEXTURE_3D, ctx->noise_tex);
    gl->BindVertexArray(ctx->empty_vao);
}

void cu_pass_shadow_add(const cu_pass_shadow *p, const cu_gpu_scene *ctx, const cu_cloud *caster, double ke,
                        vec3 origin, vec3 ax, vec3 ay, int size, const int rect[4])
{
    const cu_gl *gl = ctx->gl;
    (void)size;
    if (rect[2] <= rect[0] || rect[3] <= rect[1] || !(ke > 0))
        return;
    cu_gpu_scene c = *ctx; /* the density uniforms of the caster, at its density now */
    c.cloud = caster;
    c.ke_scale = ke / (caster->ke > 0 ? caster->ke : 1.0);
    cu_density_uniforms(&c, &p->density);
    gl->Uniform3f(p->origin, (float)origin.x, (float)origin.y, (float)origin.z);
    gl->Uniform3f(p->ax, (float)ax.x, (float)ax.y, (float)ax.z);
    gl->Uniform3f(p->ay, (float)ay.x, (float)ay.y, (float)ay.z);
    gl->Uniform3f(p->dir, (float)-ctx->sun_dir.x, (float)-ctx->sun_dir.y, (float)-ctx->sun_dir.z);
    gl->Scissor(rect[0], rect[1], rect[2] - rect[0], rect[3] - rect[1]);
    gl->DrawArrays(GL_TRIANGLES, 0, 3);
}

void cu_pass_shadow_end(const cu_gpu_scene *ctx)
{
    const cu_gl *gl = ctx->gl;
    gl->Disable(GL_SCISSOR_TEST);
    gl->Disable(GL_BLEND);
    gl->BindVertexArray(0);
}
