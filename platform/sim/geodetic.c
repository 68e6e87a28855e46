/* platform/sim/geodetic.c: WGS84 geodetic positions and aviation attitudes to cumulo's world camera (geodetic.h). */
#include "geodetic.h"
#include <math.h>

#define DEG (3.14159265358979323846 / 180.0)

void cu_geo_to_ecef(double lat_deg, double lon_deg, double alt_m, double ecef[3])
{
    double e2 = CU_WGS84_F * (2.0 - CU_WGS84_F);
    double sl = sin(lat_deg * DEG), cl = cos(lat_deg * DEG);
    double n = CU_WGS84_A / sqrt(1.0 - e2 * sl * sl); /* prime vertical radius of curvature */
    ecef[0] = (n + alt_m) * cl * cos(lon_deg * DEG);
    ecef[1] = (n + alt_m) * cl * sin(lon_deg * DEG);
    ecef[2] = (n * (1.0 - e2) + alt_m) * sl;
}

/* East, north, up at a geodetic latitude and longitude, as ECEF unit vectors (rows). */
static void enu_axes(double lat_deg, double lon_deg, double m[3][3])
{
    double sl = sin(lat_deg * DEG), cl = cos(lat_deg * DEG), so = sin(lon_deg * DEG), co = cos(lon_deg * DEG);
    double e[3] = { -so, co, 0 }, n[3] = { -sl * co, -sl * so, cl }, u[3] = { cl * co, cl * so, sl };
    for (int i = 0; i < 3; i++) {
        m[0][i] = e[i];
        m[1][i] = n[i];
        m[2][i] = u[i];
    }
}

void cu_geo_frame_init(cu_geo_frame *f, double lat_deg, double lon_deg, double alt_m)
{
    f->lat0 = lat_deg;
    f->lon0 = lon_deg;
    f->alt0 = alt_m;
    cu_geo_to_ecef(lat_deg, lon_deg, alt_m, f->ecef0);
    enu_axes(lat_deg, lon_deg, f->enu);
}

/* An ECEF direction as world (x east, y up, z south) at the frame's origin. */
static void ecef_dir_to_world(const cu_geo_frame *f, const double d[3], double w[3])
{
    double e = 0, n = 0, u = 0;
    for (int i = 0; i < 3; i++) {
        e += f->enu[0][i] * d[i];
        n += f->enu[1][i] * d[i];
        u += f->enu[2][i] * d[i];
    }
    w[0] = e;
    w[1] = u;
    w[2] = -n;
}

void cu_geo_to_world(const cu_geo_frame *f, double lat_deg, double lon_deg, double alt_m, double world[3])
{
    double p[3], d[3];
    cu_geo_to_ecef(lat_deg, lon_deg, alt_m, p);
    for (int i = 0; i < 3; i++)
        d[i] = p[i] - f->ecef0[i];
    ecef_dir_to_world(f, d, world);
}

/* The body axes (forward, right, down) of yaw, pitch, roll (aerospace order z-y-x) in a north-east-down frame. */
static void body_axes(double yaw, double pitch, double roll, double fwd[3], double right[3], double down[3])
{
    double cy = cos(yaw * DEG), sy = sin(yaw * DEG), cp = cos(pitch * DEG), sp = sin(pitch * DEG);
    double cr = cos(roll * DEG), sr = sin(roll * DEG);
    /* columns of C = Rz(yaw) Ry(pitch) Rx(roll), body -> NED */
    fwd[0] = cy * cp;                     fwd[1] = sy * cp;                     fwd[2] = -sp;
    right[0] = cy * sp * sr - sy * cr;    right[1] = sy * sp * sr + cy * cr;    right[2] = cp * sr;
    down[0] = cy * sp * cr + sy * sr;     down[1] = sy * sp * cr - cy * sr;     down[2] = cp * cr;
}

