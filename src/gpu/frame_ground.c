/* src/gpu/frame_ground.c: the clouds' shadow on the ground (pass_shadow.c draws it, sky.frag reads it): their optical
 * depth toward the sun over a square about the camera, a map for each wind the clouds ride (a layer's clouds share
 * one), made in a frame drifting with that wind so that a shadow follows its cloud by where the map is read, and made
 * again only when something changes in that frame: whole, a band of rows a frame, or, when only some clouds' densities
 * changed (their life cycles), just the texels their shadows cover. */
#include "frame.h"
#include <math.h>
#include <stdint.h>
#include <string.h>

#define GROUND_TEXELS 512 /* a map's side */
#define PATCHES_MAX 32    /* clouds whose density changed, made again one by one; more: the map in bands */

/* The texels of the clouds whose density is not the one a map holds, a rectangle each ({x0, y0, x1, y1}): a field's
 * clouds lie apart, and the box about all of them would be most of the map. */
typedef struct patch_list {
    int n;                /* PATCHES_MAX + 1: more than that */
    long area;            /* texels, overlaps counted twice */
    int rect[PATCHES_MAX][4];
} patch_list;

static int same_vec(vec3 a, vec3 b) /* the same vector, to the bit: a wind, a sun */
{
    return a.x == b.x && a.y == b.y && a.z == b.z;
}

/* A cloud's density in the ground's maps: in 64ths of its mature one, so that a map made again over part of its
 * texels is, texel for texel, the map made whole (what it holds is a function of its signature). */
static int dens_q(const cu_cloud_slot *cl)
{
    return (int)llround(64.0 * cl->factor);
}

/* Which map cloud j's shadow goes into: the one of its wind; with more winds than maps, the last. */
static int map_of(const cu_renderer *r, const cu_cloud_slot *cl)
{
    for (int g = 0; g < r->ground_maps - 1; g++)
        if (same_vec(cl->wind, r->ground[g].wind))
            return g;
    return r->ground_maps - 1;
}

/* The maps' winds, in the order the clouds first ride them; the last map mixed when more winds than maps remain. A
 * map whose wind changed holds other clouds now: its signature no longer matches, so it is made whole. */
static void assign_winds(cu_renderer *r)
{
    int n = 0, mixed = 0;
    vec3 w[CU_GROUND_MAPS];
    for (int j = 0; j < r->clouds.n; j++) {
        const cu_cloud_slot *cl = &r->clouds.slot[j];
        if (cl->cloud.n == 0)
            continue;
        int g = 0;
        while (g < n && !same_vec(cl->wind, w[g]))
            g++;
        if (g == n && n < CU_GROUND_MAPS)
            w[n++] = cl->wind;
        else if (g == n)
            mixed = 1;
    }
    r->ground_maps = n > 0 ? n : 1;
    for (int g = 0; g < r->ground_maps; g++) {
        r->ground[g].wind = n > 0 ? w[g] : v3(0, 0, 0);
        r->ground[g].mixed = g == r->ground_maps - 1 && mixed;
    }
}

/* Where map g's wind has carried its clouds by now (zero for a mixed map: it does not drift). */
static vec3 drift_of(const cu_renderer *r, int g)
{
    return r->ground[g].mixed ? v3(0, 0, 0) : v3_scale(r->ground[g].wind, r->time);
}

static const int NO_INK[4] = {0, 0, 0, 0};

/* ink grown to hold rect (texels, half-open; an empty rect adds nothing). */
static void ink_add(int ink[4], const int rect[4])
{
    if (rect[2] <= rect[0] || rect[3] <= rect[1])
        return;
    if (ink[2] <= ink[0] || ink[3] <= ink[1]) {
        memcpy(ink, rect, 4 * sizeof *ink);
        return;
    }
    for (int k = 0; k < 2; k++) {
        ink[k] = rect[k] < ink[k] ? rect[k] : ink[k];
        ink[k + 2] = rect[k + 2] > ink[k + 2] ? rect[k + 2] : ink[k + 2];
    }
}

