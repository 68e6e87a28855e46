/* src/gpu/pass_cloud.c: the depth pre-pass and the cloud pass (see pass_cloud.h). */
#include "pass_cloud.h"
#include <string.h>

int cu_pass_cloud_create(cu_pass_cloud *p, const cu_gpu_scene *ctx, const char *hull_defs, const char *fs_defs,
                         cu_error *err)
{
    const cu_gl *gl = ctx->gl;
    memset(p, 0, sizeof *p);
    if (!(p->prog_depth = cu_gl_program(gl, "hull.vert", "depth.frag", hull_defs, err)) ||
        !(p->prog_hull = cu_gl_program(gl, "hull.vert", "cloud.frag", hull_defs, err)) ||
        !(p->prog_fs = cu_gl_program(gl, "fullscreen.vert", "cloud.frag", fs_defs, err)))
        return 1;
    p->depth_viewproj = cu_gpu_loc(gl, p->prog_depth, "u_viewproj");
    gl->GenSamplers(1, &p->host_sampler);
    gl->SamplerParameteri(p->host_sampler, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->SamplerParameteri(p->host_sampler, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl->SamplerParameteri(p->host_sampler, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    gl->SamplerParameteri(p->host_sampler, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl->SamplerParameteri(p->host_sampler, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    cu_shading_locs_get(gl, p->prog_hull, &p->hull);
    cu_shading_locs_get(gl, p->prog_fs, &p->fs);
    return 0;
}

void cu_pass_cloud_destroy(cu_pass_cloud *p, const cu_gl *gl)
{
    GLuint progs[3] = {p->prog_depth, p->prog_hull, p->prog_fs};
    for (int i = 0; i < 3; i++)
        if (progs[i])
            gl->DeleteProgram(progs[i]);
    p->prog_depth = p->prog_hull = p->prog_fs = 0;
    if (p->host_sampler)
        gl->DeleteSamplers(1, &p->host_sampler);
    p->host_sampler = 0;
}

/* Could the near plane cut some hull? Then hull rasterisation would miss pixels. A point of the near plane lies
 * within d = znear * near_reach of the eye; the points within d of an ellipsoid with radii r lie inside the one
 * with radii r + d, so inside s <= 1 + d / r_min in its normalised coordinates, and inside the sphere of radius
 * r_max + d: the plane cuts the hull only if the eye passes both tests. */
int cu_pass_cloud_fullscreen(const cu_gpu_scene *ctx)
{
    const cu_camera *cam = &ctx->camera;
    if (cam->ortho)
        return cam->near_cuts;
    const cu_cloud *cl = ctx->cloud;
    double k = cu_hull_scale(ctx->scene->hull_tessellation), d = cam->znear * cam->near_reach;
    for (int i = 0; i < cl->n; i++) {
        vec3 rr = v3_scale(cl->r[i], k);
        double rmin = fmin(rr.x, fmin(rr.y, rr.z)), rmax = fmax(rr.x, fmax(rr.y, rr.z));
        vec3 q = v3_sub(cam->pos, cl->c[i]);
        double s = v3_len(v3(q.x / rr.x, q.y / rr.y, q.z / rr.z));
        if (s <= 1.0 + d / rmin && v3_len(q) <= rmax + d)
            return 1;
    }
    return 0;
}

void cu_pass_cloud_draw(const cu_pass_cloud *p, const cu_gpu_scene *ctx)
{
    const cu_gl *gl = ctx->gl;
    const cu_camera *cam = &ctx->camera;
    if (!(ctx->cloud->ke > 0) || !cam->visible) /* zero density, or clouds out of view, cannot change a pixel */
        return;
    cu_shading_bind(ctx);
    if (ctx->host_depth.tex) {
        /* Drawn into cumulo's own target, so the texture may be the host framebuffer's attachment: no loop. */
        gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_HOST_DEPTH);
        gl->BindTexture(GL_TEXTURE_2D, ctx->host_depth.tex);
        gl->BindSampler(CU_UNIT_HOST_DEPTH, p->host_sampler);
        gl->ActiveTexture(GL_TEXTURE0);
    }
    gl->Enable(GL_BLEND);
    gl->BlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA); /* premultiplied over the sky */
    /* While refining (quality.edge_refine), the full-screen triangle too: one fragment a pixel for the stencil test
     * to reject, where the hull would bring a depth pre-pass and every layer of every ellipsoid to reject. */
    if (ctx->refining || cu_pass_cloud_fullscreen(ctx)) {
        gl->Disable(GL_DEPTH_TEST);
        if (ctx->refining) { /* only the pixels quality.edge_refine marked; never written (pass_refine.c), so the test
                              * runs before the shader although it can discard */
            gl->Enable(GL_STENCIL_TEST);
            gl->StencilFunc(GL_EQUAL, 0, CU_REFINE_SKIP);
            gl->StencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
        }
        cu_shading_uniforms(ctx, p->prog_fs, &p->fs, cam->pos, cam->vp, cam->inv_vp);
        cu_shading_frame(ctx, &p->fs);
        gl->BindVertexArray(ctx->empty_vao);
        gl->DrawArrays(GL_TRIANGLES, 0, 3);
        gl->Disable(GL_STENCIL_TEST);
        gl->Disable(GL_BLEND);
        return;
    }
    /* Depth pre-pass: the nearest hull fragment per pixel, no colour. */
    gl->Disable(GL_BLEND);
    gl->Enable(GL_DEPTH_TEST);
    gl->DepthFunc(GL_LESS);
    gl->ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    gl->UseProgram(p->prog_depth);
    gl->UniformMatrix4fv(p->depth_viewproj, 1, GL_FALSE, cam->vp);
    gl->BindVertexArray(ctx->hull_vao);
    gl->DrawElementsInstanced(GL_TRIANGLES, ctx->hull_indices, GL_UNSIGNED_SHORT, 0, ctx->cloud->n);
    /* Cloud pass: only the fragment that won the depth test is shaded. Where two hulls' depths are equal to the
     * depth buffer's precision, both would pass GL_EQUAL and blend the whole ray twice; the stencil lets the first
     * of them through and no other (the shader integrates the whole ray, so any one will do). */
    gl->ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl->Enable(GL_BLEND);
    gl->DepthFunc(GL_EQUAL);
    gl->DepthMask(GL_FALSE);
    gl->Enable(GL_STENCIL_TEST);
    gl->StencilFunc(GL_EQUAL, 0, 0xff);
    gl->StencilOp(GL_KEEP, GL_KEEP, GL_INCR);
    cu_shading_uniforms(ctx, p->prog_hull, &p->hull, cam->pos, cam->vp, cam->inv_vp);
    cu_shading_frame(ctx, &p->hull);
    gl->DrawElementsInstanced(GL_TRIANGLES, ctx->hull_indices, GL_UNSIGNED_SHORT, 0, ctx->cloud->n);
    gl->Disable(GL_STENCIL_TEST);
    gl->DepthMask(GL_TRUE);
    gl->DepthFunc(GL_LESS);
    gl->Disable(GL_BLEND);
}
