/* src/gpu/renderer.c: renderer lifetime, scene upload (shader variants for exactly the scene's features) and the
 * frame: it creates the passes, orders them (sun, slab maps, energy closure; sky, depth and cloud; tone map) and
 * tracks what is dirty (the sun moved, the scene changed, the frame's size changed). */
#include "renderer.h"
#include "camera.h"
#include "error.h"
#include "glstate.h"
#include "scene_camera.h"
#include "scene_sun.h"
#include "upload.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define NOISE_SEED 20130612u /* fixed: the same clouds on every machine */

static void copy_gl_string(const cu_gl *gl, GLenum e, char *dst, size_t n)
{
    const char *s = (const char *)gl->GetString(e);
    snprintf(dst, n, "%s", s ? s : "?");
}

/* Probes whether an internal format can be rendered to, by building a 1x1 target with it. */
static int probe_renderable(const cu_gl *gl, GLenum internal)
{
    cu_target t;
    cu_error e;
    cu_target_desc d = {.name = "probe", .width = 1, .height = 1, .format = internal, .colors = 1};
    int ok = cu_target_create(&t, gl, &d, &e) == 0;
    cu_target_delete(&t, gl);
    while (gl->GetError() != GL_NO_ERROR) {
    }
    return ok;
}

int cu_renderer_create(cu_renderer **out, const cu_desc *desc, cu_error *err)
{
    *out = NULL;
    cu_renderer *r = calloc(1, sizeof *r);
    if (!r)
        return cu_fail(err, "renderer: out of memory");
    if (desc)
        r->desc = *desc;
    /* Resolved once, sokol-style: after this no code asks whether a data folder was given. */
    const char *dd = r->desc.data_dir ? r->desc.data_dir : cu_default_data_dir();
    if (strlen(dd) >= sizeof r->data_dir) {
        free(r);
        return cu_fail(err, "data folder '%.64s...' is longer than %zu characters", dd, sizeof r->data_dir - 1);
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
            cu_fail(err, "this context is '%s'; cumulo needs OpenGL ES 3.0 or later", r->version);
            free(r);
            return 1;
        }
    }
    cu_gpu_scene *ctx = &r->ctx;
    ctx->gl = gl;
    ctx->log = r->desc.log;
    ctx->log_user = r->desc.log_user;
    ctx->scene = &r->scene;
    ctx->cloud = &r->none;
    ctx->ke_scale = 1;
    ctx->num_ell = 1;
    ctx->sky = &r->sky;
    ctx->noise = &r->noise;
    /* GLES 3.0 core cannot render to float colour targets; EXT_color_buffer_float / _half_float add it. Desktop GL
     * (OSMesa) has it in core. We probe the real answer rather than trusting the strings alone. */
    int ext_f = !r->is_gles || cu_gl_has_extension(gl, "GL_EXT_color_buffer_float");
    int ext_h = ext_f || cu_gl_has_extension(gl, "GL_EXT_color_buffer_half_float");
    cu_glstate st;
    cu_glstate_enter(gl, &st);
    ctx->float_rt = ext_f && probe_renderable(gl, GL_RGBA32F);
    ctx->half_rt = ext_h && probe_renderable(gl, GL_RGBA16F);
    cu_glstate_leave(gl, &st);
    cu_gpu_log(ctx, CU_LOG_INFO, "GL: %s | %s | %s", r->vendor, r->renderer_name, r->version);
    cu_gpu_log(ctx, CU_LOG_INFO, "HDR target: %s", ctx->half_rt ? "RGBA16F (EXT_color_buffer_half_float/float)"
                                           : "RGBA8 fallback (no float colour targets: highlights clip)");
    *out = r;
    return 0;
}

const char *cu_renderer_gl_string(const cu_renderer *r, int which)
{
    return which == 0 ? r->vendor : which == 1 ? r->renderer_name : r->version;
}

static void delete_scene_objects(cu_renderer *r)
{
    const cu_gl *gl = &r->gl;
    cu_pass_energy_destroy(&r->pass_energy, gl);
    cu_pass_sun_destroy(&r->pass_sun, gl);
    cu_pass_cloud_destroy(&r->pass_cloud, gl);
    cu_pass_sky_destroy(&r->pass_sky, gl);
    cu_pass_tonemap_destroy(&r->pass_tonemap, gl);
    cu_pass_slab_destroy(&r->pass_slab, gl);
    cu_pass_shadow_destroy(&r->pass_shadow, gl);
    cu_target_delete(&r->ground, gl);
    r->ground_sig = 0;
    cu_cloud_set_free(&r->clouds, gl);
    free(r->order);
    free(r->order_key);
    free(r->cams);
    r->order = NULL;
    r->order_key = NULL;
    r->cams = NULL;
    cu_upload_delete(&r->ctx);
    r->ctx.cloud = &r->none;
    r->ctx.hull_vao = 0;
    memset(&r->ctx.sun, 0, sizeof r->ctx.sun);
    memset(&r->ctx.slab, 0, sizeof r->ctx.slab);
}

