/* src/renderer.c: renderer lifetime, scene upload (shader variants for exactly the scene's features, textures,
 * hull meshes) and the frame: sun pass, sky pass, depth pre-pass, cloud pass (GL_EQUAL), tone map. */
#include "renderer.h"
#include "collector.h"
#include "energy.h"
#include "slabmap.h"
#include "sunmap.h"
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define NOISE_SEED 20130612u /* fixed: the same clouds on every machine */

void cu_log(const cu_renderer *r, cu_log_level level, const char *fmt, ...)
{
    if (!r->desc.log)
        return;
    char buf[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    r->desc.log(r->desc.log_user, level, buf);
}

static int fail(cu_error *err, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    va_end(ap);
    return 1;
}

static void copy_gl_string(const cu_gl *gl, GLenum e, char *dst, size_t n)
{
    const char *s = (const char *)gl->GetString(e);
    snprintf(dst, n, "%s", s ? s : "?");
}

/* Probes whether an internal format can be rendered to, by building a 1x1 framebuffer with it. */
static int probe_renderable(cu_gl *gl, GLenum internal, GLenum type)
{
    GLuint tex, fbo;
    gl->GenTextures(1, &tex);
    gl->BindTexture(GL_TEXTURE_2D, tex);
    gl->TexImage2D(GL_TEXTURE_2D, 0, (GLint)internal, 1, 1, 0, GL_RGBA, type, NULL);
    gl->GenFramebuffers(1, &fbo);
    gl->BindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl->FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    int ok = gl->CheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl->DeleteFramebuffers(1, &fbo);
    gl->DeleteTextures(1, &tex);
    while (gl->GetError() != GL_NO_ERROR) {
    }
    return ok;
}

int cu_renderer_create(cu_renderer **out, const cu_desc *desc, cu_error *err)
{
    *out = NULL;
    cu_renderer *r = calloc(1, sizeof *r);
    if (!r)
        return fail(err, "renderer: out of memory");
    if (desc)
        r->desc = *desc;
    /* Resolved once, sokol-style: after this no code asks whether a data folder was given. */
    const char *dd = r->desc.data_dir ? r->desc.data_dir : cu_default_data_dir();
    if (strlen(dd) >= sizeof r->data_dir) {
        free(r);
        return fail(err, "data folder '%.64s...' is longer than %zu characters", dd, sizeof r->data_dir - 1);
    }
    snprintf(r->data_dir, sizeof r->data_dir, "%s", dd);
    r->desc.data_dir = r->data_dir;
    if (cu_gl_load(&r->gl, r->desc.get_proc_address, r->desc.get_proc_user, err)) {
        free(r);
        return 1;
    }
    cu_gl *gl = &r->gl;
    copy_gl_string(gl, GL_VENDOR, r->vendor, sizeof r->vendor);
    copy_gl_string(gl, GL_RENDERER, r->renderer_name, sizeof r->renderer_name);
    copy_gl_string(gl, GL_VERSION, r->version, sizeof r->version);
    r->is_gles = strstr(r->version, "OpenGL ES") != NULL;
    if (r->is_gles) {
        int major = 0;
        if (sscanf(r->version, "OpenGL ES %d", &major) != 1 || major < 3) {
            fail(err, "this context is '%s'; cumulo needs OpenGL ES 3.0 or later", r->version);
            free(r);
            return 1;
        }
    }
    /* GLES 3.0 core cannot render to float colour targets; EXT_color_buffer_float / _half_float add it. Desktop GL
     * (OSMesa) has it in core. We probe the real answer rather than trusting the strings alone. */
    int ext_f = !r->is_gles || cu_gl_has_extension(gl, "GL_EXT_color_buffer_float");
    int ext_h = ext_f || cu_gl_has_extension(gl, "GL_EXT_color_buffer_half_float");
    r->float_rt = ext_f && probe_renderable(gl, GL_RGBA32F, GL_FLOAT);
    r->half_rt = ext_h && probe_renderable(gl, GL_RGBA16F, GL_HALF_FLOAT);
    cu_log(r, CU_LOG_INFO, "GL: %s | %s | %s", r->vendor, r->renderer_name, r->version);
    cu_log(r, CU_LOG_INFO, "HDR target: %s", r->half_rt ? "RGBA16F (EXT_color_buffer_half_float/float)"
                                               : "RGBA8 fallback (no float colour targets: highlights clip)");
    *out = r;
    return 0;
}

const char *cu_renderer_gl_string(const cu_renderer *r, int which)
{
    return which == 0 ? r->vendor : which == 1 ? r->renderer_name : r->version;
}

static void delete_programs(cu_renderer *r)
{
    GLuint *p[] = {&r->prog_sun, &r->prog_sun_opacity, &r->prog_depth, &r->prog_cloud, &r->prog_cloud_fs, &r->prog_sky, &r->prog_tonemap,
                   &r->prog_copy};
    for (size_t i = 0; i < sizeof p / sizeof p[0]; i++)
        if (*p[i]) {
            r->gl.DeleteProgram(*p[i]);
            *p[i] = 0;
        }
}

static void delete_scene_objects(cu_renderer *r)
{
    cu_gl *gl = &r->gl;
    cu_energy_delete(r);
    delete_programs(r);
    cu_slab_delete(r);
    GLuint tex[] = {r->noise_tex, r->phase_tex, r->sun_tex, r->hdr_tex, r->sun_layers_tex, r->sun_tau_tex};
    for (size_t i = 0; i < sizeof tex / sizeof tex[0]; i++)
        if (tex[i])
            gl->DeleteTextures(1, &tex[i]);
    r->noise_tex = r->phase_tex = r->sun_tex = r->hdr_tex = r->sun_layers_tex = r->sun_tau_tex = 0;
    if (r->sun_opacity_fbo) gl->DeleteFramebuffers(1, &r->sun_opacity_fbo);
    r->sun_opacity_fbo = 0;
    if (r->sun_fbo) gl->DeleteFramebuffers(1, &r->sun_fbo);
    if (r->hdr_fbo) gl->DeleteFramebuffers(1, &r->hdr_fbo);
    if (r->hdr_depth) gl->DeleteRenderbuffers(1, &r->hdr_depth);
    r->sun_fbo = r->hdr_fbo = r->hdr_depth = 0;
    r->hdr_w = r->hdr_h = 0;
    GLuint bufs[] = {r->hull_vbo, r->hull_ibo, r->inst_vbo};
    for (size_t i = 0; i < 3; i++)
        if (bufs[i])
            gl->DeleteBuffers(1, &bufs[i]);
    r->hull_vbo = r->hull_ibo = r->inst_vbo = 0;
    if (r->hull_vao) gl->DeleteVertexArrays(1, &r->hull_vao);
    if (r->empty_vao) gl->DeleteVertexArrays(1, &r->empty_vao);
    r->hull_vao = r->empty_vao = 0;
}

void cu_renderer_destroy(cu_renderer *r)
{
    if (!r)
        return;
    delete_scene_objects(r);
    if (r->noise_ready)
        cu_noise_destroy(&r->noise);
    free(r->slab_model);
    if (r->collector)
        cu_collector_free(r->collector);
    free(r->collector);
    free(r);
}

static int upload_noise(cu_renderer *r, cu_error *err)
{
    cu_gl *gl = &r->gl;
    if (!r->noise_ready) {
        if (cu_noise_create(&r->noise, NOISE_SEED))
            return fail(err, "noise: out of memory");
        r->noise_ready = 1;
    }
    gl->GenTextures(1, &r->noise_tex);
    gl->BindTexture(GL_TEXTURE_3D, r->noise_tex);
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int L = 0; L < CU_NOISE_LEVELS; L++) {
        int s = CU_NOISE_SIZE >> L;
        gl->TexImage3D(GL_TEXTURE_3D, L, GL_R8, s, s, s, 0, GL_RED, GL_UNSIGNED_BYTE, r->noise.level[L]);
    }
    /* Our own box-filtered levels (not glGenerateMipmap) so the CPU twin samples the same bytes. LINEAR within a
     * level, NEAREST between levels: the shader always asks for whole LODs (eq. 3.74). */
    gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_NEAREST);
    gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_R, GL_REPEAT);
    gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAX_LEVEL, CU_NOISE_LEVELS - 1);
    return 0;
}

