/* src/gpu/pass_tonemap.c: the HDR target and the tone map (see pass_tonemap.h). */
#include "pass_tonemap.h"
#include "error.h"
#include <string.h>

static void locs_get(const cu_gl *gl, GLuint prog, cu_tonemap_locs *l)
{
    l->exposure = cu_gpu_loc(gl, prog, "u_exposure");
    l->white = cu_gpu_loc(gl, prog, "u_white");
    l->composite = cu_gpu_loc(gl, prog, "u_composite");
    cu_gpu_unit(gl, prog, "u_hdr", 0);
}

int cu_pass_tonemap_create(cu_pass_tonemap *p, const cu_gpu_scene *ctx, const char *defines,
                           const char *linear_defines, cu_error *err)
{
    const cu_gl *gl = ctx->gl;
    memset(p, 0, sizeof *p);
    if (!(p->prog_tonemap = cu_gl_program(gl, "fullscreen.vert", "tonemap.frag", defines, err)) ||
        !(p->prog_copy = cu_gl_program(gl, "fullscreen.vert", "tonemap.frag", linear_defines, err)))
        return 1;
    locs_get(gl, p->prog_tonemap, &p->tonemap);
    locs_get(gl, p->prog_copy, &p->copy);
    return 0;
}

void cu_pass_tonemap_destroy(cu_pass_tonemap *p, const cu_gl *gl)
{
    if (p->prog_tonemap)
        gl->DeleteProgram(p->prog_tonemap);
    if (p->prog_copy)
        gl->DeleteProgram(p->prog_copy);
    p->prog_tonemap = p->prog_copy = 0;
    cu_target_delete(&p->hdr, gl);
}

int cu_pass_tonemap_resize(cu_pass_tonemap *p, const cu_gpu_scene *ctx, int w, int h, int linear, cu_error *err)
{
    GLenum want;
    if (linear) {
        if (!ctx->float_rt)
            return cu_fail(err, "linear output needs a float colour target (EXT_color_buffer_float), which this "
                                "context lacks");
        want = GL_RGBA32F;
    } else {
        want = ctx->half_rt ? GL_RGBA16F : GL_RGBA8;
    }
    if (p->hdr.fbo && p->hdr.width == w && p->hdr.height == h && p->hdr.format == want)
        return 0;
    cu_target_delete(&p->hdr, ctx->gl);
    cu_target_desc d = {.name = "HDR target", .width = w, .height = h, .format = want, .colors = 1,
                        .depth_stencil = 1};
    return cu_target_create(&p->hdr, ctx->gl, &d, err);
}

void cu_pass_tonemap_draw(const cu_pass_tonemap *p, const cu_gpu_scene *ctx, unsigned fbo, int linear,
                          int composite)
{
    const cu_gl *gl = ctx->gl;
    const cu_scene *s = ctx->scene;
    gl->Disable(GL_DEPTH_TEST);
    gl->BindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl->Viewport(0, 0, p->hdr.width, p->hdr.height);
    const cu_tonemap_locs *l = linear ? &p->copy : &p->tonemap;
    gl->UseProgram(linear ? p->prog_copy : p->prog_tonemap);
    gl->Uniform1i(l->composite, composite);
    if (composite) {
        gl->Enable(GL_BLEND);
        gl->BlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    } else {
        gl->Disable(GL_BLEND);
    }
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindTexture(GL_TEXTURE_2D, p->hdr.tex[0]);
    int pre = p->hdr.format != GL_RGBA32F; /* the passes applied exposure and white already (cu_out_scale) */
    gl->Uniform1f(l->exposure, pre ? 1.0f : (float)s->exposure);
    gl->Uniform3f(l->white, pre ? 1.0f : (float)ctx->white[0], pre ? 1.0f : (float)ctx->white[1],
                  pre ? 1.0f : (float)ctx->white[2]);
    gl->BindVertexArray(ctx->empty_vao);
    gl->DrawArrays(GL_TRIANGLES, 0, 3);
    gl->BindVertexArray(0);
}
