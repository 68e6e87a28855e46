/* src/slabmap.c: the multiple-scattering slab model on the GPU side: the fitted tables as a texture, the slab maps
 * from the sun and from the zenith (shaders_gles/slab_map.frag, mipmapped for the collector-area blur), and the
 * uniforms of shaders_gles/ms_slab.glsl. */
#include "slabmap.h"
#include "collector.h"
#include "sunmap.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SLAB_SAMPLES 8 /* trapezoids per interval for the slab map's optical depth: it is blurred anyway */

static int sfail(cu_error *err, const char *what)
{
    snprintf(err->msg, sizeof err->msg, "%s", what);
    return 1;
}

int cu_slab_load(cu_renderer *r, cu_error *err)
{
    r->ms_mode = r->scene.ms_mode;
    if (r->ms_mode != CU_MS_SLAB && r->ms_mode != CU_MS_COLLECTOR)
        return 0;
    if (!r->half_rt) {
        /* RGBA16F targets (EXT_color_buffer_half_float / _float) hold the mipmapped slab maps */
        cu_log(r, CU_LOG_WARN, "ms.mode = slab needs half-float render targets, which this context lacks: using "
                               "ms.mode = octaves");
        r->ms_mode = CU_MS_OCTAVES;
        return 0;
    }
    if (!r->slab_model && !(r->slab_model = malloc(sizeof *r->slab_model)))
        return sfail(err, "slab model: out of memory");
    char path[1024];
    const char *dir = r->data_dir;
    snprintf(path, sizeof path, "%s/slab_fit_bouthors.txt", dir);
    cu_slab_transport tr;
    if (cu_slab_committed_transport(dir, &tr, err) || cu_slab_model_load(r->slab_model, path, tr, err))
        return 1;
    if (r->ms_mode != CU_MS_COLLECTOR)
        return 0;
    if (!r->collector && !(r->collector = calloc(1, sizeof *r->collector)))
        return sfail(err, "collector table: out of memory");
    cu_collector_free(r->collector);
    snprintf(path, sizeof path, "%s/slab_collector.txt", dir);
    return cu_collector_load(r->collector, path, err);
}

int cu_slab_defines(const cu_renderer *r, char *buf, size_t n)
{
    const cu_slab_model *m = r->slab_model;
    int on = r->ms_mode == CU_MS_SLAB || r->ms_mode == CU_MS_COLLECTOR;
    /* sky and ground differ only under an analytic sky; a constant sky is the same from every direction */
    int split = on && r->scene.sky_light && r->scene.sky_model != CU_SKY_CONSTANT;
    const cu_collector *c = r->ms_mode == CU_MS_COLLECTOR ? r->collector : NULL;
    return snprintf(buf, n, "#define SLAB_NT %d\n#define SLAB_NV %d\n#define SLAB_NL %d\n#define SLAB_NP %d\n"
                            "#define SKY_SPLIT %d\n#define SLAB_SAMPLES %d\n#define COLL_NT %d\n#define COLL_NL %d\n"
                            "#define COLL_NV %d\n#define COLL_NP %d\n#define COLL_ITER %d\n",
                    on ? m->nt : 1, on ? m->nv : 2, on ? m->nl : 1, on ? m->np : 2, split, SLAB_SAMPLES,
                    c ? c->nt : 1, c ? c->nl : 1, c ? c->nv : 2, c ? c->np : 1, r->scene.ms_iterations) >= (int)n;
}

static GLuint make_half_mip_texture(cu_gl *gl, int size)
{
    GLuint t;
    gl->GenTextures(1, &t);
    gl->BindTexture(GL_TEXTURE_2D, t);
    int levels = 0;
    for (int s = size; s >= 1; s /= 2, levels++)
        gl->TexImage2D(GL_TEXTURE_2D, levels, GL_RGBA16F, s, s, 0, GL_RGBA, GL_HALF_FLOAT, NULL);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, levels - 1);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return t;
}

