/* src/gpu/glstate.c: saving and restoring the host's GL state around cumulo's calls (see glstate.h). */
#include "glstate.h"

static void set_cap(const cu_gl *gl, GLenum cap, GLboolean on)
{
    if (on)
        gl->Enable(cap);
    else
        gl->Disable(cap);
}

void cu_glstate_enter(const cu_gl *gl, cu_glstate *s)
{
    gl->GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s->draw_fbo);
    gl->GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &s->read_fbo);
    gl->GetIntegerv(GL_CURRENT_PROGRAM, &s->program);
    gl->GetIntegerv(GL_VERTEX_ARRAY_BINDING, &s->vao);
    gl->GetIntegerv(GL_ARRAY_BUFFER_BINDING, &s->array_buffer);
    gl->GetIntegerv(GL_RENDERBUFFER_BINDING, &s->renderbuffer);
    gl->GetIntegerv(GL_ACTIVE_TEXTURE, &s->active_texture);
    for (int i = 0; i < CU_GLSTATE_UNITS; i++) {
        gl->ActiveTexture(GL_TEXTURE0 + (GLenum)i);
        gl->GetIntegerv(GL_TEXTURE_BINDING_2D, &s->tex2d[i]);
        gl->GetIntegerv(GL_TEXTURE_BINDING_3D, &s->tex3d[i]);
        gl->GetIntegerv(GL_SAMPLER_BINDING, &s->sampler[i]);
    }
    gl->ActiveTexture((GLenum)s->active_texture);
    gl->GetIntegerv(GL_VIEWPORT, s->viewport);
    gl->GetIntegerv(GL_SCISSOR_BOX, s->scissor_box);
    s->blend = gl->IsEnabled(GL_BLEND);
    s->depth_test = gl->IsEnabled(GL_DEPTH_TEST);
    s->stencil_test = gl->IsEnabled(GL_STENCIL_TEST);
    s->cull_face = gl->IsEnabled(GL_CULL_FACE);
    s->scissor_test = gl->IsEnabled(GL_SCISSOR_TEST);
    s->polygon_offset = gl->IsEnabled(GL_POLYGON_OFFSET_FILL);
    s->rasterizer_discard = gl->IsEnabled(GL_RASTERIZER_DISCARD);
    s->alpha_to_coverage = gl->IsEnabled(GL_SAMPLE_ALPHA_TO_COVERAGE);
    s->sample_coverage = gl->IsEnabled(GL_SAMPLE_COVERAGE);
    gl->GetIntegerv(GL_BLEND_SRC_RGB, &s->blend_src_rgb);
    gl->GetIntegerv(GL_BLEND_DST_RGB, &s->blend_dst_rgb);
    gl->GetIntegerv(GL_BLEND_SRC_ALPHA, &s->blend_src_a);
    gl->GetIntegerv(GL_BLEND_DST_ALPHA, &s->blend_dst_a);
    gl->GetIntegerv(GL_BLEND_EQUATION_RGB, &s->blend_eq_rgb);
    gl->GetIntegerv(GL_BLEND_EQUATION_ALPHA, &s->blend_eq_a);
    gl->GetBooleanv(GL_DEPTH_WRITEMASK, &s->depth_mask);
    gl->GetBooleanv(GL_COLOR_WRITEMASK, s->color_mask);
    gl->GetIntegerv(GL_DEPTH_FUNC, &s->depth_func);
    static const GLenum q[2][7] = {
        {GL_STENCIL_FUNC, GL_STENCIL_REF, GL_STENCIL_VALUE_MASK, GL_STENCIL_WRITEMASK, GL_STENCIL_FAIL,
         GL_STENCIL_PASS_DEPTH_FAIL, GL_STENCIL_PASS_DEPTH_PASS},
        {GL_STENCIL_BACK_FUNC, GL_STENCIL_BACK_REF, GL_STENCIL_BACK_VALUE_MASK, GL_STENCIL_BACK_WRITEMASK,
         GL_STENCIL_BACK_FAIL, GL_STENCIL_BACK_PASS_DEPTH_FAIL, GL_STENCIL_BACK_PASS_DEPTH_PASS}};
    for (int f = 0; f < 2; f++) {
        gl->GetIntegerv(q[f][0], &s->stencil_func[f]);
        gl->GetIntegerv(q[f][1], &s->stencil_ref[f]);
        gl->GetIntegerv(q[f][2], &s->stencil_value_mask[f]);
        gl->GetIntegerv(q[f][3], &s->stencil_writemask[f]);
        gl->GetIntegerv(q[f][4], &s->stencil_fail[f]);
        gl->GetIntegerv(q[f][5], &s->stencil_zfail[f]);
        gl->GetIntegerv(q[f][6], &s->stencil_zpass[f]);
    }
    gl->GetFloatv(GL_COLOR_CLEAR_VALUE, s->clear_color);
    gl->GetFloatv(GL_DEPTH_CLEAR_VALUE, &s->clear_depth);
    gl->GetIntegerv(GL_STENCIL_CLEAR_VALUE, &s->clear_stencil);
    gl->GetIntegerv(GL_PACK_ALIGNMENT, &s->pack_alignment);
    gl->GetIntegerv(GL_UNPACK_ALIGNMENT, &s->unpack_alignment);

    /* What the passes assume and never set themselves. */
    gl->Disable(GL_SCISSOR_TEST);
    gl->Disable(GL_POLYGON_OFFSET_FILL);
    gl->Disable(GL_RASTERIZER_DISCARD);
    gl->Disable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    gl->Disable(GL_SAMPLE_COVERAGE);
    gl->BlendEquation(GL_FUNC_ADD);
    gl->ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl->StencilMaskSeparate(GL_FRONT_AND_BACK, 0xff);
    for (int i = 0; i < CU_GLSTATE_UNITS; i++)
        if (s->sampler[i])
            gl->BindSampler((GLuint)i, 0);
}

