/* src/core/scene_sun.c: a scene's sun at a scene time (see scene_sun.h), and its place (cu_scene_sun_place). */
#include "scene_sun.h"
#include "error.h"
#include "scene_keys.h"
#include "solar.h"

int cu_scene_sun_at(const cu_scene *s, double t, double *el, double *az, cu_error *err)
{
    if (!s->has_time_utc) {
        *el = s->sun_elevation;
        *az = s->sun_azimuth;
        return 0;
    }
    cu_utc u;
    cu_solar_angles a;
    if (cu_utc_parse(s->time_utc, &u, err))
        return 1;
    if (cu_utc_add_seconds(&u, t))
        return cu_fail(err, "[sun] time_utc %s plus [scene] time %g s leaves the years 1900..2100 the solar position "
                            "covers", s->time_utc, t);
    /* geometric elevation (no refraction) seen from the ground: the direction the renderer's sunlight comes from */
    if (cu_solar_position(&u, s->latitude, s->longitude, 0.0, 0, &a, err))
        return 1;
    *el = a.elevation;
    *az = a.azimuth;
    return 0;
}

int cu_scene_sun_place(const cu_scene *s, double *latitude_deg, double *longitude_deg)
{
    *latitude_deg = s->latitude;
    *longitude_deg = s->longitude;
    return s->explicit_key[cu_scene_key_find("sun", "latitude") - cu_scene_keys] ||
           s->explicit_key[cu_scene_key_find("sun", "longitude") - cu_scene_keys];
}
