/* cumulo-slab-sphere: where light leaves a finite cloud. A homogeneous non-absorbing sphere of diameter D (m) lit by
 * the sun at zenith; reports the fraction of the intercepted sunlight that leaves through the upper and the lower
 * hemisphere (mean exitance of the top and of the base, which have equal areas) and the fraction leaving upwards or
 * downwards. Used to read Kol's Fig. 4.7 and Bouthors' "t > ~500 m reflects more than it transmits" (README). */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "rng.h"
#include "slab.h"
#include "version.h"
#include "../tool_cli.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static const char USAGE[] =
    "usage: cumulo-slab-sphere --diameter M [options]\n"
    "A homogeneous non-absorbing sphere lit by the sun at the zenith: the fractions of the intercepted sunlight that\n"
    "leave through the top and the base hemisphere, upwards and downwards (see tools/slab/README.md).\n"
    "options:\n"
    "  --diameter M     sphere diameter, metres, > 0 (required)\n"
    "  --ke K           extinction coefficient, per metre, > 0 (default 0.0905)\n"
    "  --phase P        hg:G (-1 < G < 1) or mie:FILE[:r|g|b], a chopped Mie table and its channel (default hg:0.85;\n"
    "                   channel g)\n"
    "  --photons N      photons to trace, >= 1 (default 1e5)\n"
    "  --seed S         random seed, a non-negative integer (default 1)\n"
    "  -h, --help       this text\n"
    "  --version        the version\n"
    "Argument errors exit 2, an unreadable Mie table exits 1.\n";

/* A usage error (exit 2) or a failure of the run (exit 1): one line, naming the option when there is one. */
static void die(int code, const char *arg, const char *m)
{
    fprintf(stderr, "cumulo-slab-sphere: error: %s%s%s\n", arg ? arg : "", arg ? ": " : "", m);
    exit(code);
}

static double num(const char *opt, const char *s)
{
    char *e;
    errno = 0;
    double v = strtod(s, &e);
    if (e == s || *e || errno || !isfinite(v))
        die(2, opt, "expects a number");
    return v;
}

/* new direction at angle acos(ct) from d, azimuth 2 pi u */
static void turn(double d[3], double ct, double u)
{
    double st = sqrt(fmax(0.0, 1.0 - ct * ct)), ph = 2.0 * M_PI * u, cp = cos(ph), sp = sin(ph);
    double a[3] = { 1, 0, 0 };
    if (fabs(d[0]) > 0.9) { a[0] = 0; a[1] = 1; }
    double e1[3] = { d[1] * a[2] - d[2] * a[1], d[2] * a[0] - d[0] * a[2], d[0] * a[1] - d[1] * a[0] };
    double n = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    for (int i = 0; i < 3; i++) e1[i] /= n;
    double e2[3] = { d[1] * e1[2] - d[2] * e1[1], d[2] * e1[0] - d[0] * e1[2], d[0] * e1[1] - d[1] * e1[0] };
    for (int i = 0; i < 3; i++) d[i] = ct * d[i] + st * (cp * e1[i] + sp * e2[i]);
}

