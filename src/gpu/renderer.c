/* src/gpu/renderer.c: renderer lifetime, scene upload (shader variants for exactly the scene's features, the passes,
 * the cloud set), the sun and the scene time; the frame itself is frame.c's. */
#include "renderer.h"
#include "camera.h"
#include "error.h"
#include "glstate.h"
#include "ms_lobe.h"
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
    cu_pass_cloud_destroy(&r->pass_cloud_far, gl);
    cu_pass_sky_destroy(&r->pass_sky, gl);
    cu_pass_tonemap_destroy(&r->pass_tonemap, gl);
    cu_pass_upsample_destroy(&r->pass_upsample, gl);
    cu_pass_refine_destroy(&r->pass_refine, gl);
    cu_pass_temporal_destroy(&r->pass_temporal, gl);
    cu_pass_impostor_destroy(&r->pass_impostor, gl);
    r->impostors_made = 0;
    r->temporal_off_said = 0;
    r->refine_off_said = 0;
    cu_pass_slab_destroy(&r->pass_slab, gl);
    cu_pass_shadow_destroy(&r->pass_shadow, gl);
    for (int g = 0; g < CU_GROUND_MAPS; g++) {
        cu_target_delete(&r->ground[g].map, gl);
        cu_target_delete(&r->ground[g].next, gl);
        memset(&r->ground[g], 0, sizeof r->ground[g]);
    }
    r->ground_maps = 0;
    r->ground_unseen = 0;
    r->frame_sun_valid = 0;
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
    cu_frame_budget_free(&r->fb, &r->gl);
    cu_pass_clock_free(&r->prof, &r->gl);
    if (r->noise_ready)
        cu_noise_destroy(&r->noise);
    cu_pass_slab_free(&r->pass_slab);
    free(r);
}

/* The shader variant of the scene: only what it uses is compiled, counts and features as constants. Full-screen
 * (FULLSCREEN 1) and hull programs differ in how a fragment finds its ray; LINEAR_OUTPUT picks the tone map's copy. */
typedef struct shader_defs {
    char hull[1800], fs[1800], linear[1800];
} shader_defs;

/* light.sun_planar = auto: whether to read the opacity map below each texel's entry (sunmap.glsl), by two measures of
 * a cloud's map texel W at the smallest map it may get (in a field 16 texels, frame.c). It is needed where W is wide
 * against the lit skin L (the depth over which the sun's optical depth grows its first unit: the fuzzy boundary, or
 * a mean free path where that is longer): a texel's ray enters up to W tan(theta) / 2 off a sample's own, theta the
 * sun's angle to the surface's normal. And it is right only where the surface is a plane across the texels it reads,
 * W small against the lobes' curvature (an ellipsoid's middle semi-axis, the smallest of the cloud's). So: on where
 * some cloud has L / 8 < W < rho / 8. Measured on single scattering against the same renderer with 1024 texels: a
 * 6 km layer, the view from below (1.2 L / 8; its lobes 170-300 m) and glory's flat layer gain (test_sun_planar.sh;
 * README); the default cumulus at 128 texels (W = 5.5 m, L / 8 = 7.75 m) changes by less than its own noise, and at
 * 16, 32 and 64 texels, where W passes a tenth of its 80-200 m lobes, the plane through the neighbours' entries is
 * worse than none (relative RMSE 0.30 -> 0.42, 0.10 -> 0.13, 0.035 -> 0.042). A field of such cumuli stays off. */
static int sun_planar_wanted(const cu_renderer *r)
{
    const cu_scene *s = &r->scene;
    if (s->sun_planar != 2)
        return s->sun_planar;
    int smallest = r->clouds.n > 1 && s->sun_map_size > 16 ? 16 : s->sun_map_size;
    for (int i = 0; i < r->clouds.n; i++) {
        const cu_cloud *cl = &r->clouds.slot[i].cloud;
        double skin = fmax(cl->h, cl->ke > 0.0 ? 1.0 / cl->ke : 0.0), rho = INFINITY;
        for (int e = 0; e < cl->n; e++) { /* the middle of the three semi-axes */
            vec3 a = cl->r[e];
            rho = fmin(rho, fmax(fmin(a.x, a.y), fmin(fmax(a.x, a.y), a.z)));
        }
        double texel = 2.0 * cu_sun_radius(cl) / smallest;
        if (texel > skin / 8.0 && texel < rho / 8.0) {
            cu_gpu_log(&r->ctx, CU_LOG_DEBUG, "light.sun_planar = auto: on (cloud %d's map texel %.1f m, wider than an "
                       "eighth of its lit skin, %.1f m, finer than an eighth of its lobes, %.1f m)", i, texel,
                       skin / 8.0, rho / 8.0);
            return 1;
        }
    }
    cu_gpu_log(&r->ctx, CU_LOG_DEBUG, "light.sun_planar = auto: off (no cloud's map texel is both wider than an eighth "
               "of its lit skin and finer than an eighth of its lobes)");
    return 0;
}

