/* src/gpu/pass_sun.c: the sun pass (see pass_sun.h): an orthographic view from the sun covering the clouds' bounds
 * (the plane at 2R along the sun direction, depths over 4R). */
#include "pass_sun.h"
#include "error.h"
#include "sunmap.h"
#include <string.h>

int cu_pass_sun_create(cu_pass_sun *p, const cu_gpu_scene *ctx, const char *hull_defs, const char *fs_defs,
                       cu_error *err)
{
    const cu_gl *gl = ctx->gl;
    const cu_scene *s = ctx->scene;
    memset(p, 0, sizeof *p);
    p->method = ctx->shadow;
    if (p->method != CU_SHADOW_FRONT) { /* peel, osm, fom: analytic full-screen passes over the map's tiles */
        const char *fs = p->method == CU_SHADOW_OSM ? "sun_osm.frag"
                         : p->method == CU_SHADOW_FOM ? "sun_fom.frag" : "sun_opacity.frag";
        p->prog = cu_gl_program(gl, "fullscreen.vert", fs, fs_defs, err);
    } else {
        p->prog = cu_gl_program(gl, "hull.vert", "sun_depth.frag", hull_defs, err);
    }
    if (!p->prog)
        return 1;
    cu_density_locs_get(gl, p->prog, &p->density);
    cu_sun_locs_get(gl, p->prog, &p->sun);
    p->viewproj = cu_gpu_loc(gl, p->prog, "u_viewproj");

    int size = ctx->sun_size;
    cu_target_desc d = {.width = size, .height = size, .format = GL_RGBA32F, .colors = 1};
    if (p->method == CU_SHADOW_PEEL) {
        /* One tile per interval, side by side, two targets written in one pass. */
        p->tiles = s->sun_intervals;
        d.name = "sun opacity map";
        d.colors = 2;
    } else if (p->method == CU_SHADOW_OSM || p->method == CU_SHADOW_FOM) {
        /* One target: tile 0 starts with the ray's depth range, then slices (osm) or coefficients (fom). */
        p->tiles = p->method == CU_SHADOW_OSM ? 1 + s->osm_slices / 4 : 1 + s->fom_coefficients / 2;
        d.name = p->method == CU_SHADOW_OSM ? "sun osm map" : "sun fom map";
        GLint most = 0;
        gl->GetIntegerv(GL_MAX_TEXTURE_SIZE, &most);
        if (size * p->tiles > most)
            return cu_fail(err, "sun map: %d tiles of %d texels exceed the largest texture (%d); lower "
                                "quality.sun_map_size", p->tiles, size, (int)most);
    } else {
        p->tiles = 1;
        d.name = "sun depth map";
        d.format = GL_DEPTH_COMPONENT32F;
    }
    d.width = size * p->tiles;
    p->map_desc = d;
    return 0;
}

int cu_pass_sun_map_create(const cu_pass_sun *p, const cu_gl *gl, int size, cu_target *map, cu_sun_maps *out,
                           cu_error *err)
{
    cu_target_desc d = p->map_desc;
    d.width = size * p->tiles;
    d.height = size;
    if (cu_target_create(map, gl, &d, err))
        return 1;
    out->map = map->tex[0];
    out->tau = map->tex[1];
    out->intervals = 0;
    return 0;
}

void cu_pass_sun_destroy(cu_pass_sun *p, const cu_gl *gl)
{
    if (p->prog)
        gl->DeleteProgram(p->prog);
    memset(p, 0, sizeof *p);
}

/* The front map: hull fragments from the sun, each writing its ellipsoid's exact entry depth. */
static void draw_front(const cu_pass_sun *p, const cu_gpu_scene *ctx, const cu_target *map)
{
    const cu_gl *gl = ctx->gl;
    double R = ctx->sun_R;
    vec3 eye = v3_scale(ctx->sun_dir, 2.0 * R);
    mat4 view = m4_look_dir(eye, v3_scale(ctx->sun_dir, -1.0), ctx->sun_up);
    mat4 proj = m4_ortho(-R, R, -R, R, 0.0, 4.0 * R);
    float vp[16];
    m4_to_float(m4_mul(proj, view), vp);
    gl->Viewport(0, 0, ctx->sun_size, ctx->sun_size);
    gl->DepthMask(GL_TRUE);
    gl->Enable(GL_DEPTH_TEST);
    gl->BindVertexArray(ctx->hull_vao);
    gl->BindFramebuffer(GL_FRAMEBUFFER, map->fbo);
    gl->ClearDepthf(1.0f);
    gl->Clear(GL_DEPTH_BUFFER_BIT);
    gl->DepthFunc(GL_LESS);
    gl->UseProgram(p->prog);
    gl->UniformMatrix4fv(p->viewproj, 1, GL_FALSE, vp);
    cu_density_uniforms(ctx, &p->density);
    cu_sun_uniforms(ctx, &p->sun);
    gl->DrawElementsInstanced(GL_TRIANGLES, ctx->hull_indices, GL_UNSIGNED_SHORT, 0, ctx->cloud->n);
    gl->BindVertexArray(0);
}

void cu_sun_band_scissor(const cu_gl *gl, const int rows[2])
{
    if (!rows) {
        gl->Disable(GL_SCISSOR_TEST);
        return;
    }
    gl->Enable(GL_SCISSOR_TEST);
    gl->Scissor(0, rows[0], 16384, rows[1] - rows[0]);
}