void cu_renderer_destroy(cu_renderer *r)
{
    if (!r)
        return;
    delete_scene_objects(r);
    if (r->noise_ready)
        cu_noise_destroy(&r->noise);
    cu_pass_slab_free(&r->pass_slab);
    free(r);
}

/* The shader variant of the scene: only what it uses is compiled, counts and features as constants. Full-screen
 * (FULLSCREEN 1) and hull programs differ in how a fragment finds its ray; LINEAR_OUTPUT picks the tone map's copy. */
typedef struct shader_defs {
    char hull[1500], fs[1500], linear[1500];
} shader_defs;

static int build_defines(const cu_renderer *r, shader_defs *d, cu_error *err)
{
    const cu_scene *s = &r->scene;
    const cu_gpu_scene *c = &r->ctx;
    char defs[1400];
    int n = snprintf(defs, sizeof defs,
             "#define NUM_ELL %d\n#define SEGMENTS %d\n#define MAX_INTERVALS %d\n#define NOISE %d\n"
             "#define NOISE_OCTAVES %d\n#define PROFILE_KOL %d\n#define MS_MODE %d\n#define MS_OCTAVES %d\n"
             "#define SKY_CONSTANT %d\n#define PHASE_PEAK %d\n#define SHADOW_PEEL %d\n#define SUN_INTERVALS %d\n"
             "#define SUN_FILTER %d\n#define SUN_SAMPLES %d\n#define INTEGRATION_KOL %d\n"
             "#define SHADOW_METHOD %d\n#define OSM_SLICES %d\n#define FOM_COEFFS %d\n#define EXT_SHADOW %d\n"
             "#define GROUND_SHADOW %d\n",
             c->num_ell, s->segments, s->max_intervals, s->noise ? 1 : 0, s->noise_octaves,
             s->profile == CU_PROFILE_KOL, c->ms_mode, c->ms_mode == CU_MS_OCTAVES ? s->ms_octaves : 1,
             s->sky_model == CU_SKY_CONSTANT, s->phase == CU_PHASE_MIE, c->shadow == CU_SHADOW_PEEL, s->sun_intervals,
             s->sun_filter, s->sun_samples, s->integration, c->shadow, s->osm_slices, s->fom_coefficients,
             r->shadows && r->clouds.n > 1, r->shadows && s->sky_model != CU_SKY_CONSTANT);
    if (n < 0 || n >= (int)sizeof defs ||
        cu_pass_slab_defines(&r->pass_slab, c, defs + n, sizeof defs - (size_t)n))
        return cu_fail(err, "shader defines too long");
    snprintf(d->hull, sizeof d->hull, "%s#define FULLSCREEN 0\n#define LINEAR_OUTPUT 0\n", defs);
    snprintf(d->fs, sizeof d->fs, "%s#define FULLSCREEN 1\n#define LINEAR_OUTPUT 0\n", defs);
    snprintf(d->linear, sizeof d->linear, "%s#define FULLSCREEN 1\n#define LINEAR_OUTPUT 1\n", defs);
    return 0;
}

static int create_passes(cu_renderer *r, const cu_phase_table *phase, cu_error *err)
{
    cu_gpu_scene *ctx = &r->ctx;
    shader_defs d;
    if (build_defines(r, &d, err) || cu_pass_slab_create(&r->pass_slab, ctx, d.fs, err))
        return 1;
    if (cu_pass_sun_create(&r->pass_sun, ctx, d.hull, d.fs, err) ||
        cu_pass_cloud_create(&r->pass_cloud, ctx, d.hull, d.fs, err) ||
        cu_pass_energy_create(&r->pass_energy, ctx, phase, d.fs, err) ||
        cu_pass_sky_create(&r->pass_sky, ctx, d.fs, err) ||
        cu_pass_tonemap_create(&r->pass_tonemap, ctx, d.fs, d.linear, err) ||
        (r->shadows && cu_pass_shadow_create(&r->pass_shadow, ctx, d.fs, err)))
        return 1;
    ctx->sun_ext = r->pass_shadow.zero_tex;
    ctx->ground_tau = r->pass_shadow.zero_tex;
    ctx->ms_gain[0] = r->pass_energy.gain[0];
    ctx->ms_gain[1] = r->pass_energy.gain[1];
    return 0;
}