/* far = 1: the far level of detail of a field's clouds, small on screen: one segment fewer (at least 2) and two noise
 * octaves of five (at least 1; the others stand in as their mean, density.glsl). On a field seen from the ground
 * where every cloud takes it, the octaves change the picture by 0.7 % (relative RMSE), the segment by 2.1 %; half
 * the segments would be 6 % (tests/gpu/test_field.c measures the whole). */
static int build_defines(const cu_renderer *r, shader_defs *d, int far, int sun_planar, cu_error *err)
{
    const cu_scene *s = &r->scene;
    const cu_gpu_scene *c = &r->ctx;
    int most_d, most_g; /* the frame budget may draw any resolution and grid up to these */
    cu_frame_budget_most(&r->fb, &r->scene, &most_d, &most_g);
    char defs[1700];
    int n = snprintf(defs, sizeof defs,
             "#define NUM_ELL %d\n#define SEGMENTS %d\n#define MAX_INTERVALS %d\n#define NOISE %d\n"
             "#define NOISE_OCTAVES %d\n#define PROFILE_KOL %d\n#define MS_MODE %d\n#define MS_OCTAVES %d\n"
             "#define SKY_CONSTANT %d\n#define PHASE_PEAK %d\n#define SHADOW_PEEL %d\n#define SUN_INTERVALS %d\n"
             "#define SUN_FILTER %d\n#define SUN_SAMPLES %d\n#define INTEGRATION_KOL %d\n"
             "#define SHADOW_METHOD %d\n#define OSM_SLICES %d\n#define FOM_COEFFS %d\n#define EXT_SHADOW %d\n"
             "#define GROUND_SHADOW %d\n#define METHOD_UNIFORM %d\n#define UNIFORM_STEPS %d\n"
             "#define UNIFORM_SUN_STEPS %d\n#define NOISE_BAKED %d\n#define BOUNDARY_KNOTS %d\n#define RAMP_KNOTS %d\n"
             "#define TEMPORAL %d\n#define SUN_PLANAR %d\n#define MSD_LOBE %d\n#define LOBE_ROWS %d\n"
             "#define LOBE_TS_MAX %.1f\n",
             c->num_ell, far && s->segments > 2 ? s->segments - 1 : s->segments,
             s->max_intervals, s->noise ? 1 : 0, far ? (s->noise_octaves > 2 ? 2 : 1) : s->noise_octaves,
             s->profile == CU_PROFILE_KOL, c->ms_mode, c->ms_mode == CU_MS_OCTAVES ? s->ms_octaves : 1,
             s->sky_model == CU_SKY_CONSTANT, s->phase == CU_PHASE_MIE, c->shadow == CU_SHADOW_PEEL, s->sun_intervals,
             s->sun_filter, s->sun_samples, s->integration, c->shadow, s->osm_slices, s->fom_coefficients,
             r->shadows && r->clouds.n > 1, r->shadows && s->sky_model != CU_SKY_CONSTANT,
             s->method == CU_METHOD_UNIFORM, s->uniform_steps, s->uniform_sun_steps, s->noise && s->noise_baked,
             s->noise && s->boundary_step > 0, s->noise && s->ramp_step > 0, most_g > 1, sun_planar,
             c->ms_mode == CU_MS_DIFFUSION && s->ms_lobe, CU_LOBE_ROWS, CU_LOBE_TS_MAX);
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
    int most_d, most_g;
    cu_frame_budget_most(&r->fb, &r->scene, &most_d, &most_g);
    int sun_planar = sun_planar_wanted(r); /* once: it logs its choice */
    if (build_defines(r, &d, 0, sun_planar, err) || cu_pass_slab_create(&r->pass_slab, ctx, d.fs, err))
        return 1;
    if (cu_pass_sun_create(&r->pass_sun, ctx, d.hull, d.fs, err) ||
        cu_pass_cloud_create(&r->pass_cloud, ctx, d.hull, d.fs, err) ||
        cu_pass_energy_create(&r->pass_energy, ctx, phase, d.fs, err) ||
        cu_pass_sky_create(&r->pass_sky, ctx, d.fs, err) ||
        cu_pass_tonemap_create(&r->pass_tonemap, ctx, d.fs, d.linear, err) ||
        (r->shadows && cu_pass_shadow_create(&r->pass_shadow, ctx, d.fs, err)) ||
        ((most_d > 1 || most_g > 1) && cu_pass_upsample_create(&r->pass_upsample, ctx, err)) ||
        (most_d > 1 && r->scene.edge_refine > 0 && ctx->half_rt && cu_pass_refine_create(&r->pass_refine, ctx, err)) ||
        (most_g > 1 && cu_pass_temporal_create(&r->pass_temporal, ctx, err)) ||
        (r->scene.impostor_pixels > 0 && r->clouds.n > 0 && cu_pass_impostor_create(&r->pass_impostor, ctx, d.hull, err)))
        return 1;
    /* quality.edge_refine marks the pixels it leaves alone with an alpha of 2, which an RGBA8 target cannot hold */
    if (most_d > 1 && r->scene.edge_refine > 0 && !ctx->half_rt)
        cu_gpu_log(ctx, CU_LOG_WARN, "no half-float render targets: quality.edge_refine off (the upsampled clouds "
                                     "alone)");
    if (r->clouds.n > 1 && r->scene.lod_pixels > 0) {
        shader_defs far;
        if (build_defines(r, &far, 1, sun_planar, err) || cu_pass_cloud_create(&r->pass_cloud_far, ctx, far.hull, far.fs, err))
            return 1;
    }
    ctx->sun_ext = r->pass_shadow.zero_tex;
    for (int g = 0; g < CU_GROUND_MAPS; g++) {
        ctx->ground_tau[g] = r->pass_shadow.zero_tex;
        ctx->ground_map[g] = v3(0, 0, 1);
    }
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
    r->drawn = 0; /* a new scene's first frame is a change */
    cu_frame_budget_scene(&r->fb, &r->scene, &r->ctx, r->desc.get_proc_address, r->desc.get_proc_user, r->is_gles);
    if (!r->noise_ready) {
        if (cu_noise_create(&r->noise, NOISE_SEED))
            return cu_fail(err, "noise: out of memory");
        r->noise_ready = 1;
    }
    if (cu_upload_noise(ctx, &r->noise, r->scene.noise && r->scene.noise_baked ? r->scene.noise_octaves : 0, err) ||
        cu_cloud_set_build(&r->clouds, &r->scene, &r->noise, err))
        return 1;
    r->clouds.wrap_cx = r->wrap_cx;
    r->clouds.wrap_cz = r->wrap_cz;
    r->time = r->scene.time;
    size_t n = (size_t)(r->clouds.n > 0 ? r->clouds.n : 1);
    r->order = malloc(sizeof *r->order * n);
    r->order_key = malloc(sizeof *r->order_key * n);
    r->cams = malloc(sizeof *r->cams * n);
    if (!r->order || !r->order_key || !r->cams)
        return cu_fail(err, "clouds: out of memory");
    ctx->num_ell = r->clouds.num_ell;
    /* Shadows of clouds on clouds and on the ground: what blendable half-float targets allow (else a log line). */
    r->shadows = r->clouds.n > 0 && ctx->half_rt && r->scene.cloud_shadows;
    if (r->clouds.n > 0 && !ctx->half_rt && r->scene.cloud_shadows)
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
    ctx->phase_asym = t.mean_cos[1];
    /* Diffusion's medium (ms_diffusion.glsl): the forward lobe g^2 of what the chop left counts as unscattered too. */
    double g = ctx->phase_asym, f_lobe = g > 0 ? g * g : 0;
    ctx->msd_f = 1.0 - (1.0 - ctx->peak_f[1]) * (1.0 - f_lobe);
    ctx->msd_g = g > 0 ? g / (1.0 + g) : g;
    /* The table's sigma_ext wins (DESIGN.md): every cloud's core extinction, scaled from the droplets' 2 pi r_e^2. */
    double sigma_geo = cu_scene_extinction_at(&r->scene, 1.0); /* m^-1 per cm^-3; r_e > 0, so > 0 */
    double sigma = t.sigma_ext_um2[1] > 0 ? 1e6 * t.sigma_ext_um2[1] * 1e-12 : sigma_geo;
    for (int i = 0; i < r->clouds.n; i++) {
        cu_cloud_slot *sl = &r->clouds.slot[i];
        sl->ke_rest = sigma_geo > 0 ? sl->ke_rest * (sigma / sigma_geo) : 0;
        sl->cloud.ke = sl->ke_rest;
    }
    cu_cloud_set_at_time(&r->clouds, r->time); /* the fades follow the optical depths just set */
    int lobe = r->scene.ms_mode == CU_MS_DIFFUSION && r->scene.ms_lobe;
    int rc = cu_upload_phase(ctx, &t, lobe, err) ||
             cu_pass_slab_load(&r->pass_slab, ctx, r->data_dir, &ctx->ms_mode, err) ||
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

int cu_renderer_set_wrap_center(cu_renderer *r, double x, double z, cu_error *err)
{
    if (!isfinite(x) || !isfinite(z) || fabs(x) > 1e8 || fabs(z) > 1e8)
        return cu_fail(err, "wrap center: must be finite and within 1e8 m, got %g %g", x, z);
    r->wrap_cx = r->clouds.wrap_cx = x;
    r->wrap_cz = r->clouds.wrap_cz = z;
    cu_cloud_set_at_time(&r->clouds, r->time);
    return 0;
}


int cu_renderer_budget(const cu_renderer *r, int *cloud_downsample, int *temporal_grid, double *frame_ms)
{
    int on = cu_frame_budget_on(&r->fb);
    *cloud_downsample = r->fb.d > 0 ? r->fb.d : 1;
    *temporal_grid = r->fb.g > 0 ? r->fb.g : 1;
    *frame_ms = on ? r->fb.budget.median_ms : 0;
    return on ? 0 : 1;
}
