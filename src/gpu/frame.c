/* src/gpu/frame.c: one frame: the clouds in view (culled, sorted back to front), their maps at the level of detail
 * their size on screen asks for, the energy closure, then the sky, each cloud and the tone map, in order. */
#include "frame.h"
#include "profile.h"
#include "camera.h"
#include "error.h"
#include "glstate.h"
#include "scene_camera.h"
#include "sunmap.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Points the frame context at cloud i: what the passes read of "the cloud". */
void cu_frame_bind_cloud(cu_renderer *r, cu_cloud_slot *sl)
{
    cu_gpu_scene *ctx = &r->ctx;
    ctx->cloud = &sl->cloud;
    ctx->hull_vao = sl->vao;
    ctx->sun = sl->sun;
    ctx->slab = sl->slab;
    cu_pass_msd_bind(ctx, &sl->msd);
    ctx->ke_scale = sl->factor;
    ctx->sun_ext = sl->has_shadow ? sl->shadow.tex[0] : r->pass_shadow.zero_tex;
    ctx->sun_size = sl->map_size > 0 ? sl->map_size : r->scene.sun_map_size;
    cu_gpu_scene_set_sun(ctx);
    if (sl->maps_valid) { /* the cloud is lit by the sun its maps were made for (within CU_SUN_MAP_STEP of now) */
        ctx->sun_dir = sl->maps_sun;
        cu_sun_basis(ctx->sun_dir, &ctx->sun_right, &ctx->sun_up);
    }
}

/* The level of detail of a cloud's maps in a field: about a texel per two pixels the cloud covers on screen, a power
 * of two from 16 up to quality.sun_map_size. A lone cloud always gets quality.sun_map_size. */
/* The cloud's diameter on screen, in pixels. */
static double screen_pixels(const cu_camera *c, mat4 proj, double radius, int height)
{
    double d = c->ortho ? 1.0 : fmax(v3_len(c->pos), radius);
    return radius * fabs(proj.m[5]) * height / d;
}