static int set_scene(cu_renderer *r, const cu_scene *s, cu_error *err)
{
    cu_gpu_scene *ctx = &r->ctx;
    delete_scene_objects(r);
    r->scene = *s;
    r->has_scene = 0;
    if (!r->noise_ready) {
        if (cu_noise_create(&r->noise, NOISE_SEED))
            return cu_fail(err, "noise: out of memory");
        r->noise_ready = 1;
    }
    cu_upload_noise(ctx, &r->noise);
    if (cu_cloud_set_build(&r->clouds, &r->scene, &r->noise, err))
        return 1;
    r->time = r->scene.time;
    size_t n = (size_t)(r->clouds.n > 0 ? r->clouds.n : 1);
    r->order = malloc(sizeof *r->order * n);
    r->order_key = malloc(sizeof *r->order_key * n);
    r->cams = malloc(sizeof *r->cams * n);
    if (!r->order || !r->order_key || !r->cams)
        return cu_fail(err, "clouds: out of memory");
    ctx->num_ell = r->clouds.num_ell;
    /* Shadows of clouds on clouds and on the ground: what blendable half-float targets allow (else a log line). */
    r->shadows = r->clouds.n > 0 && ctx->half_rt;
    if (r->clouds.n > 0 && !ctx->half_rt)
        cu_gpu_log(ctx, CU_LOG_WARN, "no half-float render targets: clouds cast no shadows on each other or the "
                                     "ground");
    if (cu_scene_sun_at(&r->scene, r->time, &r->scene.sun_elevation, &r->scene.sun_azimuth, err))
        return 1;
    memset(&r->none, 0, sizeof r->none);
    ctx->cloud = &r->none;
    cu_sky_compute(&r->sky, &r->scene);
    ctx->shadow = r->scene.shadow;
    if (ctx->shadow != CU_SHADOW_FRONT && !ctx->float_rt) {
        /* The opacity maps need float colour targets (EXT_color_buffer_float); without them Kol's estimate. */
        cu_gpu_log(ctx, CU_LOG_WARN, "light.shadow = %s needs float render targets, which this context lacks: "
                                     "using the front-depth estimate", ctx->shadow == CU_SHADOW_OSM ? "osm"
                                     : ctx->shadow == CU_SHADOW_FOM ? "fom" : "peel");
        ctx->shadow = CU_SHADOW_FRONT;
    }
    cu_sky_white_balance(&r->scene, ctx->white);
    ctx->sun_size = r->scene.sun_map_size;
    cu_gpu_scene_set_sun(ctx);

    cu_phase_table t;
    if (cu_phase_table_build(&t, &r->scene, r->data_dir, err))
        return 1;
    for (int c = 0; c < 3; c++)
        ctx->peak_f[c] = t.f[c];
    /* The table's sigma_ext wins (DESIGN.md): every cloud's core extinction, scaled from the droplets' 2 pi r_e^2. */
    double sigma_geo = cu_scene_extinction_at(&r->scene, 1.0); /* m^-1 per cm^-3; r_e > 0, so > 0 */
    double sigma = t.sigma_ext_um2[1] > 0 ? 1e6 * t.sigma_ext_um2[1] * 1e-12 : sigma_geo;
    for (int i = 0; i < r->clouds.n; i++) {
        cu_cloud_slot *sl = &r->clouds.slot[i];
        sl->ke_rest = sigma_geo > 0 ? sl->ke_rest * (sigma / sigma_geo) : 0;
        sl->cloud.ke = sl->ke_rest;
    }
    int rc = cu_upload_phase(ctx, &t, err) || cu_pass_slab_load(&r->pass_slab, ctx, r->data_dir, &ctx->ms_mode, err) ||
             create_passes(r, &t, err) || cu_upload_hulls(ctx, err);
    cu_phase_table_free(&t);
    if (rc)
        return 1;
    r->sun_dirty = 1;
    r->has_scene = 1;
    GLenum e = r->gl.GetError();
    if (e != GL_NO_ERROR)
        return cu_fail(err, "GL error 0x%x while uploading the scene", e);
    return 0;
}

int cu_renderer_set_scene(cu_renderer *r, const cu_scene *s, cu_error *err)
{
    cu_glstate st;
    cu_glstate_enter(&r->gl, &st);
    int rc = set_scene(r, s, err);
    cu_glstate_leave(&r->gl, &st);
    return rc;
}

