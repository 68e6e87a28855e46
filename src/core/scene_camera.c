/* src/core/scene_camera.c: the scene's [camera] (and where its world is on Earth) as view and projection matrices, the form a host passes in
 * cu_frame (the renderer builds its frame camera from the same matrices, src/gpu/camera.c). */
#include "scene_camera.h"
#include "error.h"

mat4 cu_scene_view(const cu_scene *s)
{
    vec3 eye = v3_from(s->cam_pos);
    return m4_look_dir(eye, v3_norm(v3_sub(v3_from(s->cam_look), eye)), v3(0, 1, 0));
}

int cu_scene_camera_matrices(const cu_scene *s, double aspect, double znear, double zfar, float view[16],
                             float projection[16], cu_error *err)
{
    if (!(aspect > 0) || !isfinite(aspect) || !(znear > 0) || !(zfar > znear) || !isfinite(zfar))
        return cu_fail(err, "camera matrices: need aspect > 0 and 0 < znear < zfar, all finite (got aspect %.9g, "
                            "znear %.9g, zfar %.9g)", aspect, znear, zfar);
    m4_to_float(cu_scene_view(s), view);
    m4_to_float(m4_perspective(s->cam_fov * CU_PI / 180.0, aspect, znear, zfar), projection);
    return 0;
}

void cu_scene_camera(const cu_scene *s, double position[3], double look_at[3], double *fov_deg)
{
    for (int i = 0; i < 3; i++) {
        position[i] = s->cam_pos[i];
        look_at[i] = s->cam_look[i];
    }
    *fov_deg = s->cam_fov;
}

void cu_scene_origin(const cu_scene *s, double *latitude_deg, double *longitude_deg, double *altitude_m)
{
    *latitude_deg = s->origin_lat;
    *longitude_deg = s->origin_lon;
    *altitude_m = s->origin_alt;
}