static int map_size_for(const cu_renderer *r, double pixels)
{
    int most = r->scene.sun_map_size, size = 16;
    if (r->clouds.n == 1 || most <= 16)
        return most;
    while (size < most && size < 0.5 * pixels)
        size *= 2;
    return size < most ? size : most;
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
 * rendering them in a back-to-front order"). The order is by the power distance of the eye to each cloud's footprint
 * circle seen from above, d^2 - r^2: for clouds whose footprints do not overlap (a layer's never do) every line of
 * sight meets them in that order, wherever the eye is, where the distance of the centres flips the order of a big
 * and a small cloud side by side and makes the picture jump. Returns how many. */
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
        cu_camera_clip_rect(c, view, proj, sl->cloud.origin, sl->cloud.bounds_min, sl->cloud.bounds_max);
        sl->pixels = screen_pixels(c, proj, sl->cloud.bound_radius, r->ctx.height);
        sl->want_size = map_size_for(r, sl->pixels);
        /* perspective: the power distance above (pos is the eye, cloud-local); orthographic: how far along the view
         * direction the centre lies */
        r->order_key[i] = c->ortho ? v3_dot(sl->cloud.origin, c->view_dir)
                                   : c->pos.x * c->pos.x + c->pos.z * c->pos.z - sl->radius_xz * sl->radius_xz;
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
    cu_frame_bind_cloud(r, sl);
    r->ctx.sun_ext = r->pass_shadow.zero_tex; /* the cloud's own budget, as if alone */
    cu_pass_energy_update(&r->pass_energy, &r->ctx);
    sl->factor = f;
    r->ctx.ms_gain[0] = r->pass_energy.gain[0];
    r->ctx.ms_gain[1] = r->pass_energy.gain[1];
    r->sun_dirty = 0;
}

/* The cloud pass draws every pixel of the cloud image, with no motion to record. */
static void temporal_frame_identity(cu_gpu_scene *ctx)
{
    ctx->pass_w = ctx->pass_h = 0;
    ctx->px_map[0] = ctx->px_map[1] = 1.0f;
    ctx->px_map[2] = ctx->px_map[3] = 0.0f;
    ctx->motion[0] = ctx->motion[1] = 0.0f;
}

/* quality.temporal_grid for this frame: G, or 1 where the grid cannot serve (said once a scene). */
static int temporal_grid(cu_renderer *r, const cu_frame *f, int visible)
{
    if (r->fb.g < 2 || !r->pass_temporal.prog[0] || visible == 0)
        return 1;
    const char *why = f->depth_texture ? "the host gives its depth, which the reprojection would not follow"
                      : r->pass_tonemap.hdr.format == GL_RGBA8 ? "no float render target to hold distances"
                                                               : NULL;
    if (!why)
        return r->fb.g;
    if (!r->temporal_off_said)
        cu_gpu_log(&r->ctx, CU_LOG_INFO, "quality.temporal_grid: every cloud pixel every frame: %s", why);
    r->temporal_off_said = 1;
    return 1;
}

/* The temporal grid's frame: the whole image when a camera is orthographic or inside a hull (the reprojection's
 * distances mean nothing there), else one pixel a block, each cloud's camera shifted onto those pixels. */
static int temporal_begin(cu_renderer *r, const cu_frame *f, int visible, int n, mat4 view, mat4 proj, int *sparse,
                          cu_error *err)
{
    cu_gpu_scene *ctx = &r->ctx;
    cu_pass_temporal *t = &r->pass_temporal;
    int lw = (f->width + n - 1) / n, lh = (f->height + n - 1) / n, whole = 0, g = r->fb.g;
    cu_camera keep = ctx->camera;
    const cu_cloud *keep_cloud = ctx->cloud;
    for (int j = 0; j < visible; j++) {
        ctx->camera = r->cams[r->order[j]];
        ctx->cloud = &r->clouds.slot[r->order[j]].cloud;
        whole |= ctx->camera.ortho || cu_pass_cloud_fullscreen(ctx);
    }
    ctx->camera = keep;
    ctx->cloud = keep_cloud;
    if (cu_pass_temporal_begin(t, ctx, lw, lh, g, r->pass_tonemap.hdr.format, whole, sparse, err))
        return 1;
    if (!*sparse)
        return 0;
    mat4 shifted = cu_pass_temporal_projection(t, proj, lw, lh);
    double k = cu_hull_scale(r->scene.hull_tessellation);
    for (int j = 0; j < visible; j++) {
        cu_cloud_slot *sl = &r->clouds.slot[r->order[j]];
        if (cu_camera_build(&r->cams[r->order[j]], view, shifted, sl->cloud.origin, sl->cloud.bound_radius * k, err))
            return 1;
    }
    ctx->pass_w = t->sparse.width;
    ctx->pass_h = t->sparse.height;
    ctx->px_map[0] = ctx->px_map[1] = (float)g;
    ctx->px_map[2] = (float)t->ox + 0.5f - 0.5f * (float)g;
    ctx->px_map[3] = (float)t->oy + 0.5f - 0.5f * (float)g;
    return 0;
}

/* Where this frame's clouds can be on screen (NDC x0, y0, x1, y1): the union of their cameras' rectangles, an
 * impostor's doubled about its centre (its square faces the eye it was made from, not quite this one). The passes
 * after the clouds' leave the rest to the sky. */
static void clouds_ndc_rect(const cu_renderer *r, int visible, double u[4])
{
    u[0] = u[1] = 1;
    u[2] = u[3] = -1;
    for (int j = 0; j < visible; j++) {
        const double *q = r->cams[r->order[j]].ndc_rect;
        double k = r->clouds.slot[r->order[j]].imp.in_use ? 1.0 : 0.5;
        for (int a = 0; a < 2; a++) {
            double mid = 0.5 * (q[a] + q[2 + a]), half = k * (q[2 + a] - q[a]);
            u[a] = fmin(u[a], mid - half);
            u[2 + a] = fmax(u[2 + a], mid + half);
        }
    }
}

/* Each cloud in view, back to front, into the bound target (the frame's, the low-resolution one, the temporal grid's
 * or, with ctx->refining, the edge refinement's); dt: how far back the last frame is, for the clouds' motion. clip
 * (refining only, else NULL): the pixels the refinement may touch; each cloud's full-screen pass is scissored to them
 * and its own rectangle. */
static void draw_clouds(cu_renderer *r, int visible, double dt, const int clip[4])
{
    cu_gl *gl = &r->gl;
    cu_gpu_scene *ctx = &r->ctx;
    int depth_used = 0;
    for (int j = 0; j < visible; j++) {
        cu_cloud_slot *sl = &r->clouds.slot[r->order[j]];
        cu_frame_bind_cloud(r, sl);
        sl->cloud.ke = sl->ke_rest;
        ctx->camera = r->cams[r->order[j]];
        ctx->motion[0] = (float)(sl->wind.x * dt);
        ctx->motion[1] = (float)(sl->wind.z * dt);
        if (sl->imp.in_use) { /* small on screen: its image (quality.impostor_pixels) */
            if (clip) /* not the rectangle of the cloud drawn before */
                gl->Scissor(clip[0], clip[1], clip[2] - clip[0], clip[3] - clip[1]);
            cu_pass_impostor_draw(&r->pass_impostor, ctx, &sl->imp);
            continue;
        }
        int far = r->pass_cloud_far.prog_hull && sl->pixels < r->scene.lod_pixels;
        const cu_pass_cloud *pass = far ? &r->pass_cloud_far : &r->pass_cloud;
        if (clip) { /* one full-screen triangle (pass_cloud.c), over this cloud's pixels alone */
            int px[4];
            cu_ndc_rect_pixels(ctx->camera.ndc_rect, ctx->width, ctx->height, 1, px);
            int x0 = px[0] > clip[0] ? px[0] : clip[0], y0 = px[1] > clip[1] ? px[1] : clip[1];
            int x1 = px[2] < clip[2] ? px[2] : clip[2], y1 = px[3] < clip[3] ? px[3] : clip[3];
            if (x1 > x0 && y1 > y0) {
                gl->Scissor(x0, y0, x1 - x0, y1 - y0);
                cu_pass_cloud_draw(pass, ctx);
            }
            continue;
        }
        if (depth_used) /* each cloud's depth pre-pass and stencil of its own */
            gl->Clear(GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
        depth_used = 1;
        cu_pass_cloud_draw(pass, ctx);
    }
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
    temporal_frame_identity(ctx);
    r->maps_deferred = 0;
    r->sparse_grid = 1;
    r->frame_no++;
    cu_profile_begin(r);
    int visible = visible_clouds(r, view, proj, err);
    if (visible < 0)
        return 1;
    /* Everything seen from the sun first (it draws into the maps' own targets). */
    int budget = 4;
    r->msd_work = 1000L * r->scene.ms_frame_work;
    for (int j = visible - 1; j >= 0; j--)
        if (cu_frame_cloud_maps(r, &r->clouds.slot[r->order[j]], &budget, err))
            return 1;
    cu_profile_mark(r, CU_PASS_MAPS);
    for (int j = 0; j < visible; j++)
        if (cu_frame_cloud_shadow(r, r->order[j], err))
            return 1;
    cu_profile_mark(r, CU_PASS_SHADOWS);
    if (r->sun_dirty)
        energy_closure(r, visible);
    cu_profile_mark(r, CU_PASS_ENERGY);
    if (cu_frame_impostors(r, f, visible, err))
        return 1;
    cu_profile_mark(r, CU_PASS_MAPS); /* impostor images count with the maps: made now, drawn from later */
    double cloud_rect[4]; /* before the temporal grid shifts the clouds' cameras */
    clouds_ndc_rect(r, visible, cloud_rect);
    /* The sky's camera: the view's directions alone (the world origin as the cloud frame). The sun as it is now: with
     * no cloud in view nothing above has set it since cu_renderer_set_sun moved it. */
    ctx->cloud = &r->none;
    cu_gpu_scene_set_sun(ctx);
    if (cu_camera_build(&ctx->camera, view, proj, v3(0, 0, 0), 1.0, err) || cu_frame_ground_shadow(r, err))
        return 1;
    r->frame_sun = ctx->sky->sun_dir; /* the next frame's maps compare the sun with it: did it jump? */
    r->frame_sun_valid = 1;
    cu_profile_mark(r, CU_PASS_SHADOWS);

    /* No cloud in view: the sky straight into the output, its tone map in the same pass (one full-screen pass, not
     * the sky's and the tone map's: what a view without cloud costs). Linear output and clouds-only frames take the
     * general path. */
    if (visible == 0 && !f->clouds_only && !f->linear) {
        gl->BindFramebuffer(GL_FRAMEBUFFER, f->fbo);
        gl->Viewport(0, 0, f->width, f->height);
        gl->Disable(GL_BLEND);
        if (cu_pass_sky_draw(&r->pass_sky, ctx, 1, err))
            return 1;
        ctx->camera.visible = 0;
        cu_profile_mark(r, CU_PASS_SKY);
        GLenum e = gl->GetError();
        return e != GL_NO_ERROR ? cu_fail(err, "render: GL error 0x%x", e) : 0;
    }
    /* quality.cloud_downsample: the clouds into a target of 1/N the size, brought up over the sky after them; the
     * temporal grid's image likewise. With neither the host's depth nor linear or clouds-only output, the sky pass
     * brings them up itself, tone-mapped into the output: one full-screen pass instead of three. */
    int n = r->fb.d > 1 && r->pass_upsample.prog && visible > 0 ? r->fb.d : 1;
    int g = temporal_grid(r, f, visible), sparse = 0;
    int over = (n > 1 || g > 1) && !f->linear && !f->clouds_only && !ctx->host_depth.tex;
    gl->Disable(GL_CULL_FACE); /* back faces matter when the camera is inside an ellipsoid */
    gl->Disable(GL_BLEND);
    gl->DepthMask(GL_TRUE);
    gl->ClearDepthf(1.0f);
    gl->ClearStencil(0);
    gl->ClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    if (!over) {
        gl->BindFramebuffer(GL_FRAMEBUFFER, r->pass_tonemap.hdr.fbo);
        gl->Viewport(0, 0, f->width, f->height);
        /* Clouds only: they are drawn over nothing (premultiplied, alpha = coverage) and composited over the host. */
        gl->Clear(GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT | (f->clouds_only ? GL_COLOR_BUFFER_BIT : 0));
        if (!f->clouds_only && cu_pass_sky_draw(&r->pass_sky, ctx, 0, err))
            return 1;
    }
    cu_profile_mark(r, CU_PASS_SKY);
    cu_camera view_cam = ctx->camera; /* the view's own, at the world origin: what the temporal grid reprojects */
    if (g > 1) {
        if (temporal_begin(r, f, visible, n, view, proj, &sparse, err))
            return 1;
        r->sparse_grid = sparse ? g : 1;
    } else if (n > 1) {
        if (cu_pass_upsample_begin(&r->pass_upsample, ctx, f->width, f->height, n, r->pass_tonemap.hdr.format, err))
            return 1;
    }
    ctx->host_scale = n;
    double dt = g > 1 ? r->time - r->pass_temporal.prev_time : 0.0;
    draw_clouds(r, visible, dt, NULL);
    /* The context keeps the nearest cloud's camera (what tests and a debugger see of "this frame"), or says that no
     * cloud was in view. */
    if (visible == 0)
        ctx->camera.visible = 0;
    cu_profile_mark(r, CU_PASS_CLOUDS);
    temporal_frame_identity(ctx);
    GLuint image = 0, refined = 0;
    /* the pixels the cloud image can reach: its rectangle, the temporal grid's blocks and both bilinear reads; without
     * the one-pass composite, the upsampling covers the frame */
    int reach[4] = {0, 0, f->width, f->height};
    if (over)
        cu_ndc_rect_pixels(cloud_rect, f->width, f->height, (g + 3) * n, reach);
    if (g > 1) {
        cu_pass_temporal_end(&r->pass_temporal, ctx, &view_cam, r->time, cloud_rect);
        image = cu_pass_temporal_image(&r->pass_temporal);
        if (r->scene.edge_refine > 0 && !r->refine_off_said)
            cu_gpu_log(ctx, CU_LOG_INFO, "quality.edge_refine: off while the temporal grid draws the clouds (its "
                       "image is reprojected from frames before, not refined)");
        r->refine_off_said |= r->scene.edge_refine > 0;
    } else if (n > 1) {
        image = r->pass_upsample.low.tex[0];
        /* quality.edge_refine: the pixels whose low-resolution neighbours differ, marched again at full resolution */
        if (r->scene.edge_refine > 0 && r->pass_refine.prog) {
            if (cu_pass_refine_begin(&r->pass_refine, ctx, image, f->width, f->height, n, r->scene.edge_refine,
                                     reach, r->pass_tonemap.hdr.format, err))
                return 1;
            cu_camera nearest = ctx->camera;
            ctx->host_scale = 1;
            ctx->refining = 1;
            draw_clouds(r, visible, 0.0, reach);
            ctx->refining = 0;
            ctx->camera = nearest;
            cu_pass_refine_end(&r->pass_refine, gl);
            refined = r->pass_refine.full.tex[0];
            cu_profile_mark(r, CU_PASS_CLOUDS); /* the clouds' pass, the second time */
        }
    }
    ctx->ke_scale = 1;
    if (over) { /* visible > 0 here: n and g are 1 without a cloud in view */
        cu_camera nearest = ctx->camera;
        const cu_cloud *nearest_cloud = ctx->cloud;
        ctx->camera = view_cam; /* the sky's camera and sun, as for the sky pass above */
        ctx->cloud = &r->none;
        cu_gpu_scene_set_sun(ctx);
        gl->BindFramebuffer(GL_FRAMEBUFFER, f->fbo);
        gl->Viewport(0, 0, f->width, f->height);
        gl->Disable(GL_BLEND);
        gl->Disable(GL_STENCIL_TEST);
        gl->Disable(GL_DEPTH_TEST);
        if (cu_pass_sky_draw_over(&r->pass_sky, ctx, image, refined, n, reach, err))
            return 1;
        ctx->camera = nearest;
        ctx->cloud = nearest_cloud;
        cu_profile_mark(r, CU_PASS_UPSAMPLE);
        GLenum e = gl->GetError();
        return e != GL_NO_ERROR ? cu_fail(err, "render: GL error 0x%x", e) : 0;
    }
    if (image) {
        cu_pass_upsample_draw(&r->pass_upsample, ctx, image, refined, r->pass_tonemap.hdr.fbo, f->width, f->height, n,
                              proj.m);
        cu_profile_mark(r, CU_PASS_UPSAMPLE);
    }
    cu_pass_tonemap_draw(&r->pass_tonemap, ctx, f->fbo, f->linear, f->clouds_only);
    cu_profile_mark(r, CU_PASS_TONEMAP);
    GLenum e = gl->GetError();
    if (e != GL_NO_ERROR)
        return cu_fail(err, "render: GL error 0x%x", e);
    return 0;
}

/* After a frame: the frames the temporal grid still needs before every pixel was marched since what the picture
 * depends on last changed (camera, size, output, sun, time, resolution, grid). */
static void note_settling(cu_renderer *r, const cu_frame *f)
{
    struct cu_frame_key k;
    memset(&k, 0, sizeof k); /* the padding too: keys are compared as bytes */
    mat4 view, proj;
    cu_error e;
    if (frame_matrices(r, f, &view, &proj, &e))
        return;
    memcpy(k.view, view.m, sizeof k.view);
    memcpy(k.proj, proj.m, sizeof k.proj);
    k.time = r->time;
    k.sun = r->sky.sun_dir;
    k.width = f->width;
    k.height = f->height;
    k.linear = f->linear;
    k.clouds_only = f->clouds_only;
    k.depth_texture = f->depth_texture;
    k.downsample = r->fb.d;
    k.grid = r->fb.g;
    int g = r->sparse_grid;
    if (!r->drawn || memcmp(&k, &r->last_key, sizeof k))
        r->settle_left = g > 1 ? g * g - 1 : 0;
    else if (r->settle_left > 0)
        r->settle_left--;
    r->last_key = k;
    r->drawn = 1;
}

int cu_renderer_settled(const cu_renderer *r)
{
    return r->has_scene && r->drawn && r->settle_left == 0 && !r->maps_deferred;
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
    cu_frame_budget_before(&r->fb, &r->ctx);
    cu_frame_budget_begin(&r->fb, gl);
    int rc = render_frame(r, f, err);
    cu_profile_end(r, rc == 0);
    cu_frame_budget_end(&r->fb, gl);
    if (rc == 0)
        note_settling(r, f);
    cu_glstate_leave(gl, &st);
    return rc;
}
