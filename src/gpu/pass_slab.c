/* src/gpu/pass_slab.c: the slab pass (see pass_slab.h). */
#include "pass_slab.h"
#include "pass_sun.h"
#include "collector.h"
#include "error.h"
#include "sunmap.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SLAB_SAMPLES 8 /* trapezoids per interval for the slab map's optical depth: it is blurred anyway */

static int slab_on(int ms_mode)
{
    return ms_mode == CU_MS_SLAB || ms_mode == CU_MS_COLLECTOR;
}

int cu_pass_slab_load(cu_pass_slab *p, const cu_gpu_scene *ctx, const char *dir, int *ms_mode, cu_error *err)
{
    *ms_mode = ctx->scene->ms_mode;
    if (ctx->scene->method == CU_METHOD_UNIFORM && slab_on(*ms_mode)) {
        /* the slab model fits a slab at each of Kol's intervals' entries; a uniform march has no intervals */
        cu_gpu_log(ctx, CU_LOG_INFO, "quality.method = uniform: multiple scattering by octaves (ms.mode = %s works on "
                                     "Kol's intervals)", *ms_mode == CU_MS_SLAB ? "slab" : "collector");
        *ms_mode = CU_MS_OCTAVES;
        return 0;
    }
    if (ctx->scene->method == CU_METHOD_UNIFORM && *ms_mode == CU_MS_DIFFUSION) {
        /* the grids are solved with the sun maps, which a uniform march does not make */
        cu_gpu_log(ctx, CU_LOG_INFO, "quality.method = uniform: multiple scattering by octaves (ms.mode = diffusion "
                                     "works with Kol's maps)");
        *ms_mode = CU_MS_OCTAVES;
        return 0;
    }
    if (!slab_on(*ms_mode))
        return 0;
    if (!ctx->half_rt) {
        /* RGBA16F targets (EXT_color_buffer_half_float / _float) hold the mipmapped slab maps */
        cu_gpu_log(ctx, CU_LOG_WARN, "ms.mode = slab needs half-float render targets, which this context lacks: "
                                     "using ms.mode = octaves");
        *ms_mode = CU_MS_OCTAVES;
        return 0;
    }
    if (!p->model && !(p->model = malloc(sizeof *p->model)))
        return cu_fail(err, "slab model: out of memory");
    char path[1024];
    snprintf(path, sizeof path, "%s/slab_fit_bouthors.txt", dir);
    cu_slab_transport tr;
    if (cu_slab_committed_transport(dir, &tr, err) || cu_slab_model_load(p->model, path, tr, err))
        return 1;
    if (*ms_mode != CU_MS_COLLECTOR)
        return 0;
    if (!p->collector && !(p->collector = calloc(1, sizeof *p->collector)))
        return cu_fail(err, "collector table: out of memory");
    cu_collector_free(p->collector);
    snprintf(path, sizeof path, "%s/slab_collector.txt", dir);
    return cu_collector_load(p->collector, path, err);
}

int cu_pass_slab_defines(const cu_pass_slab *p, const cu_gpu_scene *ctx, char *buf, size_t n)
{
    const cu_slab_model *m = p->model;
    const cu_scene *s = ctx->scene;
    int on = slab_on(ctx->ms_mode);
    /* sky and ground differ only under an analytic sky; a constant sky is the same from every direction */
    int split = on && s->sky_light && s->sky_model != CU_SKY_CONSTANT;
    const cu_collector *c = ctx->ms_mode == CU_MS_COLLECTOR ? p->collector : NULL;
    return snprintf(buf, n, "#define SLAB_NT %d\n#define SLAB_NV %d\n#define SLAB_NL %d\n#define SLAB_NP %d\n"
                            "#define SKY_SPLIT %d\n#define SLAB_SAMPLES %d\n#define COLL_NT %d\n#define COLL_NL %d\n"
                            "#define COLL_NV %d\n#define COLL_NP %d\n#define COLL_ITER %d\n",
                    on ? m->nt : 1, on ? m->nv : 2, on ? m->nl : 1, on ? m->np : 2, split, SLAB_SAMPLES,
                    c ? c->nt : 1, c ? c->nl : 1, c ? c->nv : 2, c ? c->np : 1, s->ms_iterations) >= (int)n;
}

/* RGBA32F with texelFetch: the fitted values span 1e-10..1e3, beyond fp16. */
static GLuint table_texture(const cu_gl *gl, int w, int h, const float *rgba)
{
    GLuint t;
    gl->GenTextures(1, &t);
    gl->BindTexture(GL_TEXTURE_2D, t);
    gl->TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, w, h, 0, GL_RGBA, GL_FLOAT, rgba);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return t;
}