int main(int argc, char **argv)
{
    double D = -1, ke = 0.0905, photons = 1e5;
    unsigned long long seed = 1;
    const char *phase = "hg:0.85";
    enum { O_DIAMETER = 256, O_KE, O_PHOTONS, O_SEED, O_PHASE, O_VERSION };
    static const struct option opts[] = {
        {"diameter", required_argument, NULL, O_DIAMETER}, {"ke", required_argument, NULL, O_KE},
        {"photons", required_argument, NULL, O_PHOTONS},   {"seed", required_argument, NULL, O_SEED},
        {"phase", required_argument, NULL, O_PHASE},       {"help", no_argument, NULL, 'h'},
        {"version", no_argument, NULL, O_VERSION},         {NULL, 0, NULL, 0}};
    opterr = 0;
    for (int o; (o = getopt_long(argc, argv, ":h", opts, NULL)) != -1;) {
        const char *a = argv[optind - 1];
        switch (o) {
        case 'h':
            fputs(USAGE, stdout);
            return 0;
        case O_VERSION:
            printf("cumulo-slab-sphere %s (%s)\n", CU_VERSION, CU_GIT_DESCRIBE);
            return 0;
        case ':': die(2, a, "needs a value (see --help)"); break;
        case '?': die(2, a, "unknown option (see --help)"); break;
        case O_DIAMETER: D = num("--diameter", optarg); break;
        case O_KE: ke = num("--ke", optarg); break;
        case O_PHOTONS: photons = num("--photons", optarg); break;
        case O_SEED:
            if (tool_parse_uints(optarg, 0, 1, 0, UINT64_MAX, &seed))
                die(2, "--seed", "must be a non-negative 64-bit integer");
            break;
        case O_PHASE: phase = optarg; break;
        }
    }
    if (optind < argc) die(2, argv[optind], "unexpected argument (see --help)");
    if (D < 0) die(2, "--diameter", "is required (see --help)");
    if (!(D > 0)) die(2, "--diameter", "must be > 0");
    if (!(ke > 0)) die(2, "--ke", "must be > 0");
    if (!(photons >= 1 && photons <= 9e18)) die(2, "--photons", "must be >= 1");
    cu_phase ph;
    memset(&ph, 0, sizeof ph);
    if (!strncmp(phase, "hg:", 3)) {
        ph.kind = CU_PH_HG;
        ph.g = num("--phase hg:", phase + 3);
        if (!(ph.g > -1 && ph.g < 1)) die(2, "--phase", "hg:G needs -1 < G < 1");
    } else if (!strncmp(phase, "mie:", 4)) {
        char path[4096], msg[256];
        int ch = 1;
        snprintf(path, sizeof path, "%s", phase + 4);
        size_t l = strlen(path);
        if (l > 2 && path[l - 2] == ':') { ch = path[l - 1] == 'r' ? 0 : path[l - 1] == 'b' ? 2 : 1; path[l - 2] = 0; }
        if (cu_phase_read_mie(&ph, path, ch, msg, sizeof msg)) die(1, NULL, msg);
    } else die(2, "--phase", "must be hg:G or mie:FILE[:r|g|b]");
    /* chopped peak: transport with (1 - f) k_e and the renormalised chopped function (README) */
    double R = 0.5 * D * ke * (1.0 - ph.f);
    cu_rng rng;
    cu_rng_seed(&rng, seed);
    long long n = (long long)photons;
    double top = 0, bot = 0, up = 0, unsc = 0, coll = 0;
    for (long long k = 0; k < n; k++) {
        double r = R * sqrt(cu_rng_u01(&rng)), a = 2.0 * M_PI * cu_rng_u01(&rng);
        double p[3] = { r * cos(a), sqrt(fmax(0.0, R * R - r * r)), r * sin(a) }, d[3] = { 0, -1, 0 };
        for (int order = 0;; order++) {
            double b = p[0] * d[0] + p[1] * d[1] + p[2] * d[2], c = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] - R * R;
            double sx = -b + sqrt(fmax(0.0, b * b - c)), s = -log(cu_rng_u01_open0(&rng));
            if (s >= sx) {
                for (int i = 0; i < 3; i++) p[i] += sx * d[i];
                if (p[1] > 0) top++; else bot++;
                if (d[1] > 0) up++;
                if (order == 0) unsc++;
                break;
            }
            for (int i = 0; i < 3; i++) p[i] += s * d[i];
            turn(d, cu_phase_sample(&ph, cu_rng_u01(&rng)), cu_rng_u01(&rng));
            coll++;
        }
    }
    double ft = top / n, fb = bot / n, fu = up / n;
    printf("# sphere D=%g m ke=%g phase=%s f=%.4f optical diameter %.4g (transported %.4g) photons=%lld seed=%llu\n",
           D, ke, phase, ph.f, D * ke, 2 * R, n, seed);
    printf("top %.5f +- %.5f\nbase %.5f +- %.5f\nup %.5f +- %.5f\ndown %.5f +- %.5f\nunscattered %.5f\ncollisions %.1f\n",
           ft, sqrt(ft * (1 - ft) / n), fb, sqrt(fb * (1 - fb) / n), fu, sqrt(fu * (1 - fu) / n), 1 - fu,
           sqrt(fu * (1 - fu) / n), unsc / n, coll / n);
    cu_phase_free(&ph);
    return 0;
}