int cu_renderer_set_sun(cu_renderer *r, double elevation_deg, double azimuth_deg, cu_error *err)
{
    if (!isfinite(elevation_deg) || !isfinite(azimuth_deg) || elevation_deg < -90 || elevation_deg > 90)
        return cu_fail(err, "sun: elevation must be in [-90, 90] and both angles finite");
    r->scene.has_time_utc = 0; /* the angles given win; set_sun_utc follows a clock again */
    r->scene.sun_elevation = elevation_deg;
    r->scene.sun_azimuth = fmod(azimuth_deg, 360.0);
    if (r->scene.sun_azimuth < 0)
        r->scene.sun_azimuth += 360.0;
    cu_sky_compute(&r->sky, &r->scene);
    r->sun_dirty = 1; /* each cloud's maps follow by themselves (cloud_maps compares their sun) */
    return 0;
}

double cu_renderer_ms_gain(const cu_renderer *r, int transmitted)
{
    return r->pass_energy.gain[transmitted ? 1 : 0];
}

void cu_renderer_get_sun(const cu_renderer *r, double *el, double *az)
{
    *el = r->scene.sun_elevation;
    *az = r->scene.sun_azimuth;
}

/* Points the frame context at cloud i: what the passes read of "the cloud". */
static void bind_cloud(cu_renderer *r, cu_cloud_slot *sl)
{
    cu_gpu_scene *ctx = &r->ctx;
    ctx->cloud = &sl->cloud;
    ctx->hull_vao = sl->vao;
    ctx->sun = sl->sun;
    ctx->slab = sl->slab;
    ctx->ke_scale = sl->factor;
    ctx->sun_ext = sl->has_shadow ? sl->shadow.tex[0] : r->pass_shadow.zero_tex;
    ctx->sun_size = sl->map_size > 0 ? sl->map_size : r->scene.sun_map_size;
    cu_gpu_scene_set_sun(ctx);
}

/* A cloud's GL objects, made the first time it is drawn: a field of thousands of clouds pays for the ones seen. */
static int cloud_objects(cu_renderer *r, cu_cloud_slot *sl, cu_error *err)
{
    cu_gpu_scene *ctx = &r->ctx;
    if (!sl->vao)
        cu_upload_instances(ctx, &sl->cloud, &sl->inst_vbo, &sl->vao);
    if (sl->has_maps && sl->want_size <= sl->map_size)
        return 0; /* maps only grow: a cloud that recedes keeps its sharper maps (no churn at a size boundary) */
    if (sl->has_maps)
        cu_cloud_slot_free_maps(sl, &r->gl);
    sl->map_size = sl->want_size;
    if (cu_pass_sun_map_create(&r->pass_sun, &r->gl, sl->map_size, &sl->sun_map, &sl->sun, err) ||
        cu_pass_slab_maps_create(&r->pass_slab, ctx, sl->map_size, sl->slab_map, &sl->slab, err))
        return 1;
    sl->has_maps = 1;
    return 0;
}

/* The level of detail of a cloud's maps in a field: about a texel per two pixels the cloud covers on screen, a power
 * of two from 16 up to quality.sun_map_size. A lone cloud always gets quality.sun_map_size. */
static int map_size_for(const cu_renderer *r, const cu_camera *c, mat4 proj, double radius, int height)
{
    int most = r->scene.sun_map_size, size = 16;
    if (r->clouds.n == 1 || most <= 16)
        return most;
    double py = fabs(proj.m[5]);
    double d = c->ortho ? 1.0 : fmax(v3_len(c->pos), radius);
    double pixels = radius * py * height / d; /* the cloud's diameter on screen */
    while (size < most && size < 0.5 * pixels)
        size *= 2;
    return size < most ? size : most;
}

/* Cloud sl's maps seen from the sun (and the zenith), remade when the sun moved or the cloud took a new look; made
 * at its mature density (ke_scale 1): the shaders scale the optical depths they read by the density now. */
static int cloud_maps(cu_renderer *r, cu_cloud_slot *sl, cu_error *err)
{
    cu_gpu_scene *ctx = &r->ctx;
    if (cloud_objects(r, sl, err))
        return 1;
    if (sl->maps_valid && v3_dot(sl->maps_sun, ctx->sky->sun_dir) > 1.0 - 1e-12 && sl->zenith_valid)
        return 0;
    double f = sl->factor;
    sl->factor = 1;
    bind_cloud(r, sl);
    sl->cloud.ke = sl->ke_rest;
    cu_pass_sun_update(&r->pass_sun, ctx, &sl->sun_map, &sl->sun);
    ctx->sun = sl->sun;
    cu_pass_slab_update(&r->pass_slab, ctx, 0, sl->slab_map, &sl->slab);
    if (!sl->zenith_valid)
        cu_pass_slab_update(&r->pass_slab, ctx, 1, sl->slab_map, &sl->slab);
    sl->zenith_valid = 1;
    sl->maps_valid = 1;
    sl->maps_sun = ctx->sky->sun_dir;
    sl->factor = f;
    return 0;
}

