/* src/core/solar.h: the sun's position in the sky from a UTC date and time and a place on Earth (NREL's SPA). */
#ifndef CU_SOLAR_H
#define CU_SOLAR_H
#include "error.h"

/* A UTC calendar time. The fields hold a real date in 1900..2100 (the range of the ΔT model below); second is in
 * [0, 60), or [60, 61) for a leap second at 23:59:60. */
typedef struct cu_utc {
    int year, month, day, hour, minute;
    double second;
} cu_utc;

/* Strict ISO 8601 extended format (RFC 3339): "YYYY-MM-DDTHH:MM:SS", optional fractional seconds ".s" (1 to 9
 * digits), then "Z" or a numeric offset "+HH:MM" / "-HHMM", which is taken off to give UTC (days, months and years
 * carried). A space may stand for the "T". Upper case only; nothing may follow the zone. Errors quote the text:
 * "time_utc '2026-02-30T00:00:00Z': day 30 is not in February 2026". */
int cu_utc_parse(const char *text, cu_utc *out, cu_error *err);

/* The Julian day of a UT time (Meeus, Astronomical Algorithms, ch. 7; Reda & Andreas 2004 eq. 4). */
double cu_utc_julian_day(const cu_utc *t);

/* Moves *t by `seconds` (negative: back), across days, months and years. A leap second 23:59:60 counts as the first
 * second of the next day. Returns 1 and leaves *t unchanged when seconds is not finite, *t is not a valid time or the
 * result leaves 1900..2100. */
int cu_utc_add_seconds(cu_utc *t, double seconds);

/* The UTC time of a POSIX time (seconds since 1970-01-01T00:00:00Z, leap seconds not counted); 1 if out of range. */
int cu_utc_from_unix(double unix_seconds, cu_utc *out);

/* Degrees. elevation: topocentric, above the horizon; zenith = 90 - elevation; azimuth: from north toward east,
 * in [0, 360). */
typedef struct cu_solar_angles {
    double elevation, azimuth;
    double zenith;
} cu_solar_angles;

/* Where the sun is seen at time *t by an observer at latitude_deg (north positive, [-90, 90]), longitude_deg (east
 * positive, [-180, 180]) and height_m above sea level ([-1000, 100000]). refraction = 0: the geometric elevation (SPA's
 * e0); refraction != 0: with SPA's atmospheric refraction for the standard atmosphere (1010 hPa, 10 °C). Accuracy:
 * SPA's ±0.0003° for UT1; taking UTC for UT1 (|UT1 - UTC| < 0.9 s) adds up to 0.004° in azimuth and elevation.
 * ΔT comes from cu_solar_delta_t. Errors name the bad argument. */
int cu_solar_position(const cu_utc *t, double latitude_deg, double longitude_deg, double height_m, int refraction,
                      cu_solar_angles *out, cu_error *err);

/* cu_solar_position_at (the same from the text of a time, in plain numbers) is public: include/cumulo.h. */

/* ---- for tests ---- */

/* ΔT = TT - UT in seconds: Espenak & Meeus 2006 ("Five Millennium Canon of Solar Eclipses", NASA/TP-2006-214141;
 * the polynomials of eclipse.gsfc.nasa.gov/SEcat5/deltatpoly.html) for 1900..2100, evaluated at
 * y = year + (month - 0.5) / 12 as they prescribe. The real ΔT has fallen below the 2005-2050 polynomial: today it is
 * 32.184 s + (TAI - UTC = 37 s) - (UT1 - UTC, under 0.9 s) = 69 s, the polynomial gives 75 s for 2026. That costs
 * little: ΔT only shifts the ephemeris (the sun's ecliptic longitude moves 0.00001° a second), not the Earth's
 * rotation angle, so 10 s of error move the sun by less than 0.0002°. */
double cu_solar_delta_t(int year, int month);

/* SPA with every input explicit: pressure (hPa) and temperature (°C) of the refraction correction (used when
 * refraction != 0) and ΔT in seconds. Reda & Andreas' test point passes 820 hPa, 11 °C and ΔT = 67 s. */
int cu_solar_position_spa(const cu_utc *t, double latitude_deg, double longitude_deg, double height_m,
                          double pressure_hpa, double temperature_c, double delta_t_s, int refraction,
                          cu_solar_angles *out, cu_error *err);
#endif
