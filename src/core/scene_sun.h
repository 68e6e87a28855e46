/* src/core/scene_sun.h: where a scene's sun is at a scene time: its [sun] angles, or with time_utc the solar position
 * (solar.c) at time_utc + t seconds, at the scene's latitude and longitude. */
#ifndef CU_SCENE_SUN_H
#define CU_SCENE_SUN_H
#include "scene.h"

/* Elevation and azimuth in degrees; fails when time_utc + t leaves 1900..2100. */
int cu_scene_sun_at(const cu_scene *s, double t, double *elevation_deg, double *azimuth_deg, cu_error *err);
#endif