static int upload_phase(cu_renderer *r, cu_error *err)
{
    cu_gl *gl = &r->gl;
    cu_phase_table t;
    if (cu_phase_table_build(&t, &r->scene, r->data_dir, err))
        return 1;

    for (int c = 0; c < 3; c++)
        r->peak_f[c] = t.f[c];
    cu_energy_phase_weights(r, &t);
    r->cloud.ke = cu_phase_table_extinction(&t, &r->scene); /* the table's sigma_ext wins (DESIGN.md) */
    float *rgba = calloc(4 * 2 * (size_t)t.n, sizeof(float));
    if (!rgba) {
        cu_phase_table_free(&t);
        return fail(err, "phase: out of memory");
    }
    for (int i = 0; i < t.n; i++)
        for (int c = 0; c < 3; c++) {
            rgba[4 * i + c] = t.rgb[3 * i + c];
            rgba[4 * (t.n + i) + c] = t.peak ? t.peak[3 * i + c] : 0.0f;
        }
    /* Row 0: the (chopped) phase function, row 1: the removed peak. RGBA32F fetched with texelFetch and interpolated
     * in the shader: exact values, no fp16 range limit (the Mie peak reaches hundreds of sr^-1), and no need for
     * OES_texture_float_linear. */
    gl->GenTextures(1, &r->phase_tex);
    gl->BindTexture(GL_TEXTURE_2D, r->phase_tex);
    gl->TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, t.n, 2, 0, GL_RGBA, GL_FLOAT, rgba);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    free(rgba);
    cu_phase_table_free(&t);
    return 0;
}

static void upload_hulls(cu_renderer *r)
{
    cu_gl *gl = &r->gl;
    int nv, ni, tess = r->scene.hull_tessellation;
    cu_hull_mesh(tess, NULL, NULL, &nv, &ni);
    float *v = malloc(sizeof(float) * 3 * (size_t)nv);
    uint16_t *idx = malloc(sizeof(uint16_t) * (size_t)ni);
    cu_hull_mesh(tess, v, idx, &nv, &ni);
    r->hull_indices = ni;
    float inst[CU_MAX_ELLIPSOIDS * 8];
    for (int i = 0; i < r->cloud.n; i++) {
        inst[8 * i + 0] = (float)r->cloud.c[i].x;
        inst[8 * i + 1] = (float)r->cloud.c[i].y;
        inst[8 * i + 2] = (float)r->cloud.c[i].z;
        inst[8 * i + 3] = 1;
        inst[8 * i + 4] = (float)r->cloud.r[i].x;
        inst[8 * i + 5] = (float)r->cloud.r[i].y;
        inst[8 * i + 6] = (float)r->cloud.r[i].z;
        inst[8 * i + 7] = 1;
    }
    gl->GenVertexArrays(1, &r->hull_vao);
    gl->BindVertexArray(r->hull_vao);
    gl->GenBuffers(1, &r->hull_vbo);
    gl->BindBuffer(GL_ARRAY_BUFFER, r->hull_vbo);
    gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(float) * 3 * (size_t)nv), v, GL_STATIC_DRAW);
    gl->EnableVertexAttribArray(0);
    gl->VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, 0);
    gl->GenBuffers(1, &r->inst_vbo);
    gl->BindBuffer(GL_ARRAY_BUFFER, r->inst_vbo);
    gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(float) * 8 * (size_t)r->cloud.n), inst, GL_STATIC_DRAW);
    gl->EnableVertexAttribArray(1);
    gl->VertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, 8 * sizeof(float), 0);
    gl->VertexAttribDivisor(1, 1);
    gl->EnableVertexAttribArray(2);
    gl->VertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, 8 * sizeof(float), (const void *)(4 * sizeof(float)));
    gl->VertexAttribDivisor(2, 1);
    gl->GenBuffers(1, &r->hull_ibo);
    gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, r->hull_ibo);
    gl->BufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(sizeof(uint16_t) * (size_t)ni), idx, GL_STATIC_DRAW);
    gl->BindVertexArray(0);
    /* Desktop core profiles need a bound VAO even for attribute-less full-screen draws. */
    gl->GenVertexArrays(1, &r->empty_vao);
    free(v);
    free(idx);
}

