/* src/gpu/frame_shadow.c: the frame's shadows of clouds on clouds and on the ground (pass_shadow.c draws them):
 * which clouds cast onto which, over what square, and when a map must be remade. */
#include "frame.h"
#include <math.h>
#include <stdint.h>

#define GROUND_TEXELS 512 /* the ground's shadow map, a side */

/* FNV-1a over what a shadow map depends on, so it is remade only when that changed: 64 bits, then a value rounded. */
static uint64_t sig_bits(uint64_t h, uint64_t q)
{
    for (int i = 0; i < 8; i++) {
        h ^= (q >> (8 * i)) & 0xff;
        h *= 1099511628211ull;
    }
    return h;
}

static uint64_t sig_add(uint64_t h, double v)
{
    return sig_bits(h, (uint64_t)llround(v));
}

/* The texels [x0, x1) x [y0, y1) of a size-texel map of half-side R about its centre (axes ax, ay on the plane of
 * normal n through it) that cloud cl can shade along the sun sd, its origin at rel from the centre: where the
 * corners of the cloud's box fall along sd. Tighter than its bounding sphere's disc for the wide, flat clouds of a
 * layer (a third of the texels on field_noon's ground), and as conservative: no ray outside it meets an ellipsoid. */
static void box_rect(const cu_cloud *cl, vec3 rel, vec3 sd, vec3 n, vec3 ax, vec3 ay, double R, int size,
                     int rect[4])
{
    double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300}, sn = v3_dot(sd, n), k = 0.5 * size / R;
    for (int i = 0; i < 8; i++) {
        vec3 b = v3(i & 1 ? cl->bounds_max.x : cl->bounds_min.x, i & 2 ? cl->bounds_max.y : cl->bounds_min.y,
                    i & 4 ? cl->bounds_max.z : cl->bounds_min.z);
        vec3 p = v3_add(rel, b), g = v3_sub(p, v3_scale(sd, v3_dot(p, n) / sn));
        double u = v3_dot(g, ax), v = v3_dot(g, ay);
        lo[0] = fmin(lo[0], u), hi[0] = fmax(hi[0], u);
        lo[1] = fmin(lo[1], v), hi[1] = fmax(hi[1], v);
    }
    for (int a = 0; a < 2; a++) {
        rect[a] = (int)fmin(size, fmax(0, floor((lo[a] + R) * k) - 1));
        rect[a + 2] = (int)fmin(size, fmax(0, ceil((hi[a] + R) * k) + 1));
    }
}

/* Whether cloud j shades cloud i: j is drawn at all, nearer the sun (along sd) and its disc seen from the sun
 * overlaps i's. Also gives j's offset from i and how far nearer the sun it is. */
static int casts_on(const cu_renderer *r, int i, int j, vec3 sd, vec3 *d, double *along)
{
    const cu_cloud_slot *si = &r->clouds.slot[i], *c = &r->clouds.slot[j];
    if (j == i || c->cloud.n == 0 || !(c->factor * c->ke_rest > 0))
        return 0;
    *d = v3_sub(c->cloud.origin, si->cloud.origin);
    *along = v3_dot(*d, sd);
    vec3 perp = v3_sub(*d, v3_scale(sd, *along));
    return *along > 0 && v3_len(perp) <= si->cloud.bound_radius + c->cloud.bound_radius;
}

/* Cloud i's shadow from the others: the casters are the clouds nearer the sun whose discs seen from the sun overlap
 * its own (for clouds that do not interpenetrate, every sun ray meets a caster before this cloud); their optical
 * depths along the sun add up over its sun-map square. Remade when the casters, their densities, their offsets or
 * the sun changed. */