/* v in the basis (a, b, c): v0 a + v1 b + v2 c */
static void combine(const double v[3], const double a[3], const double b[3], const double c[3], double out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = v[0] * a[i] + v[1] * b[i] + v[2] * c[i];
}

void cu_geo_eye(const cu_geo_frame *f, const cu_sim_state *st, double pos[3], double right[3], double up[3],
                double fwd[3])
{
    /* Local level: cumulo's sky, ground and layers are flat, so the world about the eye is the eye's own tangent
     * plane. The eye goes where the exact ECEF difference puts it east and north of the origin, at its height above
     * sea level less the origin's (not 785 m lower 100 km out, as the tangent plane at the origin would put it:
     * clouds at a constant altitude stay at a constant height over the eye), and its attitude is taken against its
     * own north and horizon (meridians converge 0.7 degree over 100 km at 47 N). */
    double p[3], d[3], w[3];
    cu_geo_to_ecef(st->lat_deg, st->lon_deg, st->alt_m, p);
    for (int i = 0; i < 3; i++)
        d[i] = p[i] - f->ecef0[i];
    ecef_dir_to_world(f, d, w);
    /* the entity's body axes and the view's in north-east-down, then as world x east, y up, z south */
    double bf[3], br[3], bd[3], vf[3], vr[3], vd[3], cf[3], cr[3], cd[3], off[3];
    body_axes(st->yaw_deg, st->pitch_deg, st->roll_deg, bf, br, bd);
    body_axes(st->view_yaw_deg, st->view_pitch_deg, st->view_roll_deg, vf, vr, vd);
    combine(vf, bf, br, bd, cf);
    combine(vr, bf, br, bd, cr);
    combine(vd, bf, br, bd, cd);
    combine(st->view_xyz, bf, br, bd, off);
    const double *ned[4] = { cf, cr, cd, off };
    double *out[4] = { fwd, right, up, pos };
    for (int k = 0; k < 4; k++) {
        double s = k == 2 ? -1.0 : 1.0; /* up is minus down */
        out[k][0] = s * ned[k][1];
        out[k][1] = -s * ned[k][2];
        out[k][2] = -s * ned[k][0];
    }
    pos[0] += w[0];
    pos[1] += st->alt_m - f->alt0;
    pos[2] += w[2];
}

void cu_geo_view_matrix(const cu_geo_frame *f, const cu_sim_state *st, float view[16])
{
    double p[3], r[3], u[3], fw[3];
    cu_geo_eye(f, st, p, r, u, fw);
    /* rows: right, up, back (the eye looks down -z) */
    const double *rows[3] = { r, u, fw };
    for (int i = 0; i < 3; i++) {
        double s = i == 2 ? -1.0 : 1.0, t = 0;
        for (int j = 0; j < 3; j++) {
            view[j * 4 + i] = (float)(s * rows[i][j]);
            t += s * rows[i][j] * p[j];
        }
        view[12 + i] = (float)-t;
    }
    view[3] = view[7] = view[11] = 0.0f;
    view[15] = 1.0f;
}

void cu_geo_projection(double left_deg, double right_deg, double bottom_deg, double top_deg, double aspect,
                       double n, double f, float proj[16])
{
    double l = n * tan(left_deg * DEG), r = n * tan(right_deg * DEG);
    double b = n * tan(bottom_deg * DEG), t = n * tan(top_deg * DEG);
    if (bottom_deg == 0 && top_deg == 0 && aspect > 0) {
        double h = 0.5 * (r - l) / aspect, c = 0; /* centred vertically */
        b = c - h;
        t = c + h;
    }
    for (int i = 0; i < 16; i++)
        proj[i] = 0.0f;
    proj[0] = (float)(2 * n / (r - l));
    proj[5] = (float)(2 * n / (t - b));
    proj[8] = (float)((r + l) / (r - l));
    proj[9] = (float)((t + b) / (t - b));
    proj[10] = (float)(-(f + n) / (f - n));
    proj[11] = -1.0f;
    proj[14] = (float)(-2 * f * n / (f - n));
}
