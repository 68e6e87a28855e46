/* src/core/sky.h: the Preetham et al. 1999 daylight model on the CPU: Perez coefficients for the sky shader, the sun's
 * irradiance after the atmosphere (Rayleigh + aerosol), and the ground radiance. Units: kcd/m^2 and klx. */
#ifndef CU_SKY_H
#define CU_SKY_H
#include "scene.h"
#include "vecmath.h"

typedef struct cu_sky {
    vec3 sun_dir;
    double sun_irradiance[3];   /* linear RGB, on a plane perpendicular to the rays */
    double perez[15];           /* A..E for Y, x, y */
    double zenith[3];           /* Y (kcd/m^2), x, y */
    double norm[3];             /* F(0, theta_s) for Y, x, y */
    double ground[3];           /* radiance of the Lambertian ground */
    double ground_sun[3];       /* the part of it lit by the sun directly (what a cloud's shadow takes away) */
    double sky_irradiance[3];   /* sky irradiance on a horizontal plane */
    double sky_mean[3];         /* mean radiance of the upper hemisphere of the environment */
    double ground_mean[3];      /* mean radiance of the lower hemisphere (the ground; the sky colour if constant) */
    double ambient[3];          /* mean radiance of the environment (sky and ground) over the whole sphere */
} cu_sky;

void cu_sky_compute(cu_sky *sky, const cu_scene *s);
/* Sky radiance (linear RGB) in a unit direction with y >= 0, as the shader computes it (without the sun disk). */
void cu_sky_radiance(const cu_sky *sky, const cu_scene *s, vec3 dir, double out[3]);
/* The Perez distribution F(theta, gamma) is a product of a function of the zenith angle theta and one of the angle
 * gamma to the sun, so the sky shader reads each factor from a table and multiplies (sky.frag): two fetches a pixel
 * instead of six exponentials and an arc cosine. Entry i of zenith_part holds, for Y, x and y, the zenith value over
 * F(0, theta_s) times (1 + A exp(B / cos theta)) at sqrt(cos theta) = i / (CU_SKY_TABLE - 1); entry i of sun_part
 * holds 1 + C exp(D gamma) + E cos^2 gamma at sin(gamma / 2) = i / (CU_SKY_TABLE - 1). Both RGBA (A = 1); their
 * product is what cu_sky_radiance converts to RGB. Both spacings put the entries where the factors bend (the horizon,
 * the sun). */
#define CU_SKY_TABLE 256
void cu_sky_tables(const cu_sky *sky, float zenith_part[4 * CU_SKY_TABLE], float sun_part[4 * CU_SKY_TABLE]);
/* The sky toward dir (unit) as sky.glsl's perez_sky reads it from those tables (entries interpolated linearly, the
 * horizon's row below it): what the GPU draws, for the CPU's estimate of the sky grid's error (pass_sky.c). */
void cu_sky_from_tables(const float zenith_part[4 * CU_SKY_TABLE], const float sun_part[4 * CU_SKY_TABLE],
                        vec3 sun_dir, vec3 dir, double out[3]);
/* White balance for display, like a camera set to daylight: the RGB colour of the sun's irradiance for a sun 60
 * degrees high (turbidity 2.5), scaled to unit luminance (clouds are lit mostly by the sun). A midday cloud is white; a low sun
 * still looks warm. With a scene that gives its own sun irradiance or a constant sky, no balance is applied. */
void cu_sky_white_balance(const cu_scene *s, double white[3]);
#endif
