/* src/gpu/pass_refine.c: the full-resolution target and the mark pass of quality.edge_refine (see pass_refine.h). */
#include "pass_refine.h"
#include "error.h"
#include <string.h>

int cu_pass_refine_create(cu_pass_refine *p, const cu_gpu_scene *ctx, cu_error *err)
{
    const cu_gl *gl = ctx->gl;
    memset(p, 0, sizeof *p);
    if (!(p->prog = cu_gl_program(gl, "fullscreen.vert", "refine_mark.frag", "", err)))
        return 1;
    p->factor = cu_gpu_loc(gl, p->prog, "u_factor");
    p->threshold = cu_gpu_loc(gl, p->prog, "u_threshold");
    cu_gpu_unit(gl, p->prog, "u_low", CU_UNIT_CLOUDS);
    return 0;
}

void cu_pass_refine_destroy(cu_pass_refine *p, const cu_gl *gl)
{
    if (p->prog)
        gl->DeleteProgram(p->prog);
    p->prog = 0;
    cu_target_delete(&p->full, gl);
}

int cu_pass_refine_begin(cu_pass_refine *p, const cu_gpu_scene *ctx, GLuint low, int w, int h, int n,
                         double threshold, const int rect[4], GLenum format, cu_error *err)
{
    const cu_gl *gl = ctx->gl;
    if (!p->full.fbo || p->full.width != w || p->full.height != h || p->full.format != format) {
        cu_target_delete(&p->full, gl);
        cu_target_desc d = {.name = "edge refinement target", .width = w, .height = h, .format = format, .colors = 1,
                            .depth_stencil = 1};
        if (cu_target_create(&p->full, gl, &d, err))
            return 1;
    }
    gl->BindFramebuffer(GL_FRAMEBUFFER, p->full.fbo);
    gl->Viewport(0, 0, w, h);
    int x0 = rect[0] < 0 ? 0 : rect[0], y0 = rect[1] < 0 ? 0 : rect[1];
    int x1 = rect[2] > w ? w : rect[2], y1 = rect[3] > h ? h : rect[3];
    if (x1 <= x0 || y1 <= y0)
        x0 = y0 = x1 = y1 = 0;
    /* the composite reads this target within rect alone: the clear and the marks need go no further */
    gl->Enable(GL_SCISSOR_TEST);
    gl->Scissor(x0, y0, x1 - x0, y1 - y0);
    gl->Disable(GL_BLEND);
    gl->Disable(GL_DEPTH_TEST);
    gl->ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl->DepthMask(GL_TRUE);
    gl->StencilMaskSeparate(GL_FRONT_AND_BACK, 0xff);
    gl->ClearColor(0.0f, 0.0f, 0.0f, 2.0f);
    gl->ClearDepthf(1.0f);
    gl->ClearStencil((GLint)CU_REFINE_SKIP);
    gl->Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    gl->ClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    gl->ClearStencil(0);
    gl->Enable(GL_STENCIL_TEST);
    gl->StencilFunc(GL_ALWAYS, 0, 0xff);
    gl->StencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    gl->UseProgram(p->prog);
    gl->Uniform1f(p->factor, (float)n);
    gl->Uniform1f(p->threshold, (float)threshold);
    gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_CLOUDS);
    gl->BindTexture(GL_TEXTURE_2D, low);
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindVertexArray(ctx->empty_vao);
    gl->DrawArrays(GL_TRIANGLES, 0, 3);
    /* what the cloud pass expects: its stencil test per draw (pass_cloud.c), never a write: the test stays early */
    gl->Enable(GL_STENCIL_TEST);
    gl->StencilFunc(GL_EQUAL, 0, CU_REFINE_SKIP);
    gl->StencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    gl->StencilMaskSeparate(GL_FRONT_AND_BACK, 0);
    return 0;
}

void cu_pass_refine_end(const cu_pass_refine *p, const cu_gl *gl)
{
    (void)p;
    gl->Disable(GL_STENCIL_TEST);
    gl->Disable(GL_SCISSOR_TEST);
    gl->StencilMaskSeparate(GL_FRONT_AND_BACK, 0xff);
}
