/* src/gpu/upload.c: scene data into GL objects (see upload.h). */
#include "upload.h"
#include "error.h"
#include "ms_lobe.h"
#include <stdlib.h>

int cu_upload_noise(cu_gpu_scene *ctx, const cu_noise *n, int baked_octaves, cu_error *err)
{
    const cu_gl *gl = ctx->gl;
    float *baked = NULL;
    if (baked_octaves > 0 && !(baked = malloc(sizeof(float) * CU_NOISE_SIZE * CU_NOISE_SIZE * CU_NOISE_SIZE)))
        return cu_fail(err, "noise: out of memory baking the octaves");
    gl->GenTextures(1, &ctx->noise_tex);
    gl->BindTexture(GL_TEXTURE_3D, ctx->noise_tex);
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_R, GL_REPEAT);
    gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    if (baked) {
        /* quality.noise_baked: the octaves' weighted sum at level 0 (cu_noise_bake), R16F (filterable in GLES 3.0;
         * values in [0, 2] keep 11 bits); the shader reads it twice (density.glsl, NOISE_BAKED) */
        cu_noise_bake(n, baked_octaves, baked);
        gl->TexImage3D(GL_TEXTURE_3D, 0, GL_R16F, CU_NOISE_SIZE, CU_NOISE_SIZE, CU_NOISE_SIZE, 0, GL_RED, GL_FLOAT,
                       baked);
        gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAX_LEVEL, 0);
        free(baked);
        return 0;
    }
    for (int L = 0; L < CU_NOISE_LEVELS; L++) {
        int s = CU_NOISE_SIZE >> L;
        gl->TexImage3D(GL_TEXTURE_3D, L, GL_R8, s, s, s, 0, GL_RED, GL_UNSIGNED_BYTE, n->level[L]);
    }
    /* Our own box-filtered levels (not glGenerateMipmap) so the CPU twin samples the same bytes. LINEAR within a
     * level, NEAREST between levels: the shader always asks for whole LODs (eq. 3.74). */
    gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_NEAREST);
    gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAX_LEVEL, CU_NOISE_LEVELS - 1);
    return 0;
}

int cu_upload_phase(cu_gpu_scene *ctx, const cu_phase_table *t, int lobe, cu_error *err)
{
    const cu_gl *gl = ctx->gl;
    int rows = 2 + (lobe ? CU_LOBE_ROWS : 0);
    float *rgba = calloc(4 * (size_t)rows * (size_t)t->n, sizeof(float));
    float *lt = lobe ? malloc(sizeof(float) * 3 * CU_LOBE_ROWS * (size_t)t->n) : NULL;
    /* ms.lobe in diffusion's medium (ms_diffusion.glsl's u_msd_dm): 1 - f_d of what the chop left, and g' */
    if (!rgba || (lobe && (!lt || cu_ms_lobe_table(t, (1.0 - ctx->msd_f) / (1.0 - ctx->peak_f[1]), ctx->msd_g, lt)))) {
        free(rgba);
        free(lt);
        return cu_fail(err, "phase: out of memory");
    }
    for (int i = 0; i < t->n; i++)
        for (int c = 0; c < 3; c++) {
            rgba[4 * i + c] = t->rgb[3 * i + c];
            rgba[4 * (t->n + i) + c] = t->peak ? t->peak[3 * i + c] : 0.0f;
            for (int r = 0; lt && r < CU_LOBE_ROWS; r++)
                rgba[4 * ((2 + r) * t->n + i) + c] = lt[3 * (r * t->n + i) + c];
        }
    /* RGBA32F fetched with texelFetch and interpolated in the shader: exact values, no fp16 range limit (the Mie
     * peak reaches hundreds of sr^-1), and no need for OES_texture_float_linear. */
    gl->GenTextures(1, &ctx->phase_tex);
    gl->BindTexture(GL_TEXTURE_2D, ctx->phase_tex);
    gl->TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, t->n, rows, 0, GL_RGBA, GL_FLOAT, rgba);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    free(rgba);
    free(lt);
    return 0;
}

