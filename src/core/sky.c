/* src/core/sky.c: Preetham daylight model (see sky.h). */
#include "sky.h"

#define TOA_ILLUMINANCE 128.0 /* klx: solar illuminance outside the atmosphere; the sun is taken as white there */

/* The Perez function's two factors: of the zenith angle, then of the angle to the sun. cos theta is clamped away
 * from 0: exp(B / cos theta) is singular at the horizon. */
static double perez_zenith(const double *c, double cos_theta)
{
    double ct = cos_theta > 0.01 ? cos_theta : 0.01;
    return 1.0 + c[0] * exp(c[1] / ct);
}

static double perez_sun(const double *c, double gamma)
{
    return 1.0 + c[2] * exp(c[3] * gamma) + c[4] * cos(gamma) * cos(gamma);
}

static double perez_f(const double *c, double cos_theta, double gamma)
{
    return perez_zenith(c, cos_theta) * perez_sun(c, gamma);
}

static void xyY_to_rgb(double x, double y, double Y, double out[3])
{
    double yy = y > 1e-4 ? y : 1e-4;
    double X = Y * x / yy, Z = Y * (1.0 - x - y) / yy;
    out[0] = 3.2406 * X - 1.5372 * Y - 0.4986 * Z;
    out[1] = -0.9689 * X + 1.8758 * Y + 0.0415 * Z;
    out[2] = 0.0557 * X - 0.2040 * Y + 1.0570 * Z;
    for (int i = 0; i < 3; i++)
        if (out[i] < 0) out[i] = 0;
}

void cu_sky_radiance(const cu_sky *sky, const cu_scene *s, vec3 dir, double out[3])
{
    if (s->sky_model == CU_SKY_CONSTANT) {
        for (int i = 0; i < 3; i++)
            out[i] = s->sky_color[i];
        return;
    }
    double cg = v3_dot(dir, sky->sun_dir);
    cg = cg > 1 ? 1 : cg < -1 ? -1 : cg;
    double gamma = acos(cg);
    double v[3];
    for (int k = 0; k < 3; k++)
        v[k] = sky->zenith[k] * perez_f(sky->perez + 5 * k, dir.y, gamma) / sky->norm[k];
    xyY_to_rgb(v[1], v[2], v[0], out);
}

void cu_sky_tables(const cu_sky *sky, float zenith_part[4 * CU_SKY_TABLE], float sun_part[4 * CU_SKY_TABLE])
{
    for (int i = 0; i < CU_SKY_TABLE; i++) {
        double t = (double)i / (CU_SKY_TABLE - 1);
        double gamma = 2.0 * asin(t);
        for (int k = 0; k < 3; k++) {
            const double *c = sky->perez + 5 * k;
            zenith_part[4 * i + k] = (float)(sky->zenith[k] / sky->norm[k] * perez_zenith(c, t * t));
            sun_part[4 * i + k] = (float)perez_sun(c, gamma);
        }
        zenith_part[4 * i + 3] = sun_part[4 * i + 3] = 1.0f;
    }
}

/* Entry t in 0..1 of a table, interpolated (sky.glsl's table()). */
static void table_at(const float *part, double t, double out[3])
{
    double f = t * (CU_SKY_TABLE - 1);
    int i = (int)f < CU_SKY_TABLE - 2 ? (int)f : CU_SKY_TABLE - 2;
    for (int k = 0; k < 3; k++)
        out[k] = part[4 * i + k] + (part[4 * (i + 1) + k] - part[4 * i + k]) * (f - i);
}

void cu_sky_from_tables(const float zenith_part[4 * CU_SKY_TABLE], const float sun_part[4 * CU_SKY_TABLE],
                        vec3 sun_dir, vec3 dir, double out[3])
{
    double s = 0.5 - 0.5 * v3_dot(dir, sun_dir), z[3], g[3];
    table_at(zenith_part, sqrt(dir.y > 0 ? dir.y : 0), z);
    table_at(sun_part, sqrt(s < 0 ? 0 : s > 1 ? 1 : s), g);
    xyY_to_rgb(z[1] * g[1], z[2] * g[2], z[0] * g[0], out);
}

