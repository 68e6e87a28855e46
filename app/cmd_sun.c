/* app/cmd_sun.c: `cumulo sun`: where the sun stands for a UTC time and a place, as one line of degrees. */
#include "commands.h"
#include "session.h"
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


static const char sun_help[] =
    "usage: cumulo sun --time-utc T --latitude DEG --longitude DEG [--height M] [--refraction]\n"
    "Prints where the sun stands (NREL's SPA) as one line: elevation E azimuth A, degrees with 4 decimals;\n"
    "elevation above the horizon, azimuth from north toward east in [0, 360).\n"
    "  --time-utc T           the time: ISO 8601 / RFC 3339, 2026-06-21T12:00:00Z or 2026-06-21T14:00:00+02:00\n"
    "                         (fractional seconds allowed; years 1900..2100)\n"
    "  --latitude DEG         north positive, -90..90\n"
    "  --longitude DEG        east positive, -180..180\n"
    "  --height M             the observer's height above sea level in metres, -1000..100000 (default 0)\n"
    "  --refraction           add atmospheric refraction (1010 hPa, 10 C); default: the geometric elevation\n"
    "  -h, --help             this help; --version: version and back ends\n";

/* v with control bytes written as \xHH, at most 64 bytes of it, for a message. */
static const char *shown(const char *v, char out[4 * 64 + 4])
{
    size_t o = 0;
    for (size_t i = 0; v[i] && i < 64; i++)
        o += (unsigned char)v[i] < 32 || v[i] == 127 ? (size_t)sprintf(out + o, "\\x%02x", (unsigned char)v[i])
                                                     : (size_t)sprintf(out + o, "%c", v[i]);
    strcpy(out + o, strlen(v) > 64 ? "..." : "");
    return out;
}

/* A plain decimal number (an exponent allowed): not hex, inf or nan, no blanks. 0, or 1 after saying why. */
static int parse_number(const char *opt, const char *v, double *out)
{
    char *end, q[4 * 64 + 4];
    double x = strtod(v, &end);
    if (end == v || *end || isspace((unsigned char)*v) || strpbrk(v, "xXiInN") || !isfinite(x)) {
        fprintf(stderr, "cumulo sun: %s expects a number, got '%s'\n", opt, shown(v, q));
        return 1;
    }
    *out = x;
    return 0;
}

enum { OPT_TIME = 0x200, OPT_LAT, OPT_LON, OPT_HEIGHT, OPT_REFRACTION };

int cmd_sun(int argc, char **argv)
{
    static const struct option longopts[] = {
        {"time-utc", required_argument, NULL, OPT_TIME},   {"latitude", required_argument, NULL, OPT_LAT},
        {"longitude", required_argument, NULL, OPT_LON},   {"height", required_argument, NULL, OPT_HEIGHT},
        {"refraction", no_argument, NULL, OPT_REFRACTION}, {"help", no_argument, NULL, 'h'},
        {"version", no_argument, NULL, CLI_OPT_VERSION},   {NULL, 0, NULL, 0},
    };
    const char *time_utc = NULL;
    double lat = NAN, lon = NAN, height = 0;
    int refraction = 0, c;
    char q[4 * 64 + 4];
    opterr = 0;
    optind = 1;
    while ((c = getopt_long(argc, argv, ":h", longopts, NULL)) != -1) {
        switch (c) {
        case OPT_TIME: time_utc = optarg; break;
        case OPT_LAT:
            if (parse_number("--latitude", optarg, &lat))
                return 2;
            break;
        case OPT_LON:
            if (parse_number("--longitude", optarg, &lon))
                return 2;
            break;
        case OPT_HEIGHT:
            if (parse_number("--height", optarg, &height))
                return 2;
            break;
        case OPT_REFRACTION: refraction = 1; break;
        case 'h': fputs(sun_help, stdout); return 0;
        case CLI_OPT_VERSION: cli_print_version(stdout, "cumulo"); return 0;
        case ':': fprintf(stderr, "cumulo sun: %s needs a value\n", shown(argv[optind - 1], q)); return 2;
        default: fprintf(stderr, "cumulo sun: unknown option '%s'\n", shown(argv[optind - 1], q)); return 2;
        }
    }
    if (optind < argc) {
        fprintf(stderr, "cumulo sun: unexpected argument '%s' (cumulo sun --help)\n", shown(argv[optind], q));
        return 2;
    }
    const char *missing = !time_utc ? "--time-utc" : isnan(lat) ? "--latitude" : isnan(lon) ? "--longitude" : NULL;
    if (missing) {
        fprintf(stderr, "cumulo sun: missing %s (usage: cumulo sun --time-utc T --latitude DEG --longitude DEG)\n",
                missing);
        return 2;
    }
    /* Every failure here is a value the user gave: out of range, or a time that is not one. */
    double elevation, azimuth;
    cu_error err = {"solar position failed"};
    if (cu_solar_position_at(time_utc, lat, lon, height, refraction, &elevation, &azimuth, &err)) {
        fprintf(stderr, "cumulo sun: %s\n", err.msg);
        return 2;
    }
    /* Rounded first, so that 359.99996 prints as 0.0000 and -0.00001 as 0.0000, not 360.0000 or -0.0000. */
    elevation = round(elevation * 1e4) / 1e4 + 0.0;
    azimuth = round(azimuth * 1e4) / 1e4;
    azimuth = azimuth >= 360 ? azimuth - 360 : azimuth + 0.0;
    printf("elevation %.4f azimuth %.4f\n", elevation, azimuth);
    return 0;
}