/* The frame's view and projection: the host's matrices, or the scene's [camera] through exactly the float matrices
 * cu_scene_camera_matrices gives a host, so both are one image by construction (camera.c replaces the depth
 * planes, so the ones asked for here do not matter). */
static int frame_matrices(const cu_renderer *r, const cu_frame *f, mat4 *view, mat4 *proj, cu_error *err)
{
    float v[16], p[16];
    if (!f->view) {
        if (cu_scene_camera_matrices(&r->scene, (double)f->width / f->height, 1.0, 2.0, v, p, err))
            return 1;
        *view = cu_camera_mat4(v);
        *proj = cu_camera_mat4(p);
        return 0;
    }
    *view = cu_camera_mat4(f->view);
    *proj = cu_camera_mat4(f->projection);
    return 0;
}

static int check_frame(const cu_frame *f, cu_error *err)
{
    if (f->width < 1 || f->height < 1 || f->width > 16384 || f->height > 16384)
        return cu_fail(err, "render: bad frame size %dx%d", f->width, f->height);
    if (!f->view != !f->projection)
        return cu_fail(err, "render: cu_frame.view and .projection are given together or not at all");
    return 0;
}

/* The clouds this frame sees (frustum-culled on each cloud's own bounds; dissolved and zero-density clouds cannot
 * change a pixel), each with its camera, sorted back to front (Kol Ch. 4: "OpenGL taking care of blending by
 * rendering them in a back-to-front order"). Returns how many. */
static int visible_clouds(cu_renderer *r, mat4 view, mat4 proj, cu_error *err)
{
    int n = 0;
    double k = cu_hull_scale(r->scene.hull_tessellation);
    for (int i = 0; i < r->clouds.n; i++) {
        cu_cloud_slot *sl = &r->clouds.slot[i];
        if (!(sl->factor * sl->ke_rest > 0) || sl->cloud.n == 0)
            continue;
        cu_camera *c = &r->cams[i];
        if (cu_camera_build(c, view, proj, sl->cloud.origin, sl->cloud.bound_radius * k, err))
            return -1;
        if (!c->visible)
            continue;
        sl->want_size = map_size_for(r, c, proj, sl->cloud.bound_radius, r->ctx.height);
        /* perspective: the eye's distance from the cloud's centre (pos is cloud-local); orthographic: how far along
         * the view direction the centre lies */
        r->order_key[i] = c->ortho ? v3_dot(sl->cloud.origin, c->view_dir) : v3_dot(c->pos, c->pos);
        r->order[n++] = i;
    }
    /* insertion sort by decreasing distance: the order changes little from frame to frame */
    for (int a = 1; a < n; a++) {
        int v = r->order[a], b = a;
        while (b > 0 && r->order_key[r->order[b - 1]] < r->order_key[v]) {
            r->order[b] = r->order[b - 1];
            b--;
        }
        r->order[b] = v;
    }
    return n;
}

/* The energy closure's gains: one pair for the scene (a field of clouds shares it, pass_energy.c), measured on the
 * largest cloud in view. */
static void energy_closure(cu_renderer *r, int visible)
{
    int best = -1;
    for (int j = 0; j < visible; j++) {
        int i = r->order[j];
        if (best < 0 || r->clouds.slot[i].cloud.bound_radius > r->clouds.slot[best].cloud.bound_radius)
            best = i;
    }
    if (best < 0)
        return;
    cu_cloud_slot *sl = &r->clouds.slot[best];
    double f = sl->factor;
    sl->factor = 1;
    bind_cloud(r, sl);
    r->ctx.sun_ext = r->pass_shadow.zero_tex; /* the cloud's own budget, as if alone */
    cu_pass_energy_update(&r->pass_energy, &r->ctx);
    sl->factor = f;
    r->ctx.ms_gain[0] = r->pass_energy.gain[0];
    r->ctx.ms_gain[1] = r->pass_energy.gain[1];
    r->sun_dirty = 0;
}

/* FNV-1a over what a shadow map depends on, so it is remade only when that changed. */
static uint64_t sig_add(uint64_t h, double v)
{
    int64_t q = (int64_t)llround(v);
    for (int i = 0; i < 8; i++) {
        h ^= (uint64_t)(q >> (8 * i)) & 0xff;
        h *= 1099511628211ull;
    }
    return h;
}