/* Attribute locations are fixed with layout-free binding order: a_pos 0, a_center 1, a_radii 2. */
static GLuint hull_program(cu_renderer *r, const char *fs, const char *defines, cu_error *err)
{
    GLuint p = cu_gl_program(&r->gl, "hull.vert", fs, defines, err);
    return p;
}

static int build_programs(cu_renderer *r, cu_error *err)
{
    const cu_scene *s = &r->scene;
    char defs[1400];
    /* Model only what the scene requires: counts and features are compile-time constants. */
    int n = snprintf(defs, sizeof defs,
             "#define NUM_ELL %d\n#define SEGMENTS %d\n#define MAX_INTERVALS %d\n#define NOISE %d\n"
             "#define NOISE_OCTAVES %d\n#define PROFILE_KOL %d\n#define MS_MODE %d\n#define MS_OCTAVES %d\n"
             "#define SKY_CONSTANT %d\n#define PHASE_PEAK %d\n#define SHADOW_PEEL %d\n#define SUN_INTERVALS %d\n"
             "#define SUN_FILTER %d\n#define SUN_SAMPLES %d\n#define INTEGRATION_KOL %d\n"
             "#define SHADOW_METHOD %d\n#define OSM_SLICES %d\n#define FOM_COEFFS %d\n",
             s->n_ellipsoids, s->segments, s->max_intervals, s->noise ? 1 : 0, s->noise_octaves,
             s->profile == CU_PROFILE_KOL, r->ms_mode, r->ms_mode == CU_MS_OCTAVES ? s->ms_octaves : 1,
             s->sky_model == CU_SKY_CONSTANT, s->phase == CU_PHASE_MIE, r->shadow == CU_SHADOW_PEEL, s->sun_intervals,
             s->sun_filter, s->sun_samples, s->integration, r->shadow, s->osm_slices, s->fom_coefficients);
    if (n < 0 || cu_slab_defines(r, defs + n, sizeof defs - (size_t)n))
        return fail(err, "shader defines too long");
    char fs_defs[1500], hull_defs[1500], lin[1500];
    snprintf(hull_defs, sizeof hull_defs, "%s#define FULLSCREEN 0\n#define LINEAR_OUTPUT 0\n", defs);
    snprintf(fs_defs, sizeof fs_defs, "%s#define FULLSCREEN 1\n#define LINEAR_OUTPUT 0\n", defs);
    snprintf(lin, sizeof lin, "%s#define FULLSCREEN 1\n#define LINEAR_OUTPUT 1\n", defs);
    if (cu_slab_targets(r, fs_defs, err))
        return 1;
    if (r->shadow != CU_SHADOW_FRONT) { /* peel, osm, fom: analytic fullscreen passes over the map's tiles */
        const char *fs = r->shadow == CU_SHADOW_OSM ? "sun_osm.frag"
                         : r->shadow == CU_SHADOW_FOM ? "sun_fom.frag" : "sun_opacity.frag";
        if (!(r->prog_sun_opacity = cu_gl_program(&r->gl, "fullscreen.vert", fs, fs_defs, err)))
            return 1;
    } else if (!(r->prog_sun = hull_program(r, "sun_depth.frag", hull_defs, err))) {
        return 1;
    }
    if (
        !(r->prog_depth = hull_program(r, "depth.frag", hull_defs, err)) ||
        !(r->prog_cloud = hull_program(r, "cloud.frag", hull_defs, err)) ||
        !(r->prog_cloud_fs = cu_gl_program(&r->gl, "fullscreen.vert", "cloud.frag", fs_defs, err)) ||
        cu_energy_init(r, fs_defs, err) ||
        !(r->prog_sky = cu_gl_program(&r->gl, "fullscreen.vert", "sky.frag", fs_defs, err)) ||
        !(r->prog_tonemap = cu_gl_program(&r->gl, "fullscreen.vert", "tonemap.frag", fs_defs, err)) ||
        !(r->prog_copy = cu_gl_program(&r->gl, "fullscreen.vert", "tonemap.frag", lin, err)))
        return 1;
    return 0;
}

static int make_depth_target(cu_renderer *r, GLuint *tex, GLuint *fbo, cu_error *err)
{
    cu_gl *gl = &r->gl;
    gl->GenTextures(1, tex);
    gl->BindTexture(GL_TEXTURE_2D, *tex);
    gl->TexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, r->sun_size, r->sun_size, 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                   NULL);
    /* Depth textures are not filterable in GLES 3.0 without comparison: NEAREST. */
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    gl->GenFramebuffers(1, fbo);
    gl->BindFramebuffer(GL_FRAMEBUFFER, *fbo);
    gl->FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, *tex, 0);
    GLenum none = GL_NONE;
    gl->DrawBuffers(1, &none);
    GLenum st = gl->CheckFramebufferStatus(GL_FRAMEBUFFER);
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    if (st != GL_FRAMEBUFFER_COMPLETE)
        return fail(err, "sun map: depth framebuffer incomplete (0x%x)", st);
    return 0;
}

static GLuint make_float_texture(cu_gl *gl, int w, int h)
{
    GLuint t;
    gl->GenTextures(1, &t);
    gl->BindTexture(GL_TEXTURE_2D, t);
    gl->TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, w, h, 0, GL_RGBA, GL_FLOAT, NULL);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return t;
}

