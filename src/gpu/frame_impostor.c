/* src/gpu/frame_impostor.c: which clouds of a frame are drawn from impostors (quality.impostor_pixels) and when an
 * impostor's image is made again: pass_impostor.c draws them. An image is made from the eye through a square frustum
 * about the cloud's bounding sphere, by the cloud pass itself (the same program, maps and shadows), so the frame it is
 * made in shows the cloud as the full pass would, to the image's resampling. It is made again at once when the cloud
 * starts being drawn from it (no pop at the switch), when it has none or it is too small for the cloud on screen;
 * and, four a frame, nearest first, when the direction to the cloud turned past quality.impostor_degrees, its maps
 * followed the sun, its life or boil moved on, or other clouds shade it differently. */
#include "frame.h"
#include "camera.h"
#include "ellipsoid.h"
#include <math.h>
#include <string.h>

#define REFRESHES_A_FRAME 4
#define IMAGE_MIN 16
#define IMAGE_MAX 256

static int eligible(const cu_renderer *r, const cu_frame *f, const cu_cloud_slot *sl, const cu_camera *c)
{
    int n = r->scene.impostor_pixels;
    if (n <= 0 || f->depth_texture || c->ortho || !r->pass_impostor.prog || sl->cloud.n == 0)
        return 0;
    /* the eye far outside the cloud's bounds: the image's square stands for a cloud seen from one side */
    double rb = sl->cloud.bound_radius * cu_hull_scale(r->scene.hull_tessellation);
    return sl->pixels < n && v3_len(c->pos) > 2.0 * rb;
}

/* Two texels per pixel of the square the image spans in the cloud pass's target (the output's, or the low-resolution
 * one's: quality.cloud_downsample), a power of two: bilinear at half a texel a pixel is nearly the full pass's edge
 * (48 dB on field_noon where one texel a pixel gave 43). */
static int size_for(const cu_renderer *r, const cu_cloud_slot *sl)
{
    double want = 2.0 * sl->pixels * cu_hull_scale(r->scene.hull_tessellation) / (r->fb.d > 1 ? r->fb.d : 1);
    int s = IMAGE_MIN;
    while (s < IMAGE_MAX && s < want)
        s *= 2;
    return s;
}

/* The sun cloud sl is lit by: its maps' (Kol's method moves them in steps of CU_SUN_MAP_STEP), or, for the uniform
 * march, which has no maps, the sun now. */
static vec3 lit_by(const cu_renderer *r, const cu_cloud_slot *sl)
{
    return r->scene.method == CU_METHOD_UNIFORM ? r->sky.sun_dir : sl->maps_sun;
}

static double degrees_between(vec3 a, vec3 b)
{
    double c = v3_dot(a, b);
    return acos(c > 1 ? 1 : c < -1 ? -1 : c) * 180.0 / CU_PI;
}