/* The texels [x0, x1) x [y0, y1) of a size-texel map of half-side R about 0 that a disc of radius rad at (u, v)
 * (metres on the map's axes) covers. */
static void disc_rect(double u, double v, double rad, double R, int size, int rect[4])
{
    double k = 0.5 * size / R, cu = (u / R * 0.5 + 0.5) * size, cv = (v / R * 0.5 + 0.5) * size;
    rect[0] = (int)fmax(0, floor(cu - rad * k) - 1);
    rect[1] = (int)fmax(0, floor(cv - rad * k) - 1);
    rect[2] = (int)fmin(size, ceil(cu + rad * k) + 1);
    rect[3] = (int)fmin(size, ceil(cv + rad * k) + 1);
}

/* Cloud i's shadow from the others: the casters are the clouds nearer the sun whose discs seen from the sun overlap
 * its own (for clouds that do not interpenetrate, every sun ray meets a caster before this cloud); their optical
 * depths along the sun add up over its sun-map square. Remade when the casters, their densities, their offsets or
 * the sun changed. */
static int cloud_shadow(cu_renderer *r, int i, cu_error *err)
{
    cu_gpu_scene *ctx = &r->ctx;
    cu_cloud_slot *sl = &r->clouds.slot[i];
    sl->has_shadow = 0;
    if (!r->shadows || r->clouds.n < 2)
        return 0;
    bind_cloud(r, sl);
    vec3 sd = ctx->sun_dir, rt = ctx->sun_right, up = ctx->sun_up;
    double Ri = ctx->sun_R;
    uint64_t sig = 1469598103934665603ull;
    sig = sig_add(sig_add(sig_add(sig, 1e6 * sd.x), 1e6 * sd.y), 1e6 * sd.z);
    int casters = 0;
    for (int j = 0; j < r->clouds.n; j++) {
        const cu_cloud_slot *c = &r->clouds.slot[j];
        if (j == i || c->cloud.n == 0 || !(c->factor * c->ke_rest > 0))
            continue;
        vec3 d = v3_sub(c->cloud.origin, sl->cloud.origin);
        double along = v3_dot(d, sd), Rj = c->cloud.bound_radius;
        vec3 perp = v3_sub(d, v3_scale(sd, along));
        if (along <= 0 || v3_len(perp) > sl->cloud.bound_radius + Rj)
            continue;
        casters++;
        sig = sig_add(sig_add(sig, j), 64.0 * c->factor);
        sig = sig_add(sig_add(sig_add(sig, 4.0 * d.x), 4.0 * d.y), 4.0 * d.z);
    }
    if (casters == 0)
        return 0;
    int size = sl->map_size / 2 > 16 ? sl->map_size / 2 : 16;
    if (sl->shadow.fbo && sl->shadow.width != size)
        cu_target_delete(&sl->shadow, &r->gl);
    if (!sl->shadow.fbo && cu_pass_shadow_target(&r->gl, size, &sl->shadow, err))
        return 1;
    sl->has_shadow = 1;
    if (sig == sl->shadow_sig)
        return 0;
    sl->shadow_sig = sig;
    cu_pass_shadow_begin(&r->pass_shadow, ctx, &sl->shadow, size);
    for (int j = 0; j < r->clouds.n; j++) {
        const cu_cloud_slot *c = &r->clouds.slot[j];
        if (j == i || c->cloud.n == 0 || !(c->factor * c->ke_rest > 0))
            continue;
        vec3 d = v3_sub(c->cloud.origin, sl->cloud.origin);
        double along = v3_dot(d, sd), Rj = c->cloud.bound_radius;
        vec3 perp = v3_sub(d, v3_scale(sd, along));
        if (along <= 0 || v3_len(perp) > sl->cloud.bound_radius + Rj)
            continue;
        /* texel (u, v): the point of cloud i's map plane, in j's frame, moved toward the sun before j */
        vec3 o = v3_add(v3_scale(d, -1.0), v3_scale(sd, along + Rj + 1.0));
        int rect[4];
        disc_rect(v3_dot(d, rt), v3_dot(d, up), Rj, Ri, size, rect);
        cu_pass_shadow_add(&r->pass_shadow, ctx, &c->cloud, c->ke_rest * c->factor, o, v3_scale(rt, Ri),
                           v3_scale(up, Ri), size, rect);
    }
    cu_pass_shadow_end(ctx);
    return 0;
}