/* A texel outside the box costs a cast through every ellipsoid and more (llvmpipe runs a loop's first trip whether
 * or not a pixel takes it); a cumulus seen from the sun leaves much of the square empty. */
void cu_sun_map_tiles(const cu_gpu_scene *ctx, vec3 right, vec3 up, int tiles, const int rows[2],
                      const int (*boxes)[4])
{
    const cu_gl *gl = ctx->gl;
    int size = ctx->sun_size, y0 = rows ? rows[0] : 0, y1 = rows ? rows[1] : size, whole[4];
    if (!boxes)
        cu_sun_map_texels(ctx->cloud, right, up, ctx->sun_R, size, whole);
    gl->Enable(GL_SCISSOR_TEST);
    for (int j = 0; j < tiles; j++) {
        const int *box = boxes ? boxes[j] : whole;
        int b0 = box[1] > y0 ? box[1] : y0, b1 = box[3] < y1 ? box[3] : y1;
        if (b1 > b0 && box[2] > box[0]) {
            gl->Scissor(j * size + box[0], b0, box[2] - box[0], b1 - b0);
            gl->DrawArrays(GL_TRIANGLES, 0, 3);
        }
    }
    cu_sun_band_scissor(gl, rows);
}

/* The analytic maps' rows first set to what their shader writes where a ray meets no ellipsoid (peel: "no interval"
 * in every tile's layers and no optical depth; osm, fom: tile 0 the same, the other tiles zero), then the tiles
 * drawn where the cloud's shadow can fall. */
static void draw_boxed(const cu_pass_sun *p, const cu_gpu_scene *ctx, int tiles, const int rows[2],
                       const int (*boxes)[4])
{
    const cu_gl *gl = ctx->gl;
    static const GLfloat none[4] = {1e30f, 1e30f, 0.0f, 0.0f}, zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    int size = ctx->sun_size, y0 = rows ? rows[0] : 0, y1 = rows ? rows[1] : size;
    gl->Enable(GL_SCISSOR_TEST);
    if (p->method == CU_SHADOW_PEEL) {
        gl->Scissor(0, y0, size * tiles, y1 - y0);
        gl->ClearBufferfv(GL_COLOR, 0, none);
        gl->ClearBufferfv(GL_COLOR, 1, zero);
    } else {
        gl->Scissor(0, y0, size, y1 - y0);
        gl->ClearBufferfv(GL_COLOR, 0, none);
        gl->Scissor(size, y0, size * (tiles - 1), y1 - y0);
        gl->ClearBufferfv(GL_COLOR, 0, zero);
    }
    cu_sun_map_tiles(ctx, ctx->sun_right, ctx->sun_up, tiles, rows, boxes);
}

void cu_pass_sun_update(const cu_pass_sun *p, const cu_gpu_scene *ctx, const cu_target *map, const int rows[2],
                        cu_sun_maps *out)
{
    const cu_gl *gl = ctx->gl;
    gl->Disable(GL_CULL_FACE);
    gl->Disable(GL_BLEND);
    int first = !rows || rows[0] == 0, kept = out->intervals;
    out->intervals = 0;
    cu_sun_band_scissor(gl, rows);
    if (p->method == CU_SHADOW_FRONT) {
        draw_front(p, ctx, map);
        return;
    }
    int tiles = p->tiles; /* osm, fom: all tiles of their one target (no interval bookkeeping) */
    if (p->method == CU_SHADOW_PEEL && !first && kept > 0) {
        /* a later band of the same map (frame_maps.c bands it from row 0 up, one sun): the first band's count,
         * so every band fills the same tiles; 4096 sun rays cast on the CPU were most of a band's cost on it */
        tiles = out->intervals = kept;
    } else if (p->method == CU_SHADOW_PEEL) {
        /* As many interval tiles as this sun direction needs (the layer count follows the scene), capped; each
         * drawn where some texel's ray crosses that many (on the cumulus, drawn whole, the second and third
         * intervals' tiles took 15-20 % of a band's time for 1 % of its rays) */
        int most = ctx->scene->sun_intervals;
        int J = cu_sun_tile_boxes(ctx->cloud, ctx->sun_dir, ctx->sun_size, most, out->tile_box);
        tiles = out->intervals = J < 1 ? 1 : J > most ? most : J;
        if (J > most)
            cu_gpu_log(ctx, CU_LOG_INFO, "sun rays cross up to %d cloud intervals; the map keeps the first %d "
                                         "(light.sun_intervals)", J, most);
    }
    gl->BindFramebuffer(GL_FRAMEBUFFER, map->fbo);
    gl->Viewport(0, 0, ctx->sun_size * tiles, ctx->sun_size);
    gl->Disable(GL_DEPTH_TEST);
    gl->UseProgram(p->prog);
    cu_density_uniforms(ctx, &p->density);
    cu_sun_uniforms(ctx, &p->sun);
    gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_NOISE);
    gl->BindTexture(GL_TEXTURE_3D, ctx->noise_tex);
    gl->BindVertexArray(ctx->empty_vao);
    draw_boxed(p, ctx, tiles, rows, p->method == CU_SHADOW_PEEL ? (const int(*)[4])out->tile_box : NULL);
    gl->BindVertexArray(0);
}