/* Makes cloud sl's image from the eye of camera c (cloud-local), at `size` texels a side. */
static int make_image(cu_renderer *r, const cu_frame *f, cu_cloud_slot *sl, const cu_camera *c, int size,
                      cu_error *err)
{
    cu_gpu_scene *ctx = &r->ctx;
    cu_impostor *im = &sl->imp;
    double k = cu_hull_scale(r->scene.hull_tessellation), rb = sl->cloud.bound_radius * k, d = v3_len(c->pos);
    double alpha = asin(rb / d); /* eligible(): d > 2 rb */
    vec3 eye = v3_add(sl->cloud.origin, c->pos), axis = v3_scale(c->pos, -1.0 / d);
    mat4 view = m4_look_dir(eye, axis, v3(0, 1, 0));
    mat4 proj = m4_perspective(2.0 * alpha, 1.0, 1.0, 2.0); /* camera.c puts its own depth planes about the cloud */
    cu_camera cam;
    GLenum format = ctx->half_rt ? GL_RGBA16F : GL_RGBA8; /* filterable on GLES 3.0 */
    if (cu_camera_build(&cam, view, proj, sl->cloud.origin, rb, err) ||
        cu_pass_impostor_begin(im, ctx, size, format, err))
        return 1;
    /* the cloud pass into the image, as if the image were the frame */
    cu_camera keep_cam = ctx->camera;
    int keep_w = ctx->width, keep_h = ctx->height, keep_scale = ctx->host_scale, keep_pw = ctx->pass_w,
        keep_ph = ctx->pass_h;
    float keep_map[4], keep_motion[2];
    memcpy(keep_map, ctx->px_map, sizeof keep_map);
    memcpy(keep_motion, ctx->motion, sizeof keep_motion);
    ctx->width = ctx->height = size;
    ctx->host_scale = 1;
    ctx->pass_w = ctx->pass_h = 0;
    ctx->px_map[0] = ctx->px_map[1] = 1.0f;
    ctx->px_map[2] = ctx->px_map[3] = 0.0f;
    ctx->motion[0] = ctx->motion[1] = 0.0f;
    cu_frame_bind_cloud(r, sl);
    sl->cloud.ke = sl->ke_rest;
    ctx->camera = cam;
    int far = r->pass_cloud_far.prog_hull && sl->pixels < r->scene.lod_pixels;
    cu_pass_cloud_draw(far ? &r->pass_cloud_far : &r->pass_cloud, ctx);
    ctx->camera = keep_cam;
    ctx->width = keep_w;
    ctx->height = keep_h;
    ctx->host_scale = keep_scale;
    ctx->pass_w = keep_pw;
    ctx->pass_h = keep_ph;
    memcpy(ctx->px_map, keep_map, sizeof keep_map);
    memcpy(ctx->motion, keep_motion, sizeof keep_motion);
    /* the square: the frustum's section through the centre; the image's right and up are the view's */
    im->axis = axis;
    im->u = v3(view.m[0], view.m[4], view.m[8]);
    im->v = v3(view.m[1], view.m[5], view.m[9]);
    im->half = d * tan(alpha);
    im->sun = lit_by(r, sl);
    im->boil = sl->boil;
    im->factor = sl->factor;
    im->shadow_sig = sl->has_shadow ? sl->shadow_sig : 0;
    im->linear = f->linear;
    im->valid = 1;
    r->impostors_made++;
    return 0;
}

int cu_frame_impostors(cu_renderer *r, const cu_frame *f, int visible, cu_error *err)
{
    int budget = REFRESHES_A_FRAME;
    for (int j = visible - 1; j >= 0; j--) { /* nearest first */
        int i = r->order[j];
        cu_cloud_slot *sl = &r->clouds.slot[i];
        cu_impostor *im = &sl->imp;
        const cu_camera *c = &r->cams[i];
        if (!eligible(r, f, sl, c)) {
            im->in_use = 0;
            continue;
        }
        int size = size_for(r, sl);
        vec3 axis = v3_scale(c->pos, -1.0 / v3_len(c->pos));
        /* drawn from its image in the frame before, or it starts now: a cloud culled for a while and back in view
         * (in_use still set from then) starts again too */
        int continued = im->in_use && im->seen + 1 == r->frame_no;
        int urgent = !im->valid || !continued || size > im->size || im->linear != f->linear;
        int stale = degrees_between(axis, im->axis) > r->scene.impostor_degrees || size * 4 <= im->size ||
                    degrees_between(im->sun, lit_by(r, sl)) > 0.5 * CU_SUN_MAP_STEP ||
                    fabs(im->factor - sl->factor) > 0.01 ||
                    v3_len(v3_sub(im->boil, sl->boil)) > CU_BOIL_STEP ||
                    im->shadow_sig != (sl->has_shadow ? sl->shadow_sig : 0);
        im->in_use = 1;
        im->seen = r->frame_no;
        if (!urgent && stale && budget <= 0)
            r->maps_deferred = 1; /* its turn comes in a later frame: the picture has not settled */
        if (!urgent && !(stale && budget > 0))
            continue;
        if (!urgent)
            budget--;
        if (make_image(r, f, sl, c, size, err))
            return 1;
    }
    return 0;
}
