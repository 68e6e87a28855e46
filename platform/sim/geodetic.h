/* platform/sim/geodetic.h: a host simulation's geodetic eyepoint as cumulo's world camera: WGS84 latitude, longitude
 * and height to metres east, up and south of a database origin, and an aviation attitude (heading, pitch, roll) with a
 * view offset to a view matrix. The horizontal offset is exact ECEF arithmetic in double; the eye is then put in its
 * own local-level frame (cu_geo_eye), because cumulo's ground and layers are flat. */
#ifndef CU_PLATFORM_SIM_GEODETIC_H
#define CU_PLATFORM_SIM_GEODETIC_H
#include "sim_state.h"

/* WGS84 (NIMA TR8350.2): semi-major axis and flattening. */
#define CU_WGS84_A 6378137.0
#define CU_WGS84_F (1.0 / 298.257223563)

/* The local frame: east-north-up at the origin's point on the ellipsoid, as cumulo's world (x east, y up, z south). */
typedef struct cu_geo_frame {
    double lat0, lon0, alt0;   /* degrees, degrees, m */
    double ecef0[3];           /* the origin, m */
    double enu[3][3];          /* rows: east, north, up in ECEF */
} cu_geo_frame;

void cu_geo_frame_init(cu_geo_frame *f, double lat_deg, double lon_deg, double alt_m);
/* WGS84 geodetic to Earth-centred, Earth-fixed metres. Heights are taken as above the ellipsoid: the geoid's
 * 100 m undulation is the same at the origin and at the eye within a few metres over a database's 100 km. */
void cu_geo_to_ecef(double lat_deg, double lon_deg, double alt_m, double ecef[3]);
/* A geodetic point as world metres (x east, y up, z south) about the frame's origin. */
void cu_geo_to_world(const cu_geo_frame *f, double lat_deg, double lon_deg, double alt_m, double world[3]);

/* The eyepoint of st (entity pose, then the view offset in the entity's body frame and the view's rotation) as a
 * world position and the camera's axes in world coordinates (right, up, and forward = where it looks): east and
 * south of the origin as cu_geo_to_world has them, up = its altitude less the origin's, and its attitude against
 * its own north and horizon (local level: a flat world about the eye; see geodetic.c). */
void cu_geo_eye(const cu_geo_frame *f, const cu_sim_state *st, double pos[3], double right[3], double up[3],
                double fwd[3]);
/* The same as a column-major view matrix (world -> eye; the eye looks down -z) for cu_frame. */
void cu_geo_view_matrix(const cu_geo_frame *f, const cu_sim_state *st, float view[16]);
/* A column-major perspective projection from half-angles in degrees (left, bottom negative for a centred view):
 * glFrustum's with near n and far f. aspect > 0 fills top and bottom when both are 0 (a horizontal field of view
 * alone, FlightGear's). */
void cu_geo_projection(double left_deg, double right_deg, double bottom_deg, double top_deg, double aspect,
                       double n, double f, float proj[16]);

#endif