/* The clouds' shadow on the ground: their optical depth toward the sun over a square about the camera (its side
 * grows with the camera's height; shadows farther away lie within a fraction of a degree of the horizon), remade
 * when the clouds, the sun or the square moved. */
static int ground_shadow(cu_renderer *r, cu_error *err)
{
    cu_gpu_scene *ctx = &r->ctx;
    ctx->ground_tau = r->pass_shadow.zero_tex;
    ctx->ground_map = v3(0, 0, 1);
    vec3 sd = ctx->sky->sun_dir, eye = ctx->camera.pos;
    if (!r->shadows || r->scene.sky_model == CU_SKY_CONSTANT || sd.y < 0.02 || ctx->camera.ortho || eye.y <= 0)
        return 0;
    const int size = 512;
    double S = fmin(fmax(40.0 * eye.y + 4000.0, 4000.0), 60000.0), snap = S / 16;
    vec3 c = v3(snap * floor(eye.x / snap + 0.5), 0, snap * floor(eye.z / snap + 0.5));
    uint64_t sig = 1469598103934665603ull;
    sig = sig_add(sig_add(sig_add(sig_add(sig, 1e6 * sd.x), 1e6 * sd.y), 1e6 * sd.z), c.x);
    sig = sig_add(sig_add(sig, c.z), S);
    for (int j = 0; j < r->clouds.n; j++) {
        const cu_cloud_slot *cl = &r->clouds.slot[j];
        sig = sig_add(sig_add(sig_add(sig_add(sig, 64.0 * cl->factor), 4.0 * cl->cloud.origin.x), 4.0 * cl->cloud.origin.y),
                      4.0 * cl->cloud.origin.z);
    }
    if (!r->ground.fbo && cu_pass_shadow_target(&r->gl, size, &r->ground, err))
        return 1;
    ctx->ground_tau = r->ground.tex[0];
    ctx->ground_map = v3(c.x, c.z, S);
    if (sig == r->ground_sig)
        return 0;
    r->ground_sig = sig;
    cu_gpu_scene_set_sun(ctx);
    cu_pass_shadow_begin(&r->pass_shadow, ctx, &r->ground, size);
    for (int j = 0; j < r->clouds.n; j++) {
        const cu_cloud_slot *cl = &r->clouds.slot[j];
        if (cl->cloud.n == 0 || !(cl->factor * cl->ke_rest > 0))
            continue;
        vec3 o = cl->cloud.origin;
        double Rj = cl->cloud.bound_radius, D = (o.y + Rj) / sd.y + 1.0;
        /* where its centre's shadow falls, and how far the shadow reaches (stretched by the low sun) */
        vec3 g = v3_sub(o, v3_scale(sd, o.y / sd.y));
        int rect[4];
        disc_rect(g.x - c.x, g.z - c.z, Rj / sd.y, 0.5 * S, size, rect);
        vec3 origin = v3_add(v3_sub(c, o), v3_scale(sd, D));
        cu_pass_shadow_add(&r->pass_shadow, ctx, &cl->cloud, cl->ke_rest * cl->factor, origin, v3(0.5 * S, 0, 0),
                           v3(0, 0, 0.5 * S), size, rect);
    }
    cu_pass_shadow_end(ctx);
    return 0;
}

