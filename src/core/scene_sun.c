/* src/core/scene_sun.c: a scene's sun at a scene time (see scene_sun.h). */
#include "scene_sun.h"
#include "error.h"
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
