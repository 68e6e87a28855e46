/* src/gpu/pass_temporal.c: the temporal grid's targets, Bayer order and resolve (see pass_temporal.h). */
#include "pass_temporal.h"
#include "camera.h"
#include "error.h"
#include <math.h>
#include <string.h>

/* The pixel of each G x G block marched in frame k of a cycle: ordered dithering's matrices read backwards, so that
 * consecutive frames land far apart and every G^2 frames cover the block once. */
static void bayer(int g, unsigned long k, int *x, int *y)
{
    static const unsigned char b2[4][2] = {{0, 0}, {1, 1}, {1, 0}, {0, 1}};
    static const unsigned char b3[9][2] = {{0, 0}, {2, 1}, {1, 2}, {2, 0}, {0, 1}, {1, 0}, {2, 2}, {0, 2}, {1, 1}};
    static const unsigned char b4[16][2] = {{0, 0}, {2, 2}, {2, 0}, {0, 2}, {1, 1}, {3, 3}, {3, 1}, {1, 3},
                                            {1, 0}, {3, 2}, {3, 0}, {1, 2}, {0, 1}, {2, 3}, {2, 1}, {0, 3}};
    const unsigned char *e = g == 2 ? b2[k % 4] : g == 3 ? b3[k % 9] : b4[k % 16];
    *x = e[0];
    *y = e[1];
}

int cu_pass_temporal_create(cu_pass_temporal *p, const cu_gpu_scene *ctx, cu_error *err)
{
    const cu_gl *gl = ctx->gl;
    memset(p, 0, sizeof *p);
    /* two variants, not a uniform: a software rasteriser pays for both sides of a branch (temporal.frag) */
    static const char *const defines[2] = {"#define HW_FILTER 0\n", "#define HW_FILTER 1\n"};
    for (int v = 0; v < 2; v++) {
        GLuint prog = p->prog[v] = cu_gl_program(gl, "sky.vert", "temporal.frag", defines[v], err);
        if (!prog)
            return 1;
        cu_temporal_locs *l = &p->loc[v];
#define LOC(f, n) l->f = cu_gpu_loc(gl, prog, n)
        LOC(grid, "u_grid"); LOC(offset, "u_offset"); LOC(size, "u_size"); LOC(inv_rot, "u_inv_viewproj");
        LOC(prev_rot, "u_prev_rot"); LOC(eye_delta, "u_eye_delta"); LOC(moved, "u_moved");
#undef LOC
        cu_gpu_unit(gl, prog, "u_fresh", 0);
        cu_gpu_unit(gl, prog, "u_fresh_depth", 1);
        cu_gpu_unit(gl, prog, "u_hist", 2);
        cu_gpu_unit(gl, prog, "u_hist_depth", 3);
    }
    return 0;
}

void cu_pass_temporal_destroy(cu_pass_temporal *p, const cu_gl *gl)
{
    for (int v = 0; v < 2; v++)
        if (p->prog[v])
            gl->DeleteProgram(p->prog[v]);
    cu_target_delete(&p->sparse, gl);
    cu_target_delete(&p->hist[0], gl);
    cu_target_delete(&p->hist[1], gl);
    memset(p, 0, sizeof *p);
}

void cu_pass_temporal_reset(cu_pass_temporal *p)
{
    p->valid = 0;
}