void cu_glstate_leave(const cu_gl *gl, const cu_glstate *s)
{
    gl->BindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)s->draw_fbo);
    gl->BindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)s->read_fbo);
    gl->UseProgram((GLuint)s->program);
    gl->BindVertexArray((GLuint)s->vao);
    gl->BindBuffer(GL_ARRAY_BUFFER, (GLuint)s->array_buffer);
    gl->BindRenderbuffer(GL_RENDERBUFFER, (GLuint)s->renderbuffer);
    for (int i = 0; i < CU_GLSTATE_UNITS; i++) {
        gl->ActiveTexture(GL_TEXTURE0 + (GLenum)i);
        gl->BindTexture(GL_TEXTURE_2D, (GLuint)s->tex2d[i]);
        gl->BindTexture(GL_TEXTURE_3D, (GLuint)s->tex3d[i]);
        gl->BindSampler((GLuint)i, (GLuint)s->sampler[i]);
    }
    gl->ActiveTexture((GLenum)s->active_texture);
    gl->Viewport(s->viewport[0], s->viewport[1], s->viewport[2], s->viewport[3]);
    gl->Scissor(s->scissor_box[0], s->scissor_box[1], s->scissor_box[2], s->scissor_box[3]);
    set_cap(gl, GL_BLEND, s->blend);
    set_cap(gl, GL_DEPTH_TEST, s->depth_test);
    set_cap(gl, GL_STENCIL_TEST, s->stencil_test);
    set_cap(gl, GL_CULL_FACE, s->cull_face);
    set_cap(gl, GL_SCISSOR_TEST, s->scissor_test);
    set_cap(gl, GL_POLYGON_OFFSET_FILL, s->polygon_offset);
    set_cap(gl, GL_RASTERIZER_DISCARD, s->rasterizer_discard);
    set_cap(gl, GL_SAMPLE_ALPHA_TO_COVERAGE, s->alpha_to_coverage);
    set_cap(gl, GL_SAMPLE_COVERAGE, s->sample_coverage);
    gl->BlendFuncSeparate((GLenum)s->blend_src_rgb, (GLenum)s->blend_dst_rgb, (GLenum)s->blend_src_a,
                          (GLenum)s->blend_dst_a);
    gl->BlendEquationSeparate((GLenum)s->blend_eq_rgb, (GLenum)s->blend_eq_a);
    gl->DepthMask(s->depth_mask);
    gl->ColorMask(s->color_mask[0], s->color_mask[1], s->color_mask[2], s->color_mask[3]);
    gl->DepthFunc((GLenum)s->depth_func);
    static const GLenum face[2] = {GL_FRONT, GL_BACK};
    for (int f = 0; f < 2; f++) {
        gl->StencilFuncSeparate(face[f], (GLenum)s->stencil_func[f], s->stencil_ref[f],
                                (GLuint)s->stencil_value_mask[f]);
        gl->StencilMaskSeparate(face[f], (GLuint)s->stencil_writemask[f]);
        gl->StencilOpSeparate(face[f], (GLenum)s->stencil_fail[f], (GLenum)s->stencil_zfail[f],
                              (GLenum)s->stencil_zpass[f]);
    }
    gl->ClearColor(s->clear_color[0], s->clear_color[1], s->clear_color[2], s->clear_color[3]);
    gl->ClearDepthf(s->clear_depth);
    gl->ClearStencil(s->clear_stencil);
    gl->PixelStorei(GL_PACK_ALIGNMENT, s->pack_alignment);
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, s->unpack_alignment);
}
