/* src/gpu/frame_maps.c: each visible cloud's sun and slab maps. Made when the cloud is first drawn, at the level of
 * detail its size on screen asks for, and made again at once when it takes a new look or the sun jumps; when the sun
 * creeps or the noise boils on, a few clouds a frame, and spread over quality.sun_map_frames frames: a band of the
 * maps' rows a frame drawn into spare targets, lit by the sun of the band's first frame, the whole swapped in with the
 * last band. A sun turned every frame then costs 1/sun_map_frames of the maps a frame, and the cloud is lit, whole
 * and consistently, by a sun at most 2 sun_map_frames - 1 frames old. */
#include "frame.h"
#include "sunmap.h"
#include "upload.h"
#include <math.h>

/* A cloud's GL objects, made the first time it is drawn: a field of thousands of clouds pays for the ones seen. */
static int cloud_objects(cu_renderer *r, cu_cloud_slot *sl, cu_error *err)
{
    cu_gpu_scene *ctx = &r->ctx;
    if (!sl->vao)
        cu_upload_instances(ctx, &sl->cloud, &sl->inst_vbo, &sl->vao);
    if (r->scene.method == CU_METHOD_UNIFORM)
        return 0; /* it marches toward the sun at every sample: no maps to make */
    if (sl->has_maps && sl->want_size <= sl->map_size)
        return 0; /* maps only grow: a cloud that recedes keeps its sharper maps (no churn at a size boundary) */
    if (sl->has_maps)
        cu_cloud_slot_free_maps(sl, &r->gl); /* the spares too: a band under way is dropped */
    sl->map_size = sl->want_size;
    if (cu_pass_sun_map_create(&r->pass_sun, &r->gl, sl->map_size, &sl->sun_map, &sl->sun, err) ||
        cu_pass_slab_maps_create(&r->pass_slab, ctx, sl->map_size, sl->slab_map, &sl->slab, err))
        return 1;
    sl->has_maps = 1;
    return 0;
}

/* Binds cloud sl at its mature density, lit by sun: the maps are made at ke_scale 1 (the shaders scale the optical
 * depths they read by the density now). Returns its density factor now, which the caller gives back. */
static double bind_mature(cu_renderer *r, cu_cloud_slot *sl, vec3 sun)
{
    cu_gpu_scene *ctx = &r->ctx;
    double f = sl->factor;
    sl->factor = 1;
    cu_frame_bind_cloud(r, sl);
    sl->cloud.ke = sl->ke_rest;
    ctx->sun_dir = sun;
    cu_sun_basis(sun, &ctx->sun_right, &ctx->sun_up);
    return f;
}

/* ms.mode = diffusion: cloud sl's grid for the sun of its maps, within the frame's work (pass_msd.h); a solve left for
 * later frames keeps the picture from settling, so that a still camera's frames go on until it is done. */
static int msd_update(cu_renderer *r, cu_cloud_slot *sl, int resample, cu_error *err)
{
    if (r->ctx.ms_mode != CU_MS_DIFFUSION)
        return 0;
    /* a scene's first frame solves every grid whole: a still image, or a sky's start, gets each cloud's own light */
    int rc = cu_pass_msd_update(&r->ctx, &sl->msd, &sl->cloud, sl->maps_sun, resample, r->drawn ? &r->msd_work : NULL,
                                err);
    if (sl->msd.pending)
        r->maps_deferred = 1;
    return rc;
}

/* The whole of cloud sl's maps, now, for the sun now (and the zenith's when the noise moved on). */
static int remake_whole(cu_renderer *r, cu_cloud_slot *sl, int boiled, cu_error *err)
{
    cu_gpu_scene *ctx = &r->ctx;
    int resample = boiled || !sl->maps_valid; /* the grid's density: a new look, or the noise boiled on */
    if (boiled)
        sl->zenith_valid = 0;
    sl->next_band = 0; /* a band under way is overtaken */
    sl->maps_boil = sl->boil;
    sl->maps_sun = ctx->sky->sun_dir;
    sl->maps_valid = 1; /* what cu_frame_bind_cloud lights it with, from now */
    double f = bind_mature(r, sl, sl->maps_sun);
    cu_pass_sun_update(&r->pass_sun, ctx, &sl->sun_map, NULL, &sl->sun);
    ctx->sun = sl->sun;
    cu_pass_slab_update(&r->pass_slab, ctx, 0, sl->slab_map, NULL, &sl->slab, 1);
    if (!sl->zenith_valid)
        cu_pass_slab_update(&r->pass_slab, ctx, 1, sl->slab_map, NULL, &sl->slab, 1);
    sl->zenith_valid = 1;
    int rc = msd_update(r, sl, resample, err);
    sl->factor = f;
    return rc;
}

static void swap_targets(cu_target *a, cu_target *b)
{
    cu_target t = *a;
    *a = *b;
    *b = t;
}

/* The spare targets a band is drawn into: as the cloud's own maps. */
static int spares(cu_renderer *r, cu_cloud_slot *sl, cu_error *err)
{
    if (sl->next_sun_map.fbo)
        return 0;
    cu_slab_maps unused;
    return cu_pass_sun_map_create(&r->pass_sun, &r->gl, sl->map_size, &sl->next_sun_map, &sl->next_sun_maps, err) ||
           cu_pass_slab_maps_create(&r->pass_slab, &r->ctx, sl->map_size, sl->next_slab_map, &unused, err);
}