int cu_slab_targets(cu_renderer *r, const char *defines, cu_error *err)
{
    if (r->ms_mode != CU_MS_SLAB && r->ms_mode != CU_MS_COLLECTOR)
        return 0;
    cu_gl *gl = &r->gl;
    const cu_slab_model *m = r->slab_model;
    int w = cu_slab_model_tex_width(m), h = cu_slab_model_tex_height(m);
    float *rgba = malloc(sizeof(float) * 4 * (size_t)w * (size_t)h);
    if (!rgba)
        return sfail(err, "slab model: out of memory");
    cu_slab_model_pack(m, rgba);
    /* RGBA32F with texelFetch: the fitted values span 1e-10..1e3, beyond fp16 */
    gl->GenTextures(1, &r->slab_tab_tex);
    gl->BindTexture(GL_TEXTURE_2D, r->slab_tab_tex);
    gl->TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, w, h, 0, GL_RGBA, GL_FLOAT, rgba);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    free(rgba);
    if (r->ms_mode == CU_MS_COLLECTOR) {
        const cu_collector *c = r->collector;
        int cw = CU_COLL_ND * c->np, ch = c->nv * c->nl * c->nt;
        float *px = malloc(sizeof(float) * 4 * (size_t)cw * (size_t)ch);
        if (!px)
            return sfail(err, "collector table: out of memory");
        cu_collector_pack(c, px);
        gl->GenTextures(1, &r->coll_tex);
        gl->BindTexture(GL_TEXTURE_2D, r->coll_tex);
        gl->TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, cw, ch, 0, GL_RGBA, GL_FLOAT, px);
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        free(px);
    }
    if (!(r->prog_slab_map = cu_gl_program(gl, "fullscreen.vert", "slab_map.frag", defines, err)))
        return 1;
    int maps = r->scene.sky_light && r->scene.sky_model != CU_SKY_CONSTANT ? 2 : 1;
    for (int i = 0; i < maps; i++) {
        r->slab_a_tex[i] = make_half_mip_texture(gl, r->sun_size);
        r->slab_n_tex[i] = make_half_mip_texture(gl, r->sun_size);
        gl->GenFramebuffers(1, &r->slab_fbo[i]);
        gl->BindFramebuffer(GL_FRAMEBUFFER, r->slab_fbo[i]);
        gl->FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, r->slab_a_tex[i], 0);
        gl->FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, r->slab_n_tex[i], 0);
        GLenum bufs[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
        gl->DrawBuffers(2, bufs);
        GLenum st = gl->CheckFramebufferStatus(GL_FRAMEBUFFER);
        gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
        if (st != GL_FRAMEBUFFER_COMPLETE) {
            snprintf(err->msg, sizeof err->msg, "slab map: framebuffer incomplete (0x%x)", st);
            return 1;
        }
    }
    r->sky_slab_dirty = maps == 2;
    return 0;
}

void cu_slab_delete(cu_renderer *r)
{
    cu_gl *gl = &r->gl;
    for (int i = 0; i < 2; i++) {
        if (r->slab_a_tex[i]) gl->DeleteTextures(1, &r->slab_a_tex[i]);
        if (r->slab_n_tex[i]) gl->DeleteTextures(1, &r->slab_n_tex[i]);
        if (r->slab_fbo[i]) gl->DeleteFramebuffers(1, &r->slab_fbo[i]);
        r->slab_a_tex[i] = r->slab_n_tex[i] = r->slab_fbo[i] = 0;
    }
    if (r->slab_tab_tex) gl->DeleteTextures(1, &r->slab_tab_tex);
    if (r->coll_tex) gl->DeleteTextures(1, &r->coll_tex);
    r->coll_tex = 0;
    if (r->prog_slab_map) gl->DeleteProgram(r->prog_slab_map);
    r->slab_tab_tex = r->prog_slab_map = 0;
}

/* Map `which` (0: from the sun, 1: from the zenith), then its mip chain: the coverage-weighted averages the shader
 * reads at the blur's level. */
void cu_slab_render(cu_renderer *r, int which)
{
    if (!r->slab_fbo[which])
        return;
    cu_gl *gl = &r->gl;
    vec3 dir = which == 0 ? r->sky.sun_dir : v3(0, 1, 0), right, up;
    cu_sun_basis(dir, &right, &up);
    if (which == 1) {
        r->sky_right = right;
        r->sky_up = up;
    }
    GLuint p = r->prog_slab_map;
    gl->BindFramebuffer(GL_FRAMEBUFFER, r->slab_fbo[which]);
    gl->Viewport(0, 0, r->sun_size, r->sun_size);
    gl->Disable(GL_DEPTH_TEST);
    gl->Disable(GL_BLEND);
    gl->UseProgram(p);
    cu_set_density_uniforms(r, p);
    gl->Uniform3f(gl->GetUniformLocation(p, "u_map_dir"), (float)dir.x, (float)dir.y, (float)dir.z);
    gl->Uniform3f(gl->GetUniformLocation(p, "u_map_right"), (float)right.x, (float)right.y, (float)right.z);
    gl->Uniform3f(gl->GetUniformLocation(p, "u_map_up"), (float)up.x, (float)up.y, (float)up.z);
    gl->Uniform1f(gl->GetUniformLocation(p, "u_map_R"), (float)cu_sun_radius(&r->cloud));
    gl->Uniform1i(gl->GetUniformLocation(p, "u_map_size"), r->sun_size);
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindTexture(GL_TEXTURE_3D, r->noise_tex);
    gl->BindVertexArray(r->empty_vao);
    gl->DrawArrays(GL_TRIANGLES, 0, 3);
    gl->BindVertexArray(0);
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    GLuint tex[2] = {r->slab_a_tex[which], r->slab_n_tex[which]};
    for (int i = 0; i < 2; i++) {
        gl->BindTexture(GL_TEXTURE_2D, tex[i]);
        gl->GenerateMipmap(GL_TEXTURE_2D);
    }
    if (which == 1)
        r->sky_slab_dirty = 0;
}