static int render_frame(cu_renderer *r, const cu_frame *f, cu_error *err)
{
    cu_gl *gl = &r->gl;
    cu_gpu_scene *ctx = &r->ctx;
    mat4 view, proj;
    if (frame_matrices(r, f, &view, &proj, err) ||
        cu_pass_tonemap_resize(&r->pass_tonemap, ctx, f->width, f->height, f->linear, err))
        return 1;
    ctx->hdr_format = r->pass_tonemap.hdr.format;
    ctx->width = f->width;
    ctx->height = f->height;
    ctx->host_depth.tex = f->depth_texture;
    ctx->host_depth.clear = f->depth_reversed ? 0.0f : 1.0f;
    int visible = visible_clouds(r, view, proj, err);
    if (visible < 0)
        return 1;
    /* Everything seen from the sun first (it draws into the maps' own targets). */
    for (int j = 0; j < visible; j++)
        if (cloud_maps(r, &r->clouds.slot[r->order[j]], err))
            return 1;
    for (int j = 0; j < visible; j++)
        if (cloud_shadow(r, r->order[j], err))
            return 1;
    if (r->sun_dirty)
        energy_closure(r, visible);
    /* The sky's camera: the view's directions alone (the world origin as the cloud frame). */
    ctx->cloud = &r->none;
    if (cu_camera_build(&ctx->camera, view, proj, v3(0, 0, 0), 1.0, err) || ground_shadow(r, err))
        return 1;

    gl->BindFramebuffer(GL_FRAMEBUFFER, r->pass_tonemap.hdr.fbo);
    gl->Viewport(0, 0, f->width, f->height);
    gl->Disable(GL_CULL_FACE); /* back faces matter when the camera is inside an ellipsoid */
    gl->Disable(GL_BLEND);
    gl->DepthMask(GL_TRUE);
    gl->ClearDepthf(1.0f);
    gl->ClearStencil(0);
    gl->ClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    /* Clouds only: they are drawn over nothing (premultiplied, alpha = coverage) and composited over the host. */
    gl->Clear(GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT | (f->clouds_only ? GL_COLOR_BUFFER_BIT : 0));
    if (!f->clouds_only)
        cu_pass_sky_draw(&r->pass_sky, ctx);
    for (int j = 0; j < visible; j++) {
        cu_cloud_slot *sl = &r->clouds.slot[r->order[j]];
        bind_cloud(r, sl);
        sl->cloud.ke = sl->ke_rest;
        ctx->camera = r->cams[r->order[j]];
        if (j > 0) /* each cloud's depth pre-pass and stencil of its own */
            gl->Clear(GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
        cu_pass_cloud_draw(&r->pass_cloud, ctx);
    }
    /* The context keeps the nearest cloud's camera (what tests and a debugger see of "this frame"), or says that no
     * cloud was in view. */
    if (visible == 0)
        ctx->camera.visible = 0;
    ctx->ke_scale = 1;
    cu_pass_tonemap_draw(&r->pass_tonemap, ctx, f->fbo, f->linear, f->clouds_only);
    GLenum e = gl->GetError();
    if (e != GL_NO_ERROR)
        return cu_fail(err, "render: GL error 0x%x", e);
    return 0;
}

int cu_renderer_set_time(cu_renderer *r, double t, cu_error *err)
{
    if (!isfinite(t) || fabs(t) > 1e9)
        return cu_fail(err, "time: must be finite and within 1e9 s, got %g", t);
    double el, az;
    if (cu_scene_sun_at(&r->scene, t, &el, &az, err))
        return 1;
    r->time = t;
    cu_cloud_set_at_time(&r->clouds, t);
    if (r->scene.has_time_utc && (el != r->scene.sun_elevation || az != r->scene.sun_azimuth)) {
        r->scene.sun_elevation = el;
        r->scene.sun_azimuth = az;
        cu_sky_compute(&r->sky, &r->scene);
        r->sun_dirty = 1;
    }
    return 0;
}

int cu_renderer_set_sun_utc(cu_renderer *r, const char *time_utc, double latitude_deg, double longitude_deg,
                            cu_error *err)
{
    cu_scene s = r->scene; /* checked on a copy: a rejected call changes nothing */
    if (!time_utc || strlen(time_utc) >= sizeof s.time_utc)
        return cu_fail(err, "sun: time_utc missing or too long");
    if (!(latitude_deg >= -90 && latitude_deg <= 90) || !(longitude_deg >= -180 && longitude_deg <= 180))
        return cu_fail(err, "sun: latitude must be in [-90, 90] and longitude in [-180, 180] degrees");
    snprintf(s.time_utc, sizeof s.time_utc, "%s", time_utc);
    s.has_time_utc = 1;
    s.latitude = latitude_deg;
    s.longitude = longitude_deg;
    double el, az;
    if (cu_scene_sun_at(&s, r->time, &el, &az, err))
        return 1;
    snprintf(r->scene.time_utc, sizeof r->scene.time_utc, "%s", time_utc);
    r->scene.has_time_utc = 1;
    r->scene.latitude = latitude_deg;
    r->scene.longitude = longitude_deg;
    r->scene.sun_elevation = el;
    r->scene.sun_azimuth = az;
    cu_sky_compute(&r->sky, &r->scene);
    r->sun_dirty = 1;
    return 0;
}

double cu_renderer_get_time(const cu_renderer *r)
{
    return r->time;
}

int cu_render(cu_renderer *r, const cu_frame *f, cu_error *err)
{
    if (!r->has_scene)
        return cu_fail(err, "render: no scene set");
    if (check_frame(f, err))
        return 1;
    cu_gl *gl = &r->gl;
    while (gl->GetError() != GL_NO_ERROR) {
    }
    cu_glstate st;
    cu_glstate_enter(gl, &st);
    int rc = render_frame(r, f, err);
    cu_glstate_leave(gl, &st);
    return rc;
}