static int make_sun_map(cu_renderer *r, cu_error *err)
{
    cu_gl *gl = &r->gl;
    if (r->shadow == CU_SHADOW_PEEL) {
        /* The opacity map: one tile per interval, side by side, two RGBA32F targets written in one pass. */
        int w = r->sun_size * r->scene.sun_intervals, h = r->sun_size;
        r->sun_layers_tex = make_float_texture(gl, w, h);
        r->sun_tau_tex = make_float_texture(gl, w, h);
        gl->GenFramebuffers(1, &r->sun_opacity_fbo);
        gl->BindFramebuffer(GL_FRAMEBUFFER, r->sun_opacity_fbo);
        gl->FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, r->sun_layers_tex, 0);
        gl->FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, r->sun_tau_tex, 0);
        GLenum bufs[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
        gl->DrawBuffers(2, bufs);
        GLenum st = gl->CheckFramebufferStatus(GL_FRAMEBUFFER);
        gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
        if (st != GL_FRAMEBUFFER_COMPLETE)
            return fail(err, "sun opacity map: framebuffer incomplete (0x%x)", st);
        return 0;
    }
    if (r->shadow == CU_SHADOW_OSM || r->shadow == CU_SHADOW_FOM) {
        /* One RGBA32F target: tile 0 starts with the ray's depth range, then slices (osm) or coefficients (fom). */
        r->sun_map_tiles = r->shadow == CU_SHADOW_OSM ? 1 + r->scene.osm_slices / 4
                                                      : 1 + r->scene.fom_coefficients / 2;
        GLint most = 0;
        gl->GetIntegerv(GL_MAX_TEXTURE_SIZE, &most);
        if (r->sun_size * r->sun_map_tiles > most)
            return fail(err, "sun map: %d tiles of %d texels exceed the largest texture (%d); lower "
                             "quality.sun_map_size", r->sun_map_tiles, r->sun_size, (int)most);
        r->sun_tex = make_float_texture(gl, r->sun_size * r->sun_map_tiles, r->sun_size);
        gl->GenFramebuffers(1, &r->sun_fbo);
        gl->BindFramebuffer(GL_FRAMEBUFFER, r->sun_fbo);
        gl->FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, r->sun_tex, 0);
        GLenum buf = GL_COLOR_ATTACHMENT0;
        gl->DrawBuffers(1, &buf);
        GLenum st = gl->CheckFramebufferStatus(GL_FRAMEBUFFER);
        gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
        if (st != GL_FRAMEBUFFER_COMPLETE)
            return fail(err, "sun %s map: framebuffer incomplete (0x%x)", r->shadow == CU_SHADOW_OSM ? "osm" : "fom",
                        st);
        return 0;
    }
    return make_depth_target(r, &r->sun_tex, &r->sun_fbo, err);
}

int cu_renderer_set_scene(cu_renderer *r, const cu_scene *s, cu_error *err)
{
    delete_scene_objects(r);
    r->scene = *s;
    r->has_scene = 0;
    if (upload_noise(r, err))
        return 1;
    cu_cloud_build(&r->cloud, &r->scene, &r->noise);
    cu_sky_compute(&r->sky, &r->scene);
    r->shadow = r->scene.shadow;
    if (r->shadow != CU_SHADOW_FRONT && !r->float_rt) {
        /* The opacity maps need float colour targets (EXT_color_buffer_float); without them Kol's estimate. */
        cu_log(r, CU_LOG_WARN, "light.shadow = %s needs float render targets, which this context lacks: "
                               "using the front-depth estimate", r->shadow == CU_SHADOW_OSM ? "osm"
                               : r->shadow == CU_SHADOW_FOM ? "fom" : "peel");
        r->shadow = CU_SHADOW_FRONT;
    }
    cu_sky_white_balance(&r->scene, r->white);
    r->sun_size = r->scene.sun_map_size;
    if (upload_phase(r, err) || cu_slab_load(r, err) || build_programs(r, err) || make_sun_map(r, err))
        return 1;
    upload_hulls(r);
    r->sun_dirty = 1;
    r->has_scene = 1;
    GLenum e = r->gl.GetError();
    if (e != GL_NO_ERROR)
        return fail(err, "GL error 0x%x while uploading the scene", e);
    return 0;
}

int cu_renderer_set_sun(cu_renderer *r, double elevation_deg, double azimuth_deg, cu_error *err)
{
    if (!isfinite(elevation_deg) || !isfinite(azimuth_deg) || elevation_deg < -90 || elevation_deg > 90)
        return fail(err, "sun: elevation must be in [-90, 90] and both angles finite");
    r->scene.sun_elevation = elevation_deg;
    r->scene.sun_azimuth = fmod(azimuth_deg, 360.0);
    if (r->scene.sun_azimuth < 0)
        r->scene.sun_azimuth += 360.0;
    cu_sky_compute(&r->sky, &r->scene);
    r->sun_dirty = 1;
    return 0;
}

double cu_renderer_ms_gain(const cu_renderer *r, int transmitted)
{
    return r->ms_gain[transmitted ? 1 : 0];
}

void cu_renderer_get_sun(const cu_renderer *r, double *el, double *az)
{
    *el = r->scene.sun_elevation;
    *az = r->scene.sun_azimuth;
}

static void set_ellipsoid_uniforms(cu_renderer *r, GLuint p)
{
    cu_gl *gl = &r->gl;
    float c[CU_MAX_ELLIPSOIDS * 4], ir[CU_MAX_ELLIPSOIDS * 4];
    for (int i = 0; i < r->cloud.n; i++) {
        c[4 * i] = (float)r->cloud.c[i].x;
        c[4 * i + 1] = (float)r->cloud.c[i].y;
        c[4 * i + 2] = (float)r->cloud.c[i].z;
        c[4 * i + 3] = 0;
        ir[4 * i] = (float)(1.0 / r->cloud.r[i].x);
        ir[4 * i + 1] = (float)(1.0 / r->cloud.r[i].y);
        ir[4 * i + 2] = (float)(1.0 / r->cloud.r[i].z);
        ir[4 * i + 3] = 0;
    }
    gl->Uniform4fv(gl->GetUniformLocation(p, "u_ell_c"), r->cloud.n, c);
    gl->Uniform4fv(gl->GetUniformLocation(p, "u_ell_ir"), r->cloud.n, ir);
}