/* One band of rows of the maps being made again for sl->next_sun; the last one swaps them in. */
static int remake_band(cu_renderer *r, cu_cloud_slot *sl, int boiled, cu_error *err)
{
    cu_gpu_scene *ctx = &r->ctx;
    const cu_gl *gl = &r->gl;
    int bands = r->scene.sun_map_frames;
    if (sl->next_band == 0) {
        if (spares(r, sl, err))
            return 1;
        sl->next_sun = ctx->sky->sun_dir;
        sl->next_boil = sl->boil;
        sl->next_zenith = boiled;
    }
    double f = bind_mature(r, sl, sl->next_sun);
    if (sl->next_band == 0) { /* the bands share out the rows of the map's box: equal work a frame */
        int box[4];
        cu_sun_map_texels(ctx->cloud, ctx->sun_right, ctx->sun_up, ctx->sun_R, ctx->sun_size, box);
        sl->next_box[0] = box[1];
        sl->next_box[1] = box[3];
    }
    int rows[2]; /* every tile of the row band (the sun map's tiles lie side by side) */
    cu_sun_band_rows(ctx->sun_size, sl->next_box[0], sl->next_box[1], bands, sl->next_band, rows);
    int last = ++sl->next_band == bands;
    cu_slab_maps slab = sl->slab;
    cu_pass_sun_update(&r->pass_sun, ctx, &sl->next_sun_map, rows, &sl->next_sun_maps);
    ctx->sun = sl->next_sun_maps;
    cu_pass_slab_update(&r->pass_slab, ctx, 0, sl->next_slab_map, rows, &slab, last);
    if (sl->next_zenith)
        cu_pass_slab_update(&r->pass_slab, ctx, 1, sl->next_slab_map, rows, &slab, last);
    gl->Disable(GL_SCISSOR_TEST);
    if (!last) {
        sl->factor = f;
        r->maps_deferred = 1; /* the picture has not settled: the cloud is lit by its old maps until the last band */
        return 0;
    }
    /* the last band: the new maps in, the old ones the next spares */
    sl->next_band = 0;
    swap_targets(&sl->sun_map, &sl->next_sun_map);
    cu_sun_maps t = sl->sun;
    sl->sun = sl->next_sun_maps;
    sl->next_sun_maps = t;
    for (int i = 0; i < 1 + sl->next_zenith; i++) {
        swap_targets(&sl->slab_map[i], &sl->next_slab_map[i]);
        if (sl->slab_map[i].fbo) {
            sl->slab.a[i] = sl->slab_map[i].tex[0];
            sl->slab.n[i] = sl->slab_map[i].tex[1];
        }
    }
    if (sl->next_zenith) {
        sl->slab.sky_right = slab.sky_right;
        sl->slab.sky_up = slab.sky_up;
    }
    sl->maps_sun = sl->next_sun;
    sl->maps_boil = sl->next_boil;
    r->sun_dirty = 1; /* the energy closure follows the maps' sun (it keeps its gains within a degree of it) */
    if (cu_sun_apart(sl->maps_sun, ctx->sky->sun_dir, CU_SUN_MAP_STEP) ||
        v3_len(v3_sub(sl->boil, sl->maps_boil)) > CU_BOIL_STEP)
        r->maps_deferred = 1; /* the sun or the noise moved on while the bands were drawn: more to come */
    cu_frame_bind_cloud(r, sl); /* its new maps, for the diffusion grid */
    int rc = msd_update(r, sl, sl->next_zenith, err);
    sl->factor = f;
    return rc;
}

/* Cloud sl's maps seen from the sun (and the zenith), brought up to date (see the top of this file). Remade whole at
 * once when it has none, took a new look, the sun jumped more than CU_SUN_MAP_JUMP since the last frame or its maps
 * fell more than cu_sun_map_lag behind; when the sun crept past CU_SUN_MAP_STEP or the noise boiled past
 * CU_BOIL_STEP, a band while *budget lasts (a few bands a frame, nearest clouds first): until the last band the
 * cloud is lit by the sun its maps were made for (cu_frame_bind_cloud), consistently. */
int cu_frame_cloud_maps(cu_renderer *r, cu_cloud_slot *sl, int *budget, cu_error *err)
{
    cu_gpu_scene *ctx = &r->ctx;
    if (cloud_objects(r, sl, err))
        return 1;
    if (r->scene.method == CU_METHOD_UNIFORM)
        return 0;
    vec3 sun = ctx->sky->sun_dir;
    int boiled = v3_len(v3_sub(sl->boil, sl->maps_boil)) > CU_BOIL_STEP;
    int crept = cu_sun_apart(sl->maps_sun, sun, CU_SUN_MAP_STEP);
    int jumped = r->frame_sun_valid && cu_sun_apart(r->frame_sun, sun, CU_SUN_MAP_JUMP);
    int lagged = cu_sun_apart(sl->maps_sun, sun, cu_sun_map_lag(r->scene.sun_map_frames));
    if (!sl->maps_valid || !sl->zenith_valid || jumped || lagged)
        return remake_whole(r, sl, boiled, err);
    if (!boiled && !crept && sl->next_band == 0) /* up to date; a grid a busier frame left behind catches up */
        return msd_update(r, sl, 0, err);
    if (*budget <= 0) {
        r->maps_deferred = 1; /* its turn comes in a later frame: the picture has not settled */
        return 0;
    }
    (*budget)--;
    return r->scene.sun_map_frames > 1 ? remake_band(r, sl, boiled, err) : remake_whole(r, sl, boiled, err);
}