int cu_pass_slab_create(cu_pass_slab *p, const cu_gpu_scene *ctx, const char *defines, cu_error *err)
{
    memset(&p->out, 0, sizeof p->out);
    if (!slab_on(ctx->ms_mode))
        return 0;
    const cu_gl *gl = ctx->gl;
    const cu_slab_model *m = p->model;
    int w = cu_slab_model_tex_width(m), h = cu_slab_model_tex_height(m);
    float *rgba = malloc(sizeof(float) * 4 * (size_t)w * (size_t)h);
    if (!rgba)
        return cu_fail(err, "slab model: out of memory");
    cu_slab_model_pack(m, rgba);
    p->tab_tex = table_texture(gl, w, h, rgba);
    free(rgba);
    if (ctx->ms_mode == CU_MS_COLLECTOR) {
        const cu_collector *c = p->collector;
        int cw = CU_COLL_ND * c->np, ch = c->nv * c->nl * c->nt;
        float *px = malloc(sizeof(float) * 4 * (size_t)cw * (size_t)ch);
        if (!px)
            return cu_fail(err, "collector table: out of memory");
        cu_collector_pack(c, px);
        p->coll_tex = table_texture(gl, cw, ch, px);
        free(px);
    }
    if (!(p->prog = cu_gl_program(gl, "fullscreen.vert", "slab_map.frag", defines, err)))
        return 1;
    cu_density_locs_get(gl, p->prog, &p->density);
    p->map_dir = cu_gpu_loc(gl, p->prog, "u_map_dir");
    p->map_right = cu_gpu_loc(gl, p->prog, "u_map_right");
    p->map_up = cu_gpu_loc(gl, p->prog, "u_map_up");
    p->map_R = cu_gpu_loc(gl, p->prog, "u_map_R");
    p->map_size = cu_gpu_loc(gl, p->prog, "u_map_size");
    p->maps = ctx->scene->sky_light && ctx->scene->sky_model != CU_SKY_CONSTANT ? 2 : 1;
    p->out.model = p->model;
    p->out.collector = ctx->ms_mode == CU_MS_COLLECTOR ? p->collector : NULL;
    p->out.tab = p->tab_tex;
    p->out.coll = p->coll_tex;
    return 0;
}

int cu_pass_slab_maps_create(const cu_pass_slab *p, const cu_gpu_scene *ctx, int size, cu_target map[2],
                             cu_slab_maps *out, cu_error *err)
{
    *out = p->out;
    if (!p->prog)
        return 0;
    for (int i = 0; i < p->maps; i++) {
        cu_target_desc d = {.name = i ? "slab map from the zenith" : "slab map from the sun",
                            .width = size, .height = size, .format = GL_RGBA16F, .colors = 2,
                            .mipmaps = 1};
        if (cu_target_create(&map[i], ctx->gl, &d, err))
            return 1;
        out->a[i] = map[i].tex[0];
        out->n[i] = map[i].tex[1];
    }
    return 0;
}

void cu_pass_slab_destroy(cu_pass_slab *p, const cu_gl *gl)
{
    if (p->tab_tex) gl->DeleteTextures(1, &p->tab_tex);
    if (p->coll_tex) gl->DeleteTextures(1, &p->coll_tex);
    if (p->prog) gl->DeleteProgram(p->prog);
    p->tab_tex = p->coll_tex = p->prog = 0;
    memset(&p->out, 0, sizeof p->out);
}

void cu_pass_slab_free(cu_pass_slab *p)
{
    free(p->model);
    if (p->collector)
        cu_collector_free(p->collector);
    free(p->collector);
    p->model = NULL;
    p->collector = NULL;
}

/* Map `which`, then its mip chain: the coverage-weighted averages the shader reads at the blur's level. */
void cu_pass_slab_update(const cu_pass_slab *p, const cu_gpu_scene *ctx, int which, const cu_target map[2],
                         const int rows[2], cu_slab_maps *out, int mipmaps)
{
    if (!map[which].fbo)
        return;
    const cu_gl *gl = ctx->gl;
    vec3 dir = which == 0 ? ctx->sun_dir : v3(0, 1, 0), right, up;
    cu_sun_basis(dir, &right, &up);
    if (which == 1) {
        out->sky_right = right;
        out->sky_up = up;
    }
    gl->BindFramebuffer(GL_FRAMEBUFFER, map[which].fbo);
    gl->Viewport(0, 0, ctx->sun_size, ctx->sun_size);
    gl->Disable(GL_DEPTH_TEST);
    gl->Disable(GL_BLEND);
    gl->UseProgram(p->prog);
    cu_density_uniforms(ctx, &p->density);
    gl->Uniform3f(p->map_dir, (float)dir.x, (float)dir.y, (float)dir.z);
    gl->Uniform3f(p->map_right, (float)right.x, (float)right.y, (float)right.z);
    gl->Uniform3f(p->map_up, (float)up.x, (float)up.y, (float)up.z);
    gl->Uniform1f(p->map_R, (float)ctx->sun_R);
    gl->Uniform1i(p->map_size, ctx->sun_size);
    gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_NOISE);
    gl->BindTexture(GL_TEXTURE_3D, ctx->noise_tex);
    gl->BindVertexArray(ctx->empty_vao);
    /* zero where a ray meets no ellipsoid (slab_map.frag), drawn only where one can */
    static const GLfloat zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    cu_sun_band_scissor(gl, rows);
    gl->ClearBufferfv(GL_COLOR, 0, zero);
    gl->ClearBufferfv(GL_COLOR, 1, zero);
    cu_sun_map_tiles(ctx, right, up, 1, rows, NULL);
    gl->BindVertexArray(0);
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    for (int i = 0; i < 2 && mipmaps; i++) {
        gl->BindTexture(GL_TEXTURE_2D, map[which].tex[i]);
        gl->GenerateMipmap(GL_TEXTURE_2D);
    }
}
