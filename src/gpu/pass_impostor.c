/* src/gpu/pass_impostor.c: drawing a cloud from its impostor (see pass_impostor.h). */
#include "pass_impostor.h"
#include <string.h>

int cu_pass_impostor_create(cu_pass_impostor *p, const cu_gpu_scene *ctx, const char *defs, cu_error *err)
{
    const cu_gl *gl = ctx->gl;
    memset(p, 0, sizeof *p);
    if (!(p->prog = cu_gl_program(gl, "impostor.vert", "impostor.frag", defs, err)))
        return 1;
    p->rot_vp = cu_gpu_loc(gl, p->prog, "u_rot_vp");
    p->corner0 = cu_gpu_loc(gl, p->prog, "u_corner0");
    p->du = cu_gpu_loc(gl, p->prog, "u_du");
    p->dv = cu_gpu_loc(gl, p->prog, "u_dv");
    p->motion = cu_gpu_loc(gl, p->prog, "u_motion");
    p->image = cu_gpu_loc(gl, p->prog, "u_image");
    /* bilinear: the image is made at about a texel per pixel of the cloud, and drawn as the cloud grows or shrinks */
    gl->GenSamplers(1, &p->sampler);
    gl->SamplerParameteri(p->sampler, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl->SamplerParameteri(p->sampler, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl->SamplerParameteri(p->sampler, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl->SamplerParameteri(p->sampler, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return 0;
}

void cu_pass_impostor_destroy(cu_pass_impostor *p, const cu_gl *gl)
{
    if (p->prog)
        gl->DeleteProgram(p->prog);
    if (p->sampler)
        gl->DeleteSamplers(1, &p->sampler);
    memset(p, 0, sizeof *p);
}

int cu_pass_impostor_begin(cu_impostor *im, const cu_gpu_scene *ctx, int size, GLenum format, cu_error *err)
{
    const cu_gl *gl = ctx->gl;
    if (!im->image.fbo || im->image.width != size || im->image.format != format) {
        cu_target_delete(&im->image, gl);
        cu_target_desc d = {.name = "cloud impostor", .width = size, .height = size, .format = format, .colors = 1,
                            .depth_stencil = 1};
        if (cu_target_create(&im->image, gl, &d, err))
            return 1;
    }
    im->size = size;
    gl->BindFramebuffer(GL_FRAMEBUFFER, im->image.fbo);
    gl->Viewport(0, 0, size, size);
    gl->ClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    gl->Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    return 0;
}

void cu_pass_impostor_draw(const cu_pass_impostor *p, const cu_gpu_scene *ctx, const cu_impostor *im)
{
    const cu_gl *gl = ctx->gl;
    const cu_camera *cam = &ctx->camera;
    /* corner (0, 0) is the centre (the local origin) - half (u + v); about the eye: minus the eye */
    vec3 c0 = v3_sub(v3_scale(v3_add(im->u, im->v), -im->half), cam->pos);
    vec3 du = v3_scale(im->u, 2.0 * im->half), dv = v3_scale(im->v, 2.0 * im->half);
    gl->UseProgram(p->prog);
    gl->UniformMatrix4fv(p->rot_vp, 1, GL_FALSE, cam->rot_vp);
    gl->Uniform3f(p->corner0, (float)c0.x, (float)c0.y, (float)c0.z);
    gl->Uniform3f(p->du, (float)du.x, (float)du.y, (float)du.z);
    gl->Uniform3f(p->dv, (float)dv.x, (float)dv.y, (float)dv.z);
    gl->Uniform2f(p->motion, ctx->motion[0], ctx->motion[1]);
    gl->Uniform1i(p->image, CU_UNIT_CLOUDS);
    gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_CLOUDS); /* the sky pass composites from this unit later in the frame */
    gl->BindTexture(GL_TEXTURE_2D, im->image.tex[0]);
    gl->BindSampler(CU_UNIT_CLOUDS, p->sampler);
    gl->ActiveTexture(GL_TEXTURE0);
    gl->Disable(GL_DEPTH_TEST);
    if (ctx->refining) { /* only the pixels quality.edge_refine marked */
        gl->Enable(GL_STENCIL_TEST);
        gl->StencilFunc(GL_EQUAL, 0, CU_REFINE_SKIP);
        gl->StencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    } else {
        gl->Disable(GL_STENCIL_TEST);
    }
    gl->Enable(GL_BLEND);
    gl->BlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA); /* premultiplied, as the cloud pass */
    gl->BindVertexArray(ctx->empty_vao);
    gl->DrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    gl->Disable(GL_BLEND);
    gl->BindSampler(CU_UNIT_CLOUDS, 0);
}

void cu_impostor_free(cu_impostor *im, const cu_gl *gl)
{
    cu_target_delete(&im->image, gl);
    memset(im, 0, sizeof *im);
}