static void sun_basis(const cu_renderer *r, vec3 *right, vec3 *up)
{
    cu_sun_basis(r->sky.sun_dir, right, up);
}

static double sun_R(const cu_renderer *r)
{
    return cu_sun_radius(&r->cloud);
}

void cu_set_density_uniforms(cu_renderer *r, GLuint p)
{
    cu_gl *gl = &r->gl;
    set_ellipsoid_uniforms(r, p);
    gl->Uniform1f(gl->GetUniformLocation(p, "u_ke"), (float)r->cloud.ke);
    gl->Uniform1f(gl->GetUniformLocation(p, "u_h"), (float)(r->cloud.h > 1e-6 ? r->cloud.h : 1e-6));
    gl->Uniform1f(gl->GetUniformLocation(p, "u_noise_freq"), (float)r->cloud.noise_freq);
    gl->Uniform3f(gl->GetUniformLocation(p, "u_noise_offset"), (float)r->cloud.noise_offset.x,
                  (float)r->cloud.noise_offset.y, (float)r->cloud.noise_offset.z);
    float means[5];
    for (int i = 0; i < 5; i++)
        means[i] = (float)r->noise.level_mean[i];
    gl->Uniform1fv(gl->GetUniformLocation(p, "u_noise_mean"), 5, means);
    gl->Uniform1i(gl->GetUniformLocation(p, "u_noise"), 0);
}

/* Uniforms of sunmap.glsl (and the opacity pass): the sun-space frame and the maps' texture units 2 and 3. */
static void set_sun_uniforms(cu_renderer *r, GLuint p)
{
    cu_gl *gl = &r->gl;
    vec3 sd = r->sky.sun_dir;
    gl->Uniform3f(gl->GetUniformLocation(p, "u_sun_dir"), (float)sd.x, (float)sd.y, (float)sd.z);
    gl->Uniform3f(gl->GetUniformLocation(p, "u_sun_right"), (float)r->sun_right.x, (float)r->sun_right.y,
                  (float)r->sun_right.z);
    gl->Uniform3f(gl->GetUniformLocation(p, "u_sun_up"), (float)r->sun_up.x, (float)r->sun_up.y, (float)r->sun_up.z);
    gl->Uniform1f(gl->GetUniformLocation(p, "u_sun_R"), (float)sun_R(r));
    gl->Uniform1i(gl->GetUniformLocation(p, "u_sun_size"), r->sun_size);
    gl->Uniform1i(gl->GetUniformLocation(p, "u_sun_intervals"), r->sun_intervals);
    gl->Uniform1i(gl->GetUniformLocation(p, "u_sun_layers"), 2);
    gl->Uniform1i(gl->GetUniformLocation(p, "u_sun_tau"), 3);
    gl->Uniform1i(gl->GetUniformLocation(p, "u_sun_depth"), 2);
    gl->Uniform1i(gl->GetUniformLocation(p, "u_sun_map"), 2);
}

static void shadow_pass(cu_renderer *r)
{
    cu_gl *gl = &r->gl;
    double R = sun_R(r);
    if (r->shadow == CU_SHADOW_OSM || r->shadow == CU_SHADOW_FOM) {
        /* One pass over all tiles of their single target (fixed tile count: no interval bookkeeping). */
        gl->BindFramebuffer(GL_FRAMEBUFFER, r->sun_fbo);
        gl->Viewport(0, 0, r->sun_size * r->sun_map_tiles, r->sun_size);
    } else if (r->shadow == CU_SHADOW_PEEL) {
        /* As many interval tiles as this sun direction needs (the layer count follows the scene), capped. */
        int J = cu_sun_max_intervals(&r->cloud, r->sky.sun_dir, 64);
        r->sun_intervals = J < 1 ? 1 : J > r->scene.sun_intervals ? r->scene.sun_intervals : J;
        if (J > r->scene.sun_intervals)
            cu_log(r, CU_LOG_INFO, "sun rays cross up to %d cloud intervals; the map keeps the first %d "
                                   "(light.sun_intervals)", J, r->scene.sun_intervals);
        gl->BindFramebuffer(GL_FRAMEBUFFER, r->sun_opacity_fbo);
        gl->Viewport(0, 0, r->sun_size * r->sun_intervals, r->sun_size);
    }
    if (r->shadow != CU_SHADOW_FRONT) {
        GLuint p = r->prog_sun_opacity;
        gl->Disable(GL_DEPTH_TEST);
        gl->UseProgram(p);
        cu_set_density_uniforms(r, p);
        set_sun_uniforms(r, p);
        gl->ActiveTexture(GL_TEXTURE0);
        gl->BindTexture(GL_TEXTURE_3D, r->noise_tex);
        gl->BindVertexArray(r->empty_vao);
        gl->DrawArrays(GL_TRIANGLES, 0, 3);
        gl->BindVertexArray(0);
        return;
    }
    vec3 eye = v3_scale(r->sky.sun_dir, 2.0 * R);
    mat4 view = m4_look_dir(eye, v3_scale(r->sky.sun_dir, -1.0), r->sun_up);
    mat4 proj = m4_ortho(-R, R, -R, R, 0.0, 4.0 * R);
    float vp[16];
    m4_to_float(m4_mul(proj, view), vp);
    gl->Viewport(0, 0, r->sun_size, r->sun_size);
    gl->DepthMask(GL_TRUE);
    gl->Enable(GL_DEPTH_TEST);
    gl->BindVertexArray(r->hull_vao);
    GLuint prog = r->prog_sun;
    gl->BindFramebuffer(GL_FRAMEBUFFER, r->sun_fbo);
    gl->ClearDepthf(1.0f);
    gl->Clear(GL_DEPTH_BUFFER_BIT);
    gl->DepthFunc(GL_LESS);
    gl->UseProgram(prog);
    gl->UniformMatrix4fv(gl->GetUniformLocation(prog, "u_viewproj"), 1, GL_FALSE, vp);
    set_ellipsoid_uniforms(r, prog);
    gl->Uniform3f(gl->GetUniformLocation(prog, "u_sun_dir"), (float)r->sky.sun_dir.x, (float)r->sky.sun_dir.y,
                  (float)r->sky.sun_dir.z);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_sun_R"), (float)R);
    gl->DrawElementsInstanced(GL_TRIANGLES, r->hull_indices, GL_UNSIGNED_SHORT, 0, r->cloud.n);
    gl->BindVertexArray(0);
}