/* The texels reg = {x0, y0, x1, y1} of map g's target t over the square of side S about c (world), for the sun sd;
 * with `band` >= 0 the map made again in bands (band `band`), and what its clouds' densities are is kept. The texels
 * a shadow was drawn into are added to ink. */
static void draw_ground(cu_renderer *r, int g, const cu_target *t, vec3 sd, vec3 c, double S, const int reg[4],
                        int band, int ink[4])
{
    cu_gpu_scene *ctx = &r->ctx;
    int size = t->width;
    cu_gpu_scene_set_sun(ctx);
    ctx->sun_dir = sd;
    cu_pass_shadow_begin(&r->pass_shadow, ctx, t, size, reg);
    for (int j = 0; j < r->clouds.n; j++) {
        cu_cloud_slot *cl = &r->clouds.slot[j];
        if (cl->cloud.n == 0 || map_of(r, cl) != g)
            continue;
        int q = dens_q(cl);
        if (band < 0)
            cl->ground_q = q;
        else if (band == 0 || cl->ground_next_q != q)
            cl->ground_next_q = band == 0 ? q : -1; /* a band of another density: mixed (made again when it changes) */
        if (!(q > 0 && cl->ke_rest > 0))
            continue;
        vec3 o = cl->cloud.origin;
        double D = (o.y + cl->cloud.bound_radius) / sd.y + 1.0;
        int rect[4];
        cu_shadow_box_rect(&cl->cloud, v3_sub(o, c), sd, v3(0, 1, 0), v3(1, 0, 0), v3(0, 0, 1), 0.5 * S, size, rect);
        for (int k = 0; k < 2; k++) {
            rect[k] = rect[k] > reg[k] ? rect[k] : reg[k];
            rect[k + 2] = rect[k + 2] < reg[k + 2] ? rect[k + 2] : reg[k + 2];
        }
        ink_add(ink, rect);
        vec3 origin = v3_add(v3_sub(c, o), v3_scale(sd, D));
        cu_pass_shadow_add(&r->pass_shadow, ctx, &cl->cloud, cl->ke_rest * q / 64.0, origin, v3(0.5 * S, 0, 0),
                           v3(0, 0, 0.5 * S), size, rect);
    }
    cu_pass_shadow_end(ctx);
    cu_gpu_scene_set_sun(ctx); /* the sky after it: the sun now */
}

/* What the square of side S about c (x, z in map g's drifting frame) shows of its clouds for the sun sd: the
 * positions (in that frame) of the clouds whose shadows can reach it, and their densities; and in pl the texels of
 * those whose density is not the one the map holds. A cloud elsewhere cannot change a texel of the map. The offset
 * keeps a scene's round numbers off the quantiser's rounding edges. */