void cu_slab_uniforms(cu_renderer *r, GLuint p)
{
    if (!r->slab_tab_tex)
        return;
    cu_gl *gl = &r->gl;
    const cu_slab_model *m = r->slab_model;
    float v[CU_SLAB_MAX_V];
    for (int i = 0; i < m->nt; i++) v[i] = (float)m->t[i];
    gl->Uniform1fv(gl->GetUniformLocation(p, "u_slab_t"), m->nt, v);
    for (int i = 0; i < m->nv; i++) v[i] = (float)m->thv[i];
    gl->Uniform1fv(gl->GetUniformLocation(p, "u_slab_thv"), m->nv, v);
    for (int i = 0; i < m->nl; i++) v[i] = (float)m->thl[i];
    gl->Uniform1fv(gl->GetUniformLocation(p, "u_slab_thl"), m->nl, v);
    for (int i = 0; i < m->np; i++) v[i] = (float)m->th[i];
    gl->Uniform1fv(gl->GetUniformLocation(p, "u_slab_th"), m->np, v);
    /* the blur in metres as a mip level of the sun-sized maps: level L averages 2^L texels of 2R / size */
    double texel = 2.0 * cu_sun_radius(&r->cloud) / r->sun_size;
    double lod = log2(fmax(r->scene.ms_blur_m / texel, 1.0));
    gl->Uniform1f(gl->GetUniformLocation(p, "u_slab_lod"), (float)lod);
    gl->Uniform1i(gl->GetUniformLocation(p, "u_slab_tab"), 4);
    gl->Uniform1i(gl->GetUniformLocation(p, "u_slab_a"), 5);
    gl->Uniform1i(gl->GetUniformLocation(p, "u_slab_n"), 6);
    gl->Uniform1i(gl->GetUniformLocation(p, "u_sky_a"), 7);
    gl->Uniform1i(gl->GetUniformLocation(p, "u_sky_n"), 8);
    gl->Uniform3f(gl->GetUniformLocation(p, "u_sky_right"), (float)r->sky_right.x, (float)r->sky_right.y,
                  (float)r->sky_right.z);
    gl->Uniform3f(gl->GetUniformLocation(p, "u_sky_up"), (float)r->sky_up.x, (float)r->sky_up.y, (float)r->sky_up.z);
    if (r->coll_tex) {
        const cu_collector *c = r->collector;
        for (int i = 0; i < c->nt; i++) v[i] = (float)c->t[i];
        gl->Uniform1fv(gl->GetUniformLocation(p, "u_coll_t"), c->nt, v);
        for (int i = 0; i < c->nl; i++) v[i] = (float)c->thl[i];
        gl->Uniform1fv(gl->GetUniformLocation(p, "u_coll_thl"), c->nl, v);
        for (int i = 0; i < c->nv; i++) v[i] = (float)c->thv[i];
        gl->Uniform1fv(gl->GetUniformLocation(p, "u_coll_thv"), c->nv, v);
        for (int i = 0; i < c->np; i++) v[i] = (float)c->phi[i];
        gl->Uniform1fv(gl->GetUniformLocation(p, "u_coll_phi"), c->np, v);
        gl->Uniform1i(gl->GetUniformLocation(p, "u_coll"), 9);
    }
}

void cu_slab_bind(cu_renderer *r)
{
    if (!r->slab_tab_tex)
        return;
    cu_gl *gl = &r->gl;
    GLuint t[6] = {r->slab_tab_tex, r->slab_a_tex[0], r->slab_n_tex[0], r->slab_a_tex[1], r->slab_n_tex[1],
                   r->coll_tex};
    for (int i = 0; i < 6; i++) {
        gl->ActiveTexture(GL_TEXTURE4 + (GLenum)i);
        gl->BindTexture(GL_TEXTURE_2D, t[i]);
    }
    gl->ActiveTexture(GL_TEXTURE0);
}
