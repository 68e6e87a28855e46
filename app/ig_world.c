/* app/ig_world.c: a host simulation's state applied to the renderer (ig_world.h). */
#include "ig_world.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define REBUILD_INTERVAL 0.5 /* s: a host ramping coverage rebuilds the layers twice a second, not every frame */

int ig_world_init(ig_world *w, const cu_scene *base, const char *scene_name, double extent, char *err, size_t n)
{
    memset(w, 0, sizeof *w);
    w->scene_name = scene_name;
    w->extent = extent;
    w->last_rebuild = -1e30;
    for (size_t cap = 1 << 16; cap <= (size_t)1 << 28; cap *= 4) {
        char *buf = malloc(cap);
        if (!buf)
            break;
        size_t len = cu_scene_format(base, buf, cap);
        if (len) {
            w->base_text = buf;
            w->base_len = len;
            break;
        }
        free(buf);
    }
    if (!w->base_text) {
        snprintf(err, n, "%s: cannot hold the scene as text (out of memory)", scene_name);
        return 1;
    }
    double lat, lon, alt, pos[3], look[3];
    cu_scene_origin(base, &lat, &lon, &alt);
    cu_geo_frame_init(&w->geo, lat, lon, alt);
    cu_scene_camera(base, pos, look, &w->scene_fov);
    return 0;
}

void ig_world_free(ig_world *w)
{
    free(w->base_text);
    w->base_text = NULL;
}

const char *ig_layer_type(const cu_sim_layer *l)
{
    /* cumulo draws cumulus: the species by the layer's depth (WMO: humilis flat, mediocris moderate, congestus
     * towering); a cumulonimbus is drawn as the congestus it grows from, without its anvil. */
    if (l->type == CU_SIM_CLOUD_CUMULUS)
        return l->thickness_m < 700 ? "cumulus-humilis" : l->thickness_m < 2500 ? "cumulus-mediocris"
                                                                                 : "cumulus-congestus";
    if (l->type == CU_SIM_CLOUD_CUMULONIMBUS)
        return "cumulus-congestus";
    return NULL;
}

/* A host layer cumulo draws: enabled, a cumulus type, some cover. */
static int drawn(const cu_sim_layer *l)
{
    return l->enabled && ig_layer_type(l) && l->coverage > 0 && l->thickness_m > 0;
}

size_t ig_layers_text(const cu_sim_layer *layers, double base_alt, double extent, char *out, size_t cap)
{
    size_t len = 0;
    for (int i = 0; i < CU_SIM_LAYERS_MAX; i++) {
        const cu_sim_layer *l = &layers[i];
        if (!drawn(l))
            continue;
        /* the wind blows from wind_from_deg: it moves the clouds toward the opposite bearing */
        double d = l->wind_from_deg * 3.14159265358979323846 / 180.0;
        double east = -l->wind_speed * sin(d), north = -l->wind_speed * cos(d);
        double base = fmax(0.0, l->base_m - base_alt), thick = fmin(15000.0, fmax(50.0, l->thickness_m));
        int k = snprintf(out + len, cap - len,
                         "[layer]\ntype = %s\nbase = %.3f\nthickness = %.3f\ncoverage = %.6f\nextent = %.3f\n"
                         "seed = %d\nwind = %.4f %.4f\n",
                         ig_layer_type(l), fmin(base, 20000.0), thick, fmin(1.0, l->coverage), extent, i + 1,
                         fmax(-200.0, fmin(200.0, east)), fmax(-200.0, fmin(200.0, north)));
        if (k < 0 || (size_t)k >= cap - len)
            return 0;
        len += (size_t)k;
    }
    if (len < cap)
        out[len] = 0;
    return len;
}

/* Two layer sets that draw the same within what a host's float jitter changes. */
static int same_layers(const cu_sim_layer *a, const cu_sim_layer *b)
{
    for (int i = 0; i < CU_SIM_LAYERS_MAX; i++) {
        int da = drawn(&a[i]), db = drawn(&b[i]);
        if (da != db)
            return 0;
        if (!da)
            continue;
        if (ig_layer_type(&a[i]) != ig_layer_type(&b[i]) || fabs(a[i].coverage - b[i].coverage) > 1e-3 ||
            fabs(a[i].base_m - b[i].base_m) > 0.5 || fabs(a[i].thickness_m - b[i].thickness_m) > 0.5 ||
            fabs(a[i].wind_speed - b[i].wind_speed) > 0.05 || fabs(a[i].wind_from_deg - b[i].wind_from_deg) > 0.5)
            return 0;
    }
    return 1;
}

/* The scene again with the host's layers; the renderer's time and sun are put back. */
static int rebuild(ig_world *w, const cu_sim_layer *layers, cu_renderer *r, char *err, size_t n)
{
    size_t cap = w->base_len + 4096;
    char *text = malloc(cap);
    if (!text) {
        snprintf(err, n, "layers: out of memory");
        return 1;
    }
    memcpy(text, w->base_text, w->base_len);
    size_t extra = ig_layers_text(layers, w->geo.alt0, w->extent, text + w->base_len, cap - w->base_len);
    cu_scene *s = NULL;
    cu_error e;
    double t = cu_renderer_get_time(r), el, az;
    cu_renderer_get_sun(r, &el, &az);
    int rc = cu_scene_parse(&s, w->scene_name, text, w->base_len + extra, &e) || cu_renderer_set_scene(r, s, &e) ||
             cu_renderer_set_time(r, t, &e) || cu_renderer_set_sun(r, el, az, &e);
    if (rc)
        snprintf(err, n, "layers: %s", e.msg);
    cu_scene_free(s);
    free(text);
    return rc;
}

