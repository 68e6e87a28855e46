/* src/gpu/pass_upsample.c: the low-resolution cloud target and its upsampling (see pass_upsample.h). */
#include "pass_upsample.h"
#include "error.h"
#include <string.h>

int cu_pass_upsample_create(cu_pass_upsample *p, const cu_gpu_scene *ctx, cu_error *err)
{
    const cu_gl *gl = ctx->gl;
    memset(p, 0, sizeof *p);
    if (!(p->prog = cu_gl_program(gl, "fullscreen.vert", "upsample.frag", "", err)))
        return 1;
    p->factor = cu_gpu_loc(gl, p->prog, "u_factor");
    p->depth_on = cu_gpu_loc(gl, p->prog, "u_depth_on");
    p->depth_clear = cu_gpu_loc(gl, p->prog, "u_depth_clear");
    p->lin = cu_gpu_loc(gl, p->prog, "u_lin");
    p->refined_on = cu_gpu_loc(gl, p->prog, "u_refined_on");
    cu_gpu_unit(gl, p->prog, "u_low", 0);
    cu_gpu_unit(gl, p->prog, "u_depth", CU_UNIT_HOST_DEPTH);
    cu_gpu_unit(gl, p->prog, "u_refined", CU_UNIT_REFINED);
    gl->GenSamplers(1, &p->depth_sampler); /* the host's filtering and compare mode are not ours to rely on */
    gl->SamplerParameteri(p->depth_sampler, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->SamplerParameteri(p->depth_sampler, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl->SamplerParameteri(p->depth_sampler, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    return 0;
}

void cu_pass_upsample_destroy(cu_pass_upsample *p, const cu_gl *gl)
{
    if (p->prog)
        gl->DeleteProgram(p->prog);
    if (p->depth_sampler)
        gl->DeleteSamplers(1, &p->depth_sampler);
    p->prog = 0;
    p->depth_sampler = 0;
    cu_target_delete(&p->low, gl);
}

int cu_pass_upsample_begin(cu_pass_upsample *p, const cu_gpu_scene *ctx, int w, int h, int n, GLenum format,
                           cu_error *err)
{
    const cu_gl *gl = ctx->gl;
    int lw = (w + n - 1) / n, lh = (h + n - 1) / n;
    if (!p->low.fbo || p->low.width != lw || p->low.height != lh || p->low.format != format) {
        cu_target_delete(&p->low, gl);
        cu_target_desc d = {.name = "low-resolution cloud target", .width = lw, .height = lh, .format = format,
                            .colors = 1, .depth_stencil = 1};
        if (cu_target_create(&p->low, gl, &d, err))
            return 1;
    }
    gl->BindFramebuffer(GL_FRAMEBUFFER, p->low.fbo);
    gl->Viewport(0, 0, lw, lh);
    gl->ClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    gl->Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    return 0;
}

void cu_pass_upsample_draw(const cu_pass_upsample *p, const cu_gpu_scene *ctx, GLuint low, GLuint refined, GLuint hdr,
                           int w, int h, int n, const double *proj)
{
    const cu_gl *gl = ctx->gl;
    gl->BindFramebuffer(GL_FRAMEBUFFER, hdr);
    gl->Viewport(0, 0, w, h);
    gl->Disable(GL_DEPTH_TEST);
    gl->Disable(GL_STENCIL_TEST);
    gl->Enable(GL_BLEND);
    gl->BlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    gl->UseProgram(p->prog);
    gl->Uniform1i(p->factor, n);
    int depth = ctx->host_depth.tex != 0;
    gl->Uniform1i(p->depth_on, depth);
    if (depth) {
        gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_HOST_DEPTH);
        gl->BindTexture(GL_TEXTURE_2D, ctx->host_depth.tex);
        gl->BindSampler(CU_UNIT_HOST_DEPTH, p->depth_sampler);
        gl->Uniform1f(p->depth_clear, ctx->host_depth.clear);
        /* perspective: bottom row (0, 0, -1, 0), z_ndc = -A - B / z_eye; orthographic: z_ndc = A z_eye + B */
        int ortho = proj[11] == 0.0;
        gl->Uniform3f(p->lin, (float)proj[10], (float)proj[14], ortho ? 1.0f : 0.0f);
    }
    gl->Uniform1i(p->refined_on, refined != 0);
    gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_REFINED);
    gl->BindTexture(GL_TEXTURE_2D, refined);
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindTexture(GL_TEXTURE_2D, low);
    gl->BindVertexArray(ctx->empty_vao);
    gl->DrawArrays(GL_TRIANGLES, 0, 3);
    gl->Disable(GL_BLEND);
}