int cu_frame_cloud_shadow(cu_renderer *r, int i, cu_error *err)
{
    cu_gpu_scene *ctx = &r->ctx;
    cu_cloud_slot *sl = &r->clouds.slot[i];
    sl->has_shadow = 0;
    if (!r->shadows || r->clouds.n < 2)
        return 0;
    cu_frame_bind_cloud(r, sl);
    vec3 sd = ctx->sun_dir, rt = ctx->sun_right, up = ctx->sun_up;
    double Ri = ctx->sun_R;
    uint64_t sig = 1469598103934665603ull;
    sig = sig_add(sig_add(sig_add(sig, 1e6 * sd.x), 1e6 * sd.y), 1e6 * sd.z);
    int casters = 0;
    for (int j = 0; j < r->clouds.n; j++) {
        const cu_cloud_slot *c = &r->clouds.slot[j];
        vec3 d;
        double along;
        if (!casts_on(r, i, j, sd, &d, &along))
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
    cu_pass_shadow_begin(&r->pass_shadow, ctx, &sl->shadow, size, 0, size);
    for (int j = 0; j < r->clouds.n; j++) {
        const cu_cloud_slot *c = &r->clouds.slot[j];
        vec3 d;
        double along, Rj = c->cloud.bound_radius;
        if (!casts_on(r, i, j, sd, &d, &along))
            continue;
        /* texel (u, v): the point of cloud i's map plane, in j's frame, moved toward the sun before j */
        vec3 o = v3_add(v3_scale(d, -1.0), v3_scale(sd, along + Rj + 1.0));
        int rect[4];
        box_rect(&c->cloud, d, sd, sd, rt, up, Ri, size, rect);
        cu_pass_shadow_add(&r->pass_shadow, ctx, &c->cloud, c->ke_rest * c->factor, o, v3_scale(rt, Ri),
                           v3_scale(up, Ri), size, rect);
    }
    cu_pass_shadow_end(ctx);
    return 0;
}

/* Rows [y0, y1) of the ground's shadow map t over the square of side S about c, for the sun sd. */
static void draw_ground(cu_renderer *r, const cu_target *t, vec3 sd, vec3 c, double S, int y0, int y1)
{
    cu_gpu_scene *ctx = &r->ctx;
    int size = t->width;
    cu_gpu_scene_set_sun(ctx);
    ctx->sun_dir = sd;
    cu_pass_shadow_begin(&r->pass_shadow, ctx, t, size, y0, y1);
    for (int j = 0; j < r->clouds.n; j++) {
        const cu_cloud_slot *cl = &r->clouds.slot[j];
        if (cl->cloud.n == 0 || !(cl->factor * cl->ke_rest > 0))
            continue;
        vec3 o = cl->cloud.origin;
        double D = (o.y + cl->cloud.bound_radius) / sd.y + 1.0;
        int rect[4];
        box_rect(&cl->cloud, v3_sub(o, c), sd, v3(0, 1, 0), v3(1, 0, 0), v3(0, 0, 1), 0.5 * S, size, rect);
        rect[1] = rect[1] > y0 ? rect[1] : y0;
        rect[3] = rect[3] < y1 ? rect[3] : y1;
        vec3 origin = v3_add(v3_sub(c, o), v3_scale(sd, D));
        cu_pass_shadow_add(&r->pass_shadow, ctx, &cl->cloud, cl->ke_rest * cl->factor, origin, v3(0.5 * S, 0, 0),
                           v3(0, 0, 0.5 * S), size, rect);
    }
    cu_pass_shadow_end(ctx);
    cu_gpu_scene_set_sun(ctx); /* the sky after it: the sun now */
}

/* Where the wind has carried the clouds by now, when they all ride one wind (a layer's clouds do; zero when winds
 * differ or there is none). The ground's shadow map is made in a frame drifting with it: a shadow follows its cloud
 * by where the map is read, not by making the map again every frame the clouds move. */
static vec3 common_drift(const cu_renderer *r)
{
    vec3 w = v3(0, 0, 0);
    int any = 0;
    for (int j = 0; j < r->clouds.n; j++) {
        const cu_cloud_slot *cl = &r->clouds.slot[j];
        if (cl->cloud.n == 0)
            continue;
        if (any && (cl->wind.x != w.x || cl->wind.y != w.y || cl->wind.z != w.z))
            return v3(0, 0, 0);
        w = cl->wind;
        any = 1;
    }
    return v3_scale(w, r->time);
}

/* What the square of side S about c (x, z in the drifting frame) shows of the clouds for the sun sd: the positions
 * (in that frame) of the clouds whose shadows can reach it, and their densities. A cloud elsewhere in the layer
 * cannot change a texel of the map. The offset keeps a scene's round numbers off the quantiser's rounding edges. */
static void ground_hashes(const cu_renderer *r, vec3 drift, vec3 sd, vec3 c, double S, uint64_t *pos, uint64_t *dens)
{
    *pos = *dens = 1469598103934665603ull;
    for (int j = 0; j < r->clouds.n; j++) {
        const cu_cloud_slot *cl = &r->clouds.slot[j];
        if (cl->cloud.n == 0 || !(cl->ke_rest > 0))
            continue;
        vec3 o = v3_sub(cl->cloud.origin, drift);
        int rect[4];
        box_rect(&cl->cloud, v3_sub(o, c), sd, v3(0, 1, 0), v3(1, 0, 0), v3(0, 0, 1), 0.5 * S, GROUND_TEXELS, rect);
        if (rect[2] <= rect[0] || rect[3] <= rect[1])
            continue;
        *pos = sig_add(sig_add(sig_add(sig_add(*pos, j), 4.0 * o.x + 0.382), 4.0 * o.y + 0.382), 4.0 * o.z + 0.382);
        *dens = sig_add(sig_add(*dens, j), 64.0 * cl->factor);
    }
}

/* Whether any of the view's rays points below the horizon (the sky pass draws the ground there, sky.frag): the
 * rays through the corners of the screen bound every other (a perspective view's directions are their cone). Clip
 * to direction through the sky's matrix, as sky.vert does. */
static int ground_in_view(const cu_camera *cam)
{
    const float *m = cam->inv_rot;
    for (int k = 0; k < 4; k++) {
        double x = k & 1 ? 1 : -1, y = k & 2 ? 1 : -1, p[2][4];
        for (int z = 0; z < 2; z++)
            for (int row = 0; row < 4; row++)
                p[z][row] = m[row] * x + m[4 + row] * y + m[8 + row] * (z ? 1.0 : -1.0) + m[12 + row];
        if (p[1][1] / p[1][3] - p[0][1] / p[0][3] < 0)
            return 1;
    }
    return 0;
}

/* The clouds' shadow on the ground: their optical depth toward the sun over a square about the camera (its side
 * grows with the camera's height; shadows farther away lie within a fraction of a degree of the horizon), in a frame
 * drifting with the clouds' common wind; not made while no ground is in view. Remade whole when there is none, a
 * cloud moved in that frame (the shadow must follow it at once: clouds on different winds do every frame), the
 * ground came back into view, the camera jumped or the sun jumped; when the
 * sun crept, the camera moved the square on or a cloud's density changed (its life cycle), as the clouds' maps are
 * (frame_maps.c), a band of rows a frame over quality.sun_map_frames frames into a spare, swapped in whole. */
int cu_frame_ground_shadow(cu_renderer *r, cu_error *err)
{
    cu_gpu_scene *ctx = &r->ctx;
    ctx->ground_tau = r->pass_shadow.zero_tex;
    ctx->ground_map = v3(0, 0, 1);
    vec3 sd = ctx->sky->sun_dir, eye = ctx->camera.pos;
    if (!r->shadows || r->scene.sky_model == CU_SKY_CONSTANT || sd.y < 0.02 || ctx->camera.ortho || eye.y <= 0)
        return 0;
    if (!ground_in_view(&ctx->camera)) { /* no pixel reads the map: left as it is (130 ms on field_noon) */
        r->ground_unseen = 1;
        return 0;
    }
    int unseen = r->ground_unseen; /* the map was left behind while the ground was out of view */
    r->ground_unseen = 0;
    const int size = GROUND_TEXELS;
    vec3 drift = common_drift(r), e = v3_sub(eye, drift);
    double S = fmin(fmax(40.0 * eye.y + 4000.0, 4000.0), 60000.0), snap = S / 16;
    vec3 c = v3(snap * floor(e.x / snap + 0.5), 0, snap * floor(e.z / snap + 0.5)); /* in the drifting frame */
    int jumped = !r->frame_sun_valid || cu_sun_apart(r->frame_sun, sd, CU_SUN_MAP_JUMP);
    /* the sun as the map was made for while it creeps less than CU_SUN_MAP_STEP (as the clouds' own maps) */
    if (r->ground_sig && !cu_sun_apart(r->ground_sun, sd, CU_SUN_MAP_STEP))
        sd = r->ground_sun;
    uint64_t pos, dens;
    ground_hashes(r, drift, sd, c, S, &pos, &dens);
    uint64_t sig = sig_add(sig_add(sig_add(sig_bits(pos, dens), c.x), c.z), S);
    sig = sig_add(sig_add(sig_add(sig, 1e6 * sd.x), 1e6 * sd.y), 1e6 * sd.z);
    if (!r->ground.fbo && cu_pass_shadow_target(&r->gl, size, &r->ground, err))
        return 1;
    int bands = r->scene.sun_map_frames;
    int lagged = cu_sun_apart(r->ground_sun, sd, cu_sun_map_lag(bands));
    /* A cloud moved in the drifting frame over the same square: its shadow follows at once; so it does when the
     * camera jumped a quarter of the square (the old map would miss the ground in view). A camera flying on moves the
     * square a sixteenth at a time: the old square still holds all but the far edge of the new one. */
    vec3 at = r->ground_at;
    int same_square = c.x == at.x && c.z == at.y && S == at.z;
    int moved = (same_square && pos != r->ground_scene) || hypot(c.x - at.x, c.z - at.y) > 0.25 * S ||
                fabs(S - at.z) > 0.25 * S;
    if (sig != r->ground_sig && (bands == 1 || !r->ground_sig || jumped || lagged || moved || unseen)) {
        r->ground_band = 0; /* a band under way is overtaken */
        r->ground_sig = sig;
        r->ground_scene = pos;
        r->ground_sun = sd;
        r->ground_at = v3(c.x, c.z, S);
        draw_ground(r, &r->ground, sd, v3_add(c, drift), S, 0, size);
    } else if (sig != r->ground_sig || r->ground_band > 0) {
        if (r->ground_band == 0) {
            if (!r->ground_next.fbo && cu_pass_shadow_target(&r->gl, size, &r->ground_next, err))
                return 1;
            r->ground_next_sig = sig;
            r->ground_next_scene = pos;
            r->ground_next_sun = sd;
            r->ground_next_at = v3(c.x, c.z, S);
        }
        vec3 nat = r->ground_next_at;
        int b = r->ground_band++;
        draw_ground(r, &r->ground_next, r->ground_next_sun, v3(nat.x + drift.x, 0, nat.y + drift.z), nat.z,
                    size * b / bands, size * (b + 1) / bands);
        if (r->ground_band == bands) { /* the last band: the new map in, the old one the next spare */
            cu_target t = r->ground;
            r->ground = r->ground_next;
            r->ground_next = t;
            r->ground_sig = r->ground_next_sig;
            r->ground_scene = r->ground_next_scene;
            r->ground_sun = r->ground_next_sun;
            r->ground_at = r->ground_next_at;
            r->ground_band = 0;
            if (sig != r->ground_sig)
                r->maps_deferred = 1; /* the sun or the clouds moved on while the bands were drawn */
        } else {
            r->maps_deferred = 1; /* the picture has not settled */
        }
    }
    ctx->ground_tau = r->ground.tex[0];
    ctx->ground_map = v3(r->ground_at.x + drift.x, r->ground_at.y + drift.z, r->ground_at.z);
    return 0;
}