void cu_sky_compute(cu_sky *sky, const cu_scene *s)
{
    double T = s->turbidity;
    sky->sun_dir = cu_sun_direction(s->sun_elevation, s->sun_azimuth);
    /* The model is fitted for the sun above the horizon; below it we keep the geometry of a sun at the horizon and
     * fade everything with an exponential twilight term so nothing is singular or negative. */
    double el = s->sun_elevation;
    double el_model = el < 0.5 ? 0.5 : el;
    double ts = (90.0 - el_model) * CU_PI / 180.0;
    double twilight = el < 0.5 ? exp((el - 0.5) / 2.0) : 1.0;

    const double cY[5] = {0.1787 * T - 1.4630, -0.3554 * T + 0.4275, -0.0227 * T + 5.3251, 0.1206 * T - 2.5771,
                          -0.0670 * T + 0.3703};
    const double cx[5] = {-0.0193 * T - 0.2592, -0.0665 * T + 0.0008, -0.0004 * T + 0.2125, -0.0641 * T - 0.8989,
                          -0.0033 * T + 0.0452};
    const double cy[5] = {-0.0167 * T - 0.2608, -0.0950 * T + 0.0092, -0.0079 * T + 0.2102, -0.0441 * T - 1.6537,
                          -0.0109 * T + 0.0529};
    for (int i = 0; i < 5; i++) {
        sky->perez[i] = cY[i];
        sky->perez[5 + i] = cx[i];
        sky->perez[10 + i] = cy[i];
    }
    double chi = (4.0 / 9.0 - T / 120.0) * (CU_PI - 2.0 * ts);
    double Yz = (4.0453 * T - 4.9710) * tan(chi) - 0.2155 * T + 2.4192;
    if (Yz < 0.01) Yz = 0.01;
    double t2 = ts * ts, t3 = t2 * ts;
    double xz = T * T * (0.00166 * t3 - 0.00375 * t2 + 0.00209 * ts) +
                T * (-0.02903 * t3 + 0.06377 * t2 - 0.03202 * ts + 0.00394) +
                (0.11693 * t3 - 0.21196 * t2 + 0.06052 * ts + 0.25886);
    double yz = T * T * (0.00275 * t3 - 0.00610 * t2 + 0.00317 * ts) +
                T * (-0.04214 * t3 + 0.08970 * t2 - 0.04153 * ts + 0.00516) +
                (0.15346 * t3 - 0.26756 * t2 + 0.06670 * ts + 0.26688);
    sky->zenith[0] = Yz * twilight;
    sky->zenith[1] = xz;
    sky->zenith[2] = yz;
    for (int k = 0; k < 3; k++)
        sky->norm[k] = perez_f(sky->perez + 5 * k, 1.0, ts);

    if (s->has_sun_irradiance) {
        for (int c = 0; c < 3; c++)
            sky->sun_irradiance[c] = s->sun_irradiance[c];
    } else {
        /* Preetham Appendix: Rayleigh and aerosol (Angstrom, alpha = 1.3) transmittance along the relative optical
         * mass m (Kasten's formula), at representative wavelengths for R, G, B. Ozone and water vapour are left out:
         * they change the sun's colour by a few percent. */
        static const double lambda_um[3] = {0.680, 0.550, 0.440};
        double zen_deg = 90.0 - el_model;
        double m = 1.0 / (cos(zen_deg * CU_PI / 180.0) + 0.15 * pow(93.885 - zen_deg, -1.253));
        double beta = 0.04608365822050 * T - 0.04586025928522;
        for (int c = 0; c < 3; c++) {
            double tr = exp(-0.008735 * pow(lambda_um[c], -4.08) * m);
            double ta = exp(-beta * pow(lambda_um[c], -1.3) * m);
            sky->sun_irradiance[c] = TOA_ILLUMINANCE * tr * ta * twilight;
        }
    }
    /* Sky irradiance on the ground: integrate the sky's radiance over the upper hemisphere (cosine-weighted). */
    double E[3] = {0, 0, 0}, M[3] = {0, 0, 0};
    const int NT = 24, NP = 48;
    for (int i = 0; i < NT; i++) {
        double th = (i + 0.5) * (CU_PI / 2) / NT;
        for (int j = 0; j < NP; j++) {
            double ph = (j + 0.5) * 2 * CU_PI / NP;
            vec3 d = v3(sin(th) * cos(ph), cos(th), sin(th) * sin(ph));
            double L[3];
            cu_sky_radiance(sky, s, d, L);
            double dw = sin(th) * (CU_PI / 2 / NT) * (2 * CU_PI / NP);
            for (int c = 0; c < 3; c++) {
                E[c] += L[c] * cos(th) * dw;
                M[c] += L[c] * dw;
            }
        }
    }
    double mu_s = sky->sun_dir.y > 0 ? sky->sun_dir.y : 0;
    for (int c = 0; c < 3; c++) {
        sky->sky_irradiance[c] = E[c];
        sky->ground[c] = s->ground_albedo / CU_PI * (sky->sun_irradiance[c] * mu_s + E[c]);
        sky->ground_sun[c] = s->ground_albedo / CU_PI * sky->sun_irradiance[c] * mu_s;
        /* half the sphere is sky (M / 2 pi is its mean radiance), half is ground; a constant sky is everywhere */
        sky->sky_mean[c] = s->sky_model == CU_SKY_CONSTANT ? s->sky_color[c] : M[c] / (2 * CU_PI);
        sky->ground_mean[c] = s->sky_model == CU_SKY_CONSTANT ? s->sky_color[c] : sky->ground[c];
        sky->ambient[c] = 0.5 * (sky->sky_mean[c] + sky->ground_mean[c]);
    }
}

void cu_sky_white_balance(const cu_scene *s, double white[3])
{
    white[0] = white[1] = white[2] = 1.0;
    if (s->has_sun_irradiance || s->sky_model == CU_SKY_CONSTANT)
        return;
    cu_scene ref = *s;
    ref.sun_elevation = 60.0;
    ref.turbidity = 2.5;
    cu_sky sky;
    cu_sky_compute(&sky, &ref);
    double e[3];
    for (int c = 0; c < 3; c++)
        e[c] = sky.sun_irradiance[c];
    double Y = 0.2126 * e[0] + 0.7152 * e[1] + 0.0722 * e[2];
    for (int c = 0; c < 3; c++)
        white[c] = e[c] / Y;
}