/* Everything seen from the sun: redone only when the sun or the clouds change. The zenith slab map depends on the
 * clouds alone. */
static void sun_pass(cu_renderer *r)
{
    cu_gl *gl = &r->gl;
    sun_basis(r, &r->sun_right, &r->sun_up);
    gl->Disable(GL_CULL_FACE);
    gl->Disable(GL_BLEND);
    shadow_pass(r);
    cu_slab_render(r, 0);
    if (r->sky_slab_dirty)
        cu_slab_render(r, 1);
    r->sun_dirty = 0;
}

static int ensure_hdr(cu_renderer *r, int w, int h, int linear, cu_error *err)
{
    cu_gl *gl = &r->gl;
    GLenum want;
    if (linear) {
        if (!r->float_rt)
            return fail(err, "linear output needs a float colour target (EXT_color_buffer_float), which this "
                             "context lacks");
        want = GL_RGBA32F;
    } else {
        want = r->half_rt ? GL_RGBA16F : GL_RGBA8;
    }
    if (r->hdr_fbo && r->hdr_w == w && r->hdr_h == h && r->hdr_format == want)
        return 0;
    if (r->hdr_tex) gl->DeleteTextures(1, &r->hdr_tex);
    if (r->hdr_depth) gl->DeleteRenderbuffers(1, &r->hdr_depth);
    if (r->hdr_fbo) gl->DeleteFramebuffers(1, &r->hdr_fbo);
    gl->GenTextures(1, &r->hdr_tex);
    gl->BindTexture(GL_TEXTURE_2D, r->hdr_tex);
    GLenum type = want == GL_RGBA32F ? GL_FLOAT : want == GL_RGBA16F ? GL_HALF_FLOAT : GL_UNSIGNED_BYTE;
    gl->TexImage2D(GL_TEXTURE_2D, 0, (GLint)want, w, h, 0, GL_RGBA, type, NULL);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl->GenRenderbuffers(1, &r->hdr_depth);
    gl->BindRenderbuffer(GL_RENDERBUFFER, r->hdr_depth);
    gl->RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, w, h);
    gl->GenFramebuffers(1, &r->hdr_fbo);
    gl->BindFramebuffer(GL_FRAMEBUFFER, r->hdr_fbo);
    gl->FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, r->hdr_tex, 0);
    gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, r->hdr_depth);
    GLenum st = gl->CheckFramebufferStatus(GL_FRAMEBUFFER);
    if (st != GL_FRAMEBUFFER_COMPLETE)
        return fail(err, "HDR framebuffer incomplete (0x%x)", st);
    r->hdr_w = w;
    r->hdr_h = h;
    r->hdr_format = want;
    return 0;
}

/* Is the camera inside (or within the near plane of) some hull? Then hull rasterisation would miss pixels, and the
 * cloud pass runs on a full-screen triangle instead (Kol 3.4.4, "rendering from inside"). */
static int camera_inside_hull(const cu_renderer *r, vec3 cam, double znear)
{
    double k = cu_hull_scale(r->scene.hull_tessellation);
    for (int i = 0; i < r->cloud.n; i++) {
        vec3 rr = v3_scale(r->cloud.r[i], k);
        double rmin = fmin(rr.x, fmin(rr.y, rr.z));
        vec3 q = v3_sub(cam, r->cloud.c[i]);
        double s = v3_len(v3(q.x / rr.x, q.y / rr.y, q.z / rr.z));
        if (s <= 1.0 + 4.0 * znear / rmin)
            return 1;
    }
    return 0;
}

/* What the sky and cloud passes multiply their radiance by. A float HDR target stores radiance and the tone mapper
 * applies exposure and white balance; an RGBA8 target (GLES 3.0 without EXT_color_buffer_*float) holds only 0..1,
 * so there the passes store exposed, white-balanced values and the tone mapper gets 1 and 1: highlights beyond the
 * display's white clip, the rest is as with a float target. (Storing radiance, as before, clipped the whole sky to
 * 1 and the picture came out one flat grey.) */
static void out_scale(const cu_renderer *r, float s[3])
{
    for (int c = 0; c < 3; c++)
        s[c] = r->hdr_format == GL_RGBA8 ? (float)(r->scene.exposure / r->white[c]) : 1.0f;
}