/* The ISO 8601 form of the host's date and time. */
static void iso_time(const cu_sim_state *st, char *buf, size_t n)
{
    snprintf(buf, n, "%04d-%02d-%02dT%02d:%02d:%02dZ", st->year, st->month, st->day, st->hour, st->minute,
             (int)floor(st->second));
}

static int apply_sun(ig_world *w, const cu_sim_state *st, cu_renderer *r, char *err, size_t n)
{
    char utc[32];
    iso_time(st, utc, sizeof utc);
    double lat = st->pose_valid ? st->lat_deg : w->geo.lat0, lon = st->pose_valid ? st->lon_deg : w->geo.lon0;
    double alt = st->pose_valid ? st->alt_m : w->geo.alt0, el, az;
    cu_error e;
    /* the sun is seen from the eyepoint, at the host's time; geometric, as the renderer's own set_sun_utc */
    if (cu_solar_position_at(utc, lat, lon, fmax(0.0, fmin(alt, 8000.0)), 0, &el, &az, &e) ||
        cu_renderer_set_sun(r, el, az, &e)) {
        snprintf(err, n, "sun: %s", e.msg);
        return 1;
    }
    snprintf(w->utc, sizeof w->utc, "%s", utc);
    w->have_sun = 1;
    w->sun_el = el;
    w->sun_az = az;
    return 0;
}

static void apply_camera(ig_world *w, const cu_sim_state *st, int width, int height)
{
    cu_geo_view_matrix(&w->geo, st, w->view);
    double right[3];
    cu_geo_eye(&w->geo, st, w->eye, right, w->up, w->fwd);
    double aspect = height > 0 ? (double)width / height : 1.0;
    double nr = 1.0, fr = 1e6;
    if (st->frustum_valid) {
        if (st->near_m > 0 && st->far_m > st->near_m) {
            nr = st->near_m;
            fr = st->far_m;
        }
        cu_geo_projection(st->fov_left_deg, st->fov_right_deg, st->fov_bottom_deg, st->fov_top_deg, aspect, nr, fr,
                          w->proj);
    } else { /* the scene's vertical field of view, centred */
        double h = 0.5 * w->scene_fov, hw = atan(tan(h * 3.14159265358979323846 / 180.0) * aspect) * 180.0 /
                                                 3.14159265358979323846;
        cu_geo_projection(-hw, hw, -h, h, aspect, nr, fr, w->proj);
    }
    w->have_camera = 1;
}

int ig_world_apply(ig_world *w, cu_sim_state *st, cu_renderer *r, int width, int height, double now, char *err,
                   size_t n)
{
    unsigned ch = st->changed;
    st->changed = 0;
    w->notice[0] = 0;
    if (st->pose_valid && (ch & (CU_SIM_POSE | CU_SIM_VIEW | CU_SIM_FRUSTUM) || !w->have_camera))
        apply_camera(w, st, width, height);
    if (w->have_camera) {
        cu_error e;
        if (cu_renderer_set_wrap_center(r, w->eye[0], w->eye[2], &e)) {
            snprintf(err, n, "eyepoint: %s", e.msg);
            return 1;
        }
    }
    if (st->time_valid && (ch & (CU_SIM_TIME | CU_SIM_POSE) || !w->have_sun) && apply_sun(w, st, r, err, n))
        return 1;
    /* A layer without a wind of its own drifts with the global one (CIGI Atmosphere Control). */
    cu_sim_layer eff[CU_SIM_LAYERS_MAX];
    memcpy(eff, st->layers, sizeof eff);
    for (int i = 0; i < CU_SIM_LAYERS_MAX; i++)
        if (eff[i].wind_speed == 0 && st->wind_valid) {
            eff[i].wind_speed = st->wind_speed;
            eff[i].wind_from_deg = st->wind_from_deg;
        }
    if (ch & (CU_SIM_LAYERS | CU_SIM_WIND)) {
        for (int i = 0; i < CU_SIM_LAYERS_MAX; i++) {
            const cu_sim_layer *l = &st->layers[i];
            if (l->enabled && l->coverage > 0 && !ig_layer_type(l))
                snprintf(w->notice, sizeof w->notice, "layer %d: cloud type %d is not drawn (cumulo draws cumulus; "
                         "cumulonimbus as congestus)", i + 1, l->type);
            else if (l->enabled && l->coverage > 0 && (l->scud || l->transition_m > 0))
                snprintf(w->notice, sizeof w->notice, "layer %d: scud and the transition band are not modelled",
                         i + 1);
        }
        w->layers_pending = !same_layers(eff, w->layers);
    }
    if (w->layers_pending && now - w->last_rebuild >= REBUILD_INTERVAL) {
        w->last_rebuild = now;
        w->layers_pending = 0;
        if (rebuild(w, eff, r, err, n))
            return 1;
        memcpy(w->layers, eff, sizeof w->layers);
        w->rebuilds++;
    }
    return 0;
}