static int fit(cu_target *t, const cu_gl *gl, const char *name, int w, int h, GLenum format, cu_error *err)
{
    if (t->fbo && t->width == w && t->height == h && t->format == format)
        return 0;
    cu_target_delete(t, gl);
    cu_target_desc d = {.name = name, .width = w, .height = h, .format = format, .colors = 2, .depth_stencil = 1};
    if (cu_target_create(t, gl, &d, err))
        return 1;
    for (int k = 0; k < 2 && format == GL_RGBA16F; k++) { /* filterable: the resolve reads it bilinear */
        gl->BindTexture(GL_TEXTURE_2D, t->tex[k]);
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    return 0;
}

static void bind_cleared(const cu_gl *gl, const cu_target *t)
{
    static const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    gl->BindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    gl->DrawBuffers(2, both);
    gl->Viewport(0, 0, t->width, t->height);
    gl->ClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    gl->Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
}

int cu_pass_temporal_begin(cu_pass_temporal *p, const cu_gpu_scene *ctx, int lw, int lh, int g, GLenum format,
                           int whole, int *sparse, cu_error *err)
{
    const cu_gl *gl = ctx->gl;
    int sw = (lw + g - 1) / g, sh = (lh + g - 1) / g;
    int same = p->hist[p->cur].fbo && p->hist[p->cur].width == lw && p->hist[p->cur].height == lh &&
               p->hist[p->cur].format == format && p->grid == g;
    if (fit(&p->sparse, gl, "temporal grid's target", sw, sh, format, err) ||
        fit(&p->hist[0], gl, "cloud image (temporal)", lw, lh, format, err) ||
        fit(&p->hist[1], gl, "cloud image (temporal)", lw, lh, format, err))
        return 1;
    /* the sun's turn since the last frame: the lighting in the history is that old */
    double c = v3_dot(ctx->sky->sun_dir, p->prev_sun);
    int sun_jumped = !(c > cos(0.25 * CU_PI / 180.0));
    p->sparse_now = p->valid && same && !whole && !sun_jumped;
    if (!p->sparse_now)
        p->frame = 0;
    p->grid = g;
    bayer(g, p->frame, &p->ox, &p->oy);
    bind_cleared(gl, p->sparse_now ? &p->sparse : &p->hist[p->cur ^ 1]);
    *sparse = p->sparse_now;
    return 0;
}

mat4 cu_pass_temporal_projection(const cu_pass_temporal *p, mat4 proj, int lw, int lh)
{
    /* Sparse pixel i's NDC s = 2 (i + 1/2) / sw - 1 must land on the image's pixel g i + o: its NDC
     * x = a s + b with a = g sw / lw, b = (g sw - g + 2 o + 1) / lw - 1; so clip x' = (x - b w) / a. */
    int g = p->grid, sw = p->sparse.width, sh = p->sparse.height;
    double ax = (double)g * sw / lw, bx = ((double)g * sw - g + 2 * p->ox + 1) / lw - 1.0;
    double ay = (double)g * sh / lh, by = ((double)g * sh - g + 2 * p->oy + 1) / lh - 1.0;
    mat4 m = proj;
    for (int col = 0; col < 4; col++) {
        double *c = m.m + 4 * col;
        c[0] = (c[0] - bx * c[3]) / ax;
        c[1] = (c[1] - by * c[3]) / ay;
    }
    return m;
}

void cu_pass_temporal_end(cu_pass_temporal *p, const cu_gpu_scene *ctx, const cu_camera *cam, double time,
                          const double ndc_rect[4])
{
    const cu_gl *gl = ctx->gl;
    cu_target *dst = &p->hist[p->cur ^ 1], *src = &p->hist[p->cur];
    if (p->sparse_now) {
        static const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
        gl->BindFramebuffer(GL_FRAMEBUFFER, dst->fbo);
        gl->DrawBuffers(2, both);
        gl->Viewport(0, 0, dst->width, dst->height);
        /* grown by the reads about a pixel: its block's fresh samples and the bilinear ones beyond */
        int px[4];
        cu_ndc_rect_pixels(ndc_rect, dst->width, dst->height, p->grid + 2, px);
        if (px[0] > 0 || px[1] > 0 || px[2] < dst->width || px[3] < dst->height) {
            gl->ClearColor(0.0f, 0.0f, 0.0f, 0.0f);
            gl->Clear(GL_COLOR_BUFFER_BIT);
            gl->Enable(GL_SCISSOR_TEST);
            gl->Scissor(px[0], px[1], px[2] - px[0], px[3] - px[1]);
        }
        gl->Disable(GL_BLEND);
        gl->Disable(GL_DEPTH_TEST);
        gl->Disable(GL_STENCIL_TEST);
        /* RGBA16F targets are filtered by the texture unit (set LINEAR in fit); RGBA32F ones (linear output) are not
         * filterable in GLES 3.0, so the shader does it */
        int hw = dst->format == GL_RGBA16F;
        gl->UseProgram(p->prog[hw]);
        const cu_temporal_locs *l = &p->loc[hw];
        gl->Uniform1i(l->grid, p->grid);
        gl->Uniform2i(l->offset, p->ox, p->oy);
        gl->Uniform2f(l->size, (float)dst->width, (float)dst->height);
        gl->UniformMatrix4fv(l->inv_rot, 1, GL_FALSE, cam->inv_rot);
        gl->UniformMatrix4fv(l->prev_rot, 1, GL_FALSE, p->prev_rot_vp);
        vec3 d = v3_sub(cam->pos, p->prev_eye);
        gl->Uniform3f(l->eye_delta, (float)d.x, (float)d.y, (float)d.z);
        gl->Uniform1i(l->moved, memcmp(cam->rot_vp, p->prev_rot_vp, sizeof p->prev_rot_vp) || v3_len(d) > 0);
        const GLuint tex[4] = {p->sparse.tex[0], p->sparse.tex[1], src->tex[0], src->tex[1]};
        for (int u = 0; u < 4; u++) {
            gl->ActiveTexture(GL_TEXTURE0 + (GLenum)u);
            gl->BindTexture(GL_TEXTURE_2D, tex[u]);
        }
        gl->ActiveTexture(GL_TEXTURE0);
        gl->BindVertexArray(ctx->empty_vao);
        gl->DrawArrays(GL_TRIANGLES, 0, 3);
        gl->Disable(GL_SCISSOR_TEST);
    }
    p->cur ^= 1;
    p->valid = 1;
    p->frame++;
    memcpy(p->prev_rot_vp, cam->rot_vp, sizeof p->prev_rot_vp);
    p->prev_eye = cam->pos;
    p->prev_sun = ctx->sky->sun_dir;
    p->prev_time = time;
}

GLuint cu_pass_temporal_image(const cu_pass_temporal *p)
{
    return p->hist[p->cur].tex[0];
}