static void ground_hashes(const cu_renderer *r, int g, vec3 drift, vec3 sd, vec3 c, double S, uint64_t *pos,
                          uint64_t *dens, patch_list *pl)
{
    *pos = *dens = 1469598103934665603ull;
    pl->n = 0;
    pl->area = 0;
    for (int j = 0; j < r->clouds.n; j++) {
        const cu_cloud_slot *cl = &r->clouds.slot[j];
        if (cl->cloud.n == 0 || !(cl->ke_rest > 0) || map_of(r, cl) != g)
            continue;
        vec3 o = v3_sub(cl->cloud.origin, drift);
        int rect[4]; /* as draw_ground has it, to the bit */
        cu_shadow_box_rect(&cl->cloud, v3_sub(cl->cloud.origin, v3_add(c, drift)), sd, v3(0, 1, 0), v3(1, 0, 0),
                           v3(0, 0, 1), 0.5 * S, GROUND_TEXELS, rect);
        if (rect[2] <= rect[0] || rect[3] <= rect[1])
            continue;
        *pos = cu_sig_add(cu_sig_add(cu_sig_add(cu_sig_add(*pos, j), 4.0 * o.x + 0.382), 4.0 * o.y + 0.382),
                          4.0 * o.z + 0.382);
        *dens = cu_sig_add(cu_sig_add(*dens, j), dens_q(cl));
        if (dens_q(cl) != cl->ground_q && pl->n <= PATCHES_MAX) {
            if (pl->n < PATCHES_MAX)
                memcpy(pl->rect[pl->n], rect, sizeof rect);
            pl->n++;
            pl->area += (long)(rect[2] - rect[0]) * (rect[3] - rect[1]);
        }
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

/* Map g brought up to date (see the top of the file) for the sun sd, the eye and the frame's state: whole when it
 * has none, a cloud moved in its drifting frame over the same square (the shadow must follow at once; a mixed map's
 * clouds do every frame they move), the ground came back into view (unseen), the camera jumped a quarter of the
 * square or the sun jumped; only the texels of the clouds whose density changed (their life cycles), when nothing
 * else did and they are no more than a band; when the sun crept, the camera moved the square on or the densities
 * changed over more, as the clouds' maps are (frame_maps.c), a band of rows a frame over quality.sun_map_frames
 * frames into a spare, swapped in whole. */
static int update_map(cu_renderer *r, int g, vec3 sd, vec3 eye, int jumped, int unseen, cu_error *err)
{
    cu_ground_map *m = &r->ground[g];
    const int size = GROUND_TEXELS;
    vec3 drift = drift_of(r, g), e = v3_sub(eye, drift);
    double S = fmin(fmax(40.0 * eye.y + 4000.0, 4000.0), 60000.0), snap = S / 16;
    vec3 c = v3(snap * floor(e.x / snap + 0.5), 0, snap * floor(e.z / snap + 0.5)); /* in the drifting frame */
    /* the sun as the map was made for while it creeps less than CU_SUN_MAP_STEP (as the clouds' own maps) */
    if (m->sig && !cu_sun_apart(m->sun, sd, CU_SUN_MAP_STEP))
        sd = m->sun;
    uint64_t pos, dens;
    patch_list pl;
    ground_hashes(r, g, drift, sd, c, S, &pos, &dens, &pl);
    uint64_t sig = cu_sig_add(cu_sig_add(cu_sig_add(cu_sig_bits(pos, dens), c.x), c.z), S);
    sig = cu_sig_add(cu_sig_add(cu_sig_add(sig, 1e6 * sd.x), 1e6 * sd.y), 1e6 * sd.z);
    if (!m->map.fbo && cu_pass_shadow_target(&r->gl, size, &m->map, err))
        return 1;
    int bands = r->scene.sun_map_frames;
    int lagged = cu_sun_apart(m->sun, sd, cu_sun_map_lag(bands));
    /* A camera flying on moves the square a sixteenth at a time: the old square still holds all but the far edge of
     * the new one. */
    int same_square = c.x == m->at.x && c.z == m->at.y && S == m->at.z;
    int moved = (same_square && pos != m->scene) || hypot(c.x - m->at.x, c.z - m->at.y) > 0.25 * S ||
                fabs(S - m->at.z) > 0.25 * S;
    /* Only densities changed (life cycles): the texels of those clouds' shadows made again at once, when they are
     * no more than a band's worth (a time-lapse of a field changes a few clouds a frame: a band of the whole map, 28
     * ms on field_noon, for a few clouds). */
    int patch = sig != m->sig && m->sig && m->band == 0 && same_square && pos == m->scene && same_vec(sd, m->sun) &&
                !jumped && pl.n <= PATCHES_MAX && pl.area * (bands == 1 || unseen ? 1 : bands) <= (long)size * size;
    if (patch) {
        m->sig = sig;
        m->patches++;
        for (int i = 0; i < pl.n; i++)
            draw_ground(r, g, &m->map, sd, v3_add(c, drift), S, pl.rect[i], -1, m->ink);
    } else if (sig != m->sig && (bands == 1 || !m->sig || jumped || lagged || moved || unseen)) {
        m->band = 0; /* a band under way is overtaken */
        m->sig = sig;
        m->scene = pos;
        m->sun = sd;
        m->at = v3(c.x, c.z, S);
        const int whole[4] = {0, 0, size, size};
        memcpy(m->ink, NO_INK, sizeof m->ink);
        draw_ground(r, g, &m->map, sd, v3_add(c, drift), S, whole, -1, m->ink);
    } else if (sig != m->sig || m->band > 0) {
        if (m->band == 0) {
            if (!m->next.fbo && cu_pass_shadow_target(&r->gl, size, &m->next, err))
                return 1;
            m->next_sig = sig;
            m->next_scene = pos;
            m->next_sun = sd;
            m->next_at = v3(c.x, c.z, S);
            memcpy(m->next_ink, NO_INK, sizeof m->next_ink);
        }
        vec3 at = m->next_at;
        int b = m->band++;
        const int rows[4] = {0, size * b / bands, size, size * (b + 1) / bands};
        draw_ground(r, g, &m->next, m->next_sun, v3(at.x + drift.x, 0, at.y + drift.z), at.z, rows, b, m->next_ink);
        if (m->band == bands) { /* the last band: the new map in, the old one the next spare */
            cu_target t = m->map;
            m->map = m->next;
            m->next = t;
            m->sig = m->next_sig;
            m->scene = m->next_scene;
            m->sun = m->next_sun;
            m->at = m->next_at;
            memcpy(m->ink, m->next_ink, sizeof m->ink);
            m->band = 0;
            for (int j = 0; j < r->clouds.n; j++)
                if (map_of(r, &r->clouds.slot[j]) == g)
                    r->clouds.slot[j].ground_q = r->clouds.slot[j].ground_next_q;
            if (sig != m->sig)
                r->maps_deferred = 1; /* the sun or the clouds moved on while the bands were drawn */
        } else {
            r->maps_deferred = 1; /* the picture has not settled */
        }
    }
    r->ctx.ground_tau[g] = m->map.tex[0];
    r->ctx.ground_map[g] = v3(m->at.x + drift.x, m->at.y + drift.z, m->at.z);
    /* the inked texels on the ground, a texel wider on every side (the sky pass filters the map bilinearly) */
    double *ink = r->ctx.ground_ink[g], side = m->at.z / size;
    vec3 at = r->ctx.ground_map[g];
    ink[0] = at.x + (m->ink[0] - 0.5 * size - 1) * side;
    ink[1] = at.y + (m->ink[1] - 0.5 * size - 1) * side;
    ink[2] = at.x + (m->ink[2] - 0.5 * size + 1) * side;
    ink[3] = at.y + (m->ink[3] - 0.5 * size + 1) * side;
    if (m->ink[2] <= m->ink[0] || m->ink[3] <= m->ink[1])
        ink[0] = 1, ink[2] = 0; /* no shadow on it */
    return 0;
}

/* The ground's shadow maps (the square's side grows with the camera's height; shadows farther away lie within a
 * fraction of a degree of the horizon); none made while no ground is in view, or without a sun to cast them. */
int cu_frame_ground_shadow(cu_renderer *r, cu_error *err)
{
    cu_gpu_scene *ctx = &r->ctx;
    for (int g = 0; g < CU_GROUND_MAPS; g++) {
        ctx->ground_tau[g] = r->pass_shadow.zero_tex;
        ctx->ground_map[g] = v3(0, 0, 1);
        ctx->ground_ink[g][0] = 1; /* nowhere */
        ctx->ground_ink[g][2] = 0;
    }
    ctx->ground_maps = 0;
    vec3 sd = ctx->sky->sun_dir, eye = ctx->camera.pos;
    if (!r->shadows || r->scene.sky_model == CU_SKY_CONSTANT || sd.y < 0.02 || ctx->camera.ortho || eye.y <= 0)
        return 0;
    if (!ground_in_view(&ctx->camera)) { /* no pixel reads the maps: left as they are (130 ms on field_noon) */
        r->ground_unseen = 1;
        return 0;
    }
    int unseen = r->ground_unseen; /* the maps were left behind while the ground was out of view */
    r->ground_unseen = 0;
    int jumped = !r->frame_sun_valid || cu_sun_apart(r->frame_sun, sd, CU_SUN_MAP_JUMP);
    assign_winds(r);
    for (int g = 0; g < r->ground_maps; g++)
        if (update_map(r, g, sd, eye, jumped, unseen, err))
            return 1;
    ctx->ground_maps = r->ground_maps;
    return 0;
}
