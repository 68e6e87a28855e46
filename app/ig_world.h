/* app/ig_world.h: what a host simulation's state becomes in the renderer for `cumulo ig`: the eyepoint as the frame's
 * camera matrices, the host's date and time as the sun at the eyepoint, the host's cloud layers as [layer]s of a
 * rebuilt scene, and the layers' wrap square kept about the eye. */
#ifndef CU_APP_IG_WORLD_H
#define CU_APP_IG_WORLD_H
#include "cumulo.h"
#include "geodetic.h"
#include "sim_state.h"
#include <stddef.h>

typedef struct ig_world {
    const char *scene_name;
    char *base_text;            /* the scene file as cu_scene_format writes it: the start of every rebuilt scene */
    size_t base_len;
    double scene_fov;           /* its vertical field of view (degrees): the frustum before the host sends one */
    cu_geo_frame geo;           /* about the scene's database origin */
    double extent;              /* m: the side of the host's layers' squares (--layer-extent) */
    /* what the renderer holds now */
    int have_camera;
    float view[16], proj[16];
    double eye[3];              /* world position of the eye */
    double fwd[3], up[3];       /* where it looks, and its up, world unit vectors */
    int have_sun;
    double sun_el, sun_az;
    char utc[32];
    cu_sim_layer layers[CU_SIM_LAYERS_MAX]; /* the host's layers as last drawn (enabled 0: not drawn) */
    int layers_pending;         /* the host changed them; rebuilt when the last rebuild is old enough */
    double last_rebuild;        /* s, monotonic */
    unsigned long rebuilds;
    char notice[256];           /* a line for the log once (a cloud type cumulo does not draw, ...), or "" */
} ig_world;

/* From the scene (kept by the caller) and the layers' extent: 0, or 1 with a message. */
int  ig_world_init(ig_world *w, const cu_scene *base, const char *scene_name, double extent, char *err, size_t n);
void ig_world_free(ig_world *w);
/* Applies what st changed (its bits are cleared) to r for a width x height frame at monotonic time now (s): the camera,
 * the sun, the wrap centre, and the layers (a layer without a wind of its own takes the global one; the scene is
 * rebuilt at most twice a second; the scene time is kept).
 * 0, or 1 with a message (the renderer keeps what it had). */
int  ig_world_apply(ig_world *w, cu_sim_state *st, cu_renderer *r, int width, int height, double now, char *err,
                    size_t n);
/* The cumulo layer type ("cumulus-humilis", ...) for a host layer, or NULL when cumulo does not draw its cloud type. */
const char *ig_layer_type(const cu_sim_layer *l);
/* The [layer] sections for the host's drawn layers, appended to out (cap bytes): the length written, 0 if it does not
 * fit. base_alt: the origin's height above sea level (host bases are above sea level, cumulo's above the ground). */
size_t ig_layers_text(const cu_sim_layer *layers, double base_alt, double extent, char *out, size_t cap);

#endif