int cu_upload_hulls(cu_gpu_scene *ctx, cu_error *err)
{
    const cu_gl *gl = ctx->gl;
    int nv, ni, tess = ctx->scene->hull_tessellation;
    cu_hull_mesh(tess, NULL, NULL, &nv, &ni);
    float *v = malloc(sizeof(float) * 3 * (size_t)nv);
    uint16_t *idx = malloc(sizeof(uint16_t) * (size_t)ni);
    if (!v || !idx) {
        free(v);
        free(idx);
        return cu_fail(err, "hulls: out of memory");
    }
    cu_hull_mesh(tess, v, idx, &nv, &ni);
    ctx->hull_indices = ni;
    gl->GenBuffers(1, &ctx->hull_vbo);
    gl->BindBuffer(GL_ARRAY_BUFFER, ctx->hull_vbo);
    gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(float) * 3 * (size_t)nv), v, GL_STATIC_DRAW);
    gl->GenBuffers(1, &ctx->hull_ibo);
    gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, ctx->hull_ibo);
    gl->BufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(sizeof(uint16_t) * (size_t)ni), idx, GL_STATIC_DRAW);
    gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
    /* Desktop core profiles need a bound VAO even for attribute-less full-screen draws. */
    gl->GenVertexArrays(1, &ctx->empty_vao);
    free(v);
    free(idx);
    return 0;
}

/* Attributes at hull.vert's layout locations: a_pos 0, a_center 1, a_radii 2 (per instance). */
void cu_upload_instances(const cu_gpu_scene *ctx, const cu_cloud *cl, GLuint *vbo, GLuint *vao)
{
    const cu_gl *gl = ctx->gl;
    float inst[CU_MAX_ELLIPSOIDS * 8];
    for (int i = 0; i < cl->n; i++) {
        inst[8 * i + 0] = (float)cl->c[i].x;
        inst[8 * i + 1] = (float)cl->c[i].y;
        inst[8 * i + 2] = (float)cl->c[i].z;
        inst[8 * i + 3] = 1;
        inst[8 * i + 4] = (float)cl->r[i].x;
        inst[8 * i + 5] = (float)cl->r[i].y;
        inst[8 * i + 6] = (float)cl->r[i].z;
        inst[8 * i + 7] = 1;
    }
    gl->GenVertexArrays(1, vao);
    gl->BindVertexArray(*vao);
    gl->BindBuffer(GL_ARRAY_BUFFER, ctx->hull_vbo);
    gl->EnableVertexAttribArray(0);
    gl->VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, 0);
    gl->GenBuffers(1, vbo);
    gl->BindBuffer(GL_ARRAY_BUFFER, *vbo);
    gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(float) * 8 * (size_t)(cl->n > 0 ? cl->n : 1)), inst,
                   GL_STATIC_DRAW);
    gl->EnableVertexAttribArray(1);
    gl->VertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, 8 * sizeof(float), 0);
    gl->VertexAttribDivisor(1, 1);
    gl->EnableVertexAttribArray(2);
    gl->VertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, 8 * sizeof(float), (const void *)(4 * sizeof(float)));
    gl->VertexAttribDivisor(2, 1);
    gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, ctx->hull_ibo);
    gl->BindVertexArray(0);
}

void cu_upload_delete(cu_gpu_scene *ctx)
{
    const cu_gl *gl = ctx->gl;
    GLuint *tex[] = {&ctx->noise_tex, &ctx->phase_tex};
    for (int i = 0; i < 2; i++)
        if (*tex[i]) {
            gl->DeleteTextures(1, tex[i]);
            *tex[i] = 0;
        }
    GLuint *bufs[] = {&ctx->hull_vbo, &ctx->hull_ibo};
    for (int i = 0; i < 2; i++)
        if (*bufs[i]) {
            gl->DeleteBuffers(1, bufs[i]);
            *bufs[i] = 0;
        }
    GLuint *vaos[] = {&ctx->empty_vao};
    for (int i = 0; i < 1; i++)
        if (*vaos[i]) {
            gl->DeleteVertexArrays(1, vaos[i]);
            *vaos[i] = 0;
        }
}