void cu_set_cloud_uniforms(cu_renderer *r, GLuint p, vec3 cam, const float *vp, const float *inv_vp)
{
    cu_gl *gl = &r->gl;
    const cu_scene *s = &r->scene;
    gl->UseProgram(p);
    gl->UniformMatrix4fv(gl->GetUniformLocation(p, "u_viewproj"), 1, GL_FALSE, vp);
    gl->UniformMatrix4fv(gl->GetUniformLocation(p, "u_inv_viewproj"), 1, GL_FALSE, inv_vp);
    gl->Uniform3f(gl->GetUniformLocation(p, "u_cam"), (float)cam.x, (float)cam.y, (float)cam.z);
    gl->Uniform1f(gl->GetUniformLocation(p, "u_bound_R"), (float)r->cloud.bound_radius);
    cu_set_density_uniforms(r, p);
    set_sun_uniforms(r, p);
    gl->Uniform1f(gl->GetUniformLocation(p, "u_seg_ratio"), (float)s->segment_ratio);
    gl->Uniform1i(gl->GetUniformLocation(p, "u_phase"), 1);
    gl->Uniform1i(gl->GetUniformLocation(p, "u_phase_n"), CU_PHASE_N);
    gl->Uniform3f(gl->GetUniformLocation(p, "u_sun_irr"), (float)r->sky.sun_irradiance[0],
                  (float)r->sky.sun_irradiance[1], (float)r->sky.sun_irradiance[2]);
    double amb = s->sky_light ? 1.0 : 0.0;
    gl->Uniform3f(gl->GetUniformLocation(p, "u_sky_rad"), (float)(amb * r->sky.sky_mean[0]),
                  (float)(amb * r->sky.sky_mean[1]), (float)(amb * r->sky.sky_mean[2]));
    gl->Uniform3f(gl->GetUniformLocation(p, "u_ground_rad"), (float)(amb * r->sky.ground_mean[0]),
                  (float)(amb * r->sky.ground_mean[1]), (float)(amb * r->sky.ground_mean[2]));
    cu_slab_uniforms(r, p);
    gl->Uniform3f(gl->GetUniformLocation(p, "u_ms_abc"), (float)s->ms_a, (float)s->ms_b, (float)s->ms_c);
    gl->Uniform1f(gl->GetUniformLocation(p, "u_ms_g"), (float)(s->phase_g));
    gl->Uniform3f(gl->GetUniformLocation(p, "u_peak_f"), (float)r->peak_f[0], (float)r->peak_f[1],
                  (float)r->peak_f[2]);
    gl->Uniform2f(gl->GetUniformLocation(p, "u_ms_gain"), (float)r->ms_gain[0], (float)r->ms_gain[1]);
    float os[3];
    out_scale(r, os);
    gl->Uniform3f(gl->GetUniformLocation(p, "u_out_scale"), os[0], os[1], os[2]);
}

void cu_bind_cloud_textures(cu_renderer *r)
{
    cu_gl *gl = &r->gl;
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindTexture(GL_TEXTURE_3D, r->noise_tex);
    gl->ActiveTexture(GL_TEXTURE1);
    gl->BindTexture(GL_TEXTURE_2D, r->phase_tex);
    gl->ActiveTexture(GL_TEXTURE2);
    gl->BindTexture(GL_TEXTURE_2D, r->shadow == CU_SHADOW_PEEL ? r->sun_layers_tex : r->sun_tex);
    gl->ActiveTexture(GL_TEXTURE3);
    gl->BindTexture(GL_TEXTURE_2D, r->shadow == CU_SHADOW_PEEL ? r->sun_tau_tex : 0);
    gl->ActiveTexture(GL_TEXTURE0);
    cu_slab_bind(r);
}

