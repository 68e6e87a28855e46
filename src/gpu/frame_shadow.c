/* src/gpu/frame_shadow.c: the frame's shadows of clouds on clouds (pass_shadow.c draws them): which clouds cast onto
 * which, over what square, and when a map must be remade; and what the ground's (frame_ground.c) shares with it. */
#include "frame.h"
#include <math.h>
#include <stdint.h>

uint64_t cu_sig_bits(uint64_t h, uint64_t q)
{
    for (int i = 0; i < 8; i++) {
        h ^= (q >> (8 * i)) & 0xff;
        h *= 1099511628211ull;
    }
    return h;
}

uint64_t cu_sig_add(uint64_t h, double v)
{
    return cu_sig_bits(h, (uint64_t)llround(v));
}

void cu_shadow_box_rect(const cu_cloud *cl, vec3 rel, vec3 sd, vec3 n, vec3 ax, vec3 ay, double R, int size,
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
 * depths along the sun add up over its sun-map square. Remade when the casters, their densities or the sun changed,
 * or when a caster on another wind has moved an eighth of a texel of the map since it was made. A caster moves
 * against this cloud only by their winds (their offsets are hashed only to a radius of this cloud, to catch a caster
 * wrapping around the sky's square), so "moved" is the fastest relative wind times the time since: every caster
 * crossing its own grid of eighths remade a map with a dozen casters on another wind most frames (kiosk_day). */
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
    int size = sl->map_size / 2 > 16 ? sl->map_size / 2 : 16;
    uint64_t sig = 1469598103934665603ull;
    sig = cu_sig_add(cu_sig_add(cu_sig_add(sig, 1e6 * sd.x), 1e6 * sd.y), 1e6 * sd.z);
    sig = cu_sig_add(cu_sig_add(sig, size), 1e3 * Ri);
    double fastest = 0; /* m/s: the fastest caster against this cloud */
    int casters = 0;
    for (int j = 0; j < r->clouds.n; j++) {
        const cu_cloud_slot *c = &r->clouds.slot[j];
        vec3 d;
        double along;
        if (!casts_on(r, i, j, sd, &d, &along))
            continue;
        casters++;
        sig = cu_sig_add(cu_sig_add(sig, j), 64.0 * c->factor);
        sig = cu_sig_add(cu_sig_add(cu_sig_add(sig, d.x / Ri + 0.382), d.y / Ri + 0.382), d.z / Ri + 0.382);
        fastest = fmax(fastest, v3_len(v3_sub(c->wind, sl->wind)));
    }
    if (casters == 0)
        return 0;
    if (sl->shadow.fbo && sl->shadow.width != size)
        cu_target_delete(&sl->shadow, &r->gl);
    if (!sl->shadow.fbo && cu_pass_shadow_target(&r->gl, size, &sl->shadow, err))
        return 1;
    sl->has_shadow = 1;
    if (sig == sl->shadow_sig && fastest * fabs(r->time - sl->shadow_time) <= Ri / (4.0 * size))
        return 0;
    sl->shadow_sig = sig;
    sl->shadow_time = r->time;
    const int whole[4] = {0, 0, size, size};
    cu_pass_shadow_begin(&r->pass_shadow, ctx, &sl->shadow, size, whole);
    for (int j = 0; j < r->clouds.n; j++) {
        const cu_cloud_slot *c = &r->clouds.slot[j];
        vec3 d;
        double along, Rj = c->cloud.bound_radius;
        if (!casts_on(r, i, j, sd, &d, &along))
            continue;
        /* texel (u, v): the point of cloud i's map plane, in j's frame, moved toward the sun before j */
        vec3 o = v3_add(v3_scale(d, -1.0), v3_scale(sd, along + Rj + 1.0));
        int rect[4];
        cu_shadow_box_rect(&c->cloud, d, sd, sd, rt, up, Ri, size, rect);
        cu_pass_shadow_add(&r->pass_shadow, ctx, &c->cloud, c->ke_rest * c->factor, o, v3_scale(rt, Ri),
                           v3_scale(up, Ri), size, rect);
    }
    cu_pass_shadow_end(ctx);
    return 0;
}