int cu_render(cu_renderer *r, const cu_frame *f, cu_error *err)
{
    if (!r->has_scene)
        return fail(err, "render: no scene set");
    if (f->width < 1 || f->height < 1 || f->width > 16384 || f->height > 16384)
        return fail(err, "render: bad frame size %dx%d", f->width, f->height);
    cu_gl *gl = &r->gl;
    const cu_scene *s = &r->scene;
    while (gl->GetError() != GL_NO_ERROR) {
    }
    if (ensure_hdr(r, f->width, f->height, f->linear, err))
        return 1;
    if (r->sun_dirty) {
        sun_pass(r);
        cu_bind_cloud_textures(r);
        cu_energy_update(r); /* the closure's views need the new sun and slab maps (redone when the sun moved 1 deg) */
    }

    /* Camera in cloud-local coordinates: the big world offset is removed in double precision on the CPU. */
    vec3 cam = v3_sub(v3_from(s->cam_pos), r->cloud.origin);
    vec3 dir = v3_norm(v3_sub(v3_from(s->cam_look), v3_from(s->cam_pos)));
    double dist = v3_len(cam);
    double zfar = dist + r->cloud.bound_radius * cu_hull_scale(s->hull_tessellation) * 1.05 + 10.0;
    /* Near plane as far out as the clouds allow: depth precision ~ z^2 / (near 2^24). */
    double hull_r = r->cloud.bound_radius * cu_hull_scale(s->hull_tessellation);
    double znear = fmax(0.05, 0.5 * (dist - hull_r));
    mat4 view = m4_look_dir(cam, dir, v3(0, 1, 0));
    mat4 proj = m4_perspective(s->cam_fov * CU_PI / 180.0, (double)f->width / f->height, znear, zfar);
    mat4 vp_m = m4_mul(proj, view);
    float vp[16], inv_vp[16], inv_rot[16];
    m4_to_float(vp_m, vp);
    m4_to_float(m4_inverse(vp_m), inv_vp);
    /* The sky only needs directions: the camera at the origin and fixed clip planes, so the sky does not depend on
     * where the clouds are (an empty scene is bit-for-bit the sky). */
    mat4 proj_dir = m4_perspective(s->cam_fov * CU_PI / 180.0, (double)f->width / f->height, 1.0, 2.0);
    m4_to_float(m4_inverse(m4_mul(proj_dir, m4_look_dir(v3(0, 0, 0), dir, v3(0, 1, 0)))), inv_rot);

    gl->BindFramebuffer(GL_FRAMEBUFFER, r->hdr_fbo);
    gl->Viewport(0, 0, f->width, f->height);
    gl->Disable(GL_CULL_FACE); /* back faces matter when the camera is inside an ellipsoid */
    gl->Disable(GL_BLEND);
    gl->DepthMask(GL_TRUE);
    gl->ClearDepthf(1.0f);
    gl->ClearStencil(0);
    gl->Clear(GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);

    /* Sky pass. */
    gl->Disable(GL_DEPTH_TEST);
    gl->UseProgram(r->prog_sky);
    gl->UniformMatrix4fv(gl->GetUniformLocation(r->prog_sky, "u_inv_viewproj"), 1, GL_FALSE, inv_rot);
    vec3 sd = r->sky.sun_dir;
    gl->Uniform3f(gl->GetUniformLocation(r->prog_sky, "u_sun_dir"), (float)sd.x, (float)sd.y, (float)sd.z);
    gl->Uniform3f(gl->GetUniformLocation(r->prog_sky, "u_sun_irr"), (float)r->sky.sun_irradiance[0],
                  (float)r->sky.sun_irradiance[1], (float)r->sky.sun_irradiance[2]);
    gl->Uniform1f(gl->GetUniformLocation(r->prog_sky, "u_sun_disk_max"),
                  r->hdr_format == GL_RGBA32F ? 1e30f : r->hdr_format == GL_RGBA16F ? 60000.0f : 1e4f);
    gl->Uniform3f(gl->GetUniformLocation(r->prog_sky, "u_ground"), (float)r->sky.ground[0], (float)r->sky.ground[1],
                  (float)r->sky.ground[2]);
    float os[3];
    out_scale(r, os);
    gl->Uniform3f(gl->GetUniformLocation(r->prog_sky, "u_out_scale"), os[0], os[1], os[2]);
    if (s->sky_model == CU_SKY_CONSTANT) {
        gl->Uniform3f(gl->GetUniformLocation(r->prog_sky, "u_sky_color"), (float)s->sky_color[0],
                      (float)s->sky_color[1], (float)s->sky_color[2]);
    } else {
        float pz[15];
        for (int i = 0; i < 15; i++)
            pz[i] = (float)r->sky.perez[i];
        gl->Uniform1fv(gl->GetUniformLocation(r->prog_sky, "u_perez"), 15, pz);
        gl->Uniform3f(gl->GetUniformLocation(r->prog_sky, "u_zenith"), (float)r->sky.zenith[0],
                      (float)r->sky.zenith[1], (float)r->sky.zenith[2]);
        gl->Uniform3f(gl->GetUniformLocation(r->prog_sky, "u_norm"), (float)r->sky.norm[0], (float)r->sky.norm[1],
                      (float)r->sky.norm[2]);
    }
    gl->BindVertexArray(r->empty_vao);
    gl->DrawArrays(GL_TRIANGLES, 0, 3);

    /* Cloud: textures. */
    cu_bind_cloud_textures(r);

    int inside = camera_inside_hull(r, cam, znear);
    if (r->cloud.ke > 0) { /* zero density cannot change a pixel: skip the cloud passes */
        gl->Enable(GL_BLEND);
        gl->BlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA); /* premultiplied over the sky */
        if (inside) {
            gl->Disable(GL_DEPTH_TEST);
            cu_set_cloud_uniforms(r, r->prog_cloud_fs, cam, vp, inv_vp);
            gl->BindVertexArray(r->empty_vao);
            gl->DrawArrays(GL_TRIANGLES, 0, 3);
        } else {
            /* Depth pre-pass (Kol 3.4.2): the nearest hull fragment per pixel, no colour. */
            gl->Disable(GL_BLEND);
            gl->Enable(GL_DEPTH_TEST);
            gl->DepthFunc(GL_LESS);
            gl->ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
            gl->UseProgram(r->prog_depth);
            gl->UniformMatrix4fv(gl->GetUniformLocation(r->prog_depth, "u_viewproj"), 1, GL_FALSE, vp);
            gl->BindVertexArray(r->hull_vao);
            gl->DrawElementsInstanced(GL_TRIANGLES, r->hull_indices, GL_UNSIGNED_SHORT, 0, r->cloud.n);
            /* Cloud pass: only the fragment that won the depth test is shaded. Where two hulls' depths are equal
             * to the depth buffer's precision, both would pass GL_EQUAL and blend the whole ray twice; the stencil
             * lets the first of them through and no other (the shader integrates the whole ray, so any one will
             * do). */
            gl->ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
            gl->Enable(GL_BLEND);
            gl->DepthFunc(GL_EQUAL);
            gl->DepthMask(GL_FALSE);
            gl->Enable(GL_STENCIL_TEST);
            gl->StencilFunc(GL_EQUAL, 0, 0xff);
            gl->StencilOp(GL_KEEP, GL_KEEP, GL_INCR);
            cu_set_cloud_uniforms(r, r->prog_cloud, cam, vp, inv_vp);
            gl->DrawElementsInstanced(GL_TRIANGLES, r->hull_indices, GL_UNSIGNED_SHORT, 0, r->cloud.n);
            gl->Disable(GL_STENCIL_TEST);
            gl->DepthMask(GL_TRUE);
            gl->DepthFunc(GL_LESS);
        }
        gl->Disable(GL_BLEND);
    }

    /* Final pass into the caller's framebuffer. */
    gl->Disable(GL_DEPTH_TEST);
    gl->BindFramebuffer(GL_FRAMEBUFFER, f->fbo);
    gl->Viewport(0, 0, f->width, f->height);
    GLuint fp = f->linear ? r->prog_copy : r->prog_tonemap;
    gl->UseProgram(fp);
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindTexture(GL_TEXTURE_2D, r->hdr_tex);
    gl->Uniform1i(gl->GetUniformLocation(fp, "u_hdr"), 0);
    int pre = r->hdr_format == GL_RGBA8; /* the passes applied exposure and white already (out_scale) */
    gl->Uniform1f(gl->GetUniformLocation(fp, "u_exposure"), pre ? 1.0f : (float)s->exposure);
    gl->Uniform3f(gl->GetUniformLocation(fp, "u_white"), pre ? 1.0f : (float)r->white[0], pre ? 1.0f : (float)r->white[1],
                  pre ? 1.0f : (float)r->white[2]);
    gl->BindVertexArray(r->empty_vao);
    gl->DrawArrays(GL_TRIANGLES, 0, 3);
    gl->BindVertexArray(0);
    GLenum e = gl->GetError();
    if (e != GL_NO_ERROR)
        return fail(err, "render: GL error 0x%x", e);
    return 0;
}
