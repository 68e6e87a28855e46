/* cumulo-mie: command-line front end to the Mie solver (one sphere, a droplet distribution, or the engine table). */
#include "mie.h"
#include "mietable.h"
#include "version.h"
#include "water.h"
#include "../tool_cli.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static const char USAGE[] =
    "usage: cumulo-mie [options]\n"
    "Lorenz-Mie scattering by water droplets, in one of three modes:\n"
    "  one sphere:   --m N,K --x X [--angles A,B,...]\n"
    "                prints qext qsca qback g, then 'theta S11' per angle\n"
    "  droplets:     [--reff UM --veff V | --monodisperse --radius UM] [--lambda NM] [--angles A,B,...]\n"
    "                prints 'theta p' (sr^-1, normalised) per angle, then g, qext, sigma_ext_um2\n"
    "  engine table: --table FILE [--reff UM --veff V | --monodisperse --radius UM] [--band LO,HI,STEP]\n"
    "                writes the RGB phase table the renderer loads (data/mie_cloud.tbl); FILE '-' is stdout\n"
    "options:\n"
    "  --m N,K            refractive index m = N - iK (0 < N <= 10, 0 <= K <= 10); overrides water's\n"
    "  --x X              size parameter 2 pi r / lambda of the one sphere, 1e-6..1e5\n"
    "  --angles A,B,...   scattering angles in degrees, 0..180 (at most 1000)\n"
    "  --reff UM          effective radius of the gamma distribution, um, 0.001..50 (default 6)\n"
    "  --veff V           effective variance, 0.0001..0.25 (default 0.1)\n"
    "  --monodisperse     one droplet radius instead of a distribution (needs --radius)\n"
    "  --radius UM        that radius, um, 0.0001..5000\n"
    "  --lambda NM        wavelength for the droplet mode, nm, 200..1100 (default 550)\n"
    "  --table FILE       write the engine table to FILE\n"
    "  --band LO,HI,STEP  wavelengths the table averages, nm (default 400,700,20); 200 <= LO < HI <= 1100,\n"
    "                     HI - LO a multiple of STEP\n"
    "  --dx D             radius step in size parameter, 0.001..1 (default 0.05)\n"
    "  --tail-stretch S   radius step multiplier past the bulk of the distribution, 1..8 (default 4, 1 = uniform)\n"
    "  --poles 0|1        subtract the quadrature error of resonances narrower than the step (default 1)\n"
    "  --threads T        worker threads, 1..8 (default 2)\n"
    "  -h, --help         this text\n"
    "  --version          the version\n"
    "Argument errors exit 2, failures while computing or writing exit 1.\n";

/* Every argument error is one line naming the argument, then exit status 2 (see tools/mie/test_mie_cli.sh). */
static int bad(const char *arg, const char *why, const char *val)
{
    if (val)
        fprintf(stderr, "cumulo-mie: %s: %s (got '%s')\n", arg, why, val);
    else
        fprintf(stderr, "cumulo-mie: %s: %s\n", arg, why);
    return 2;
}

/* Strict number: the whole string must parse, and the value must be finite and within [lo, hi]. */
static int num(const char *s, double lo, double hi, double *out)
{
    if (!s || !*s)
        return -1;
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (errno || *end || !isfinite(v) || v < lo || v > hi)
        return -1;
    *out = v;
    return 0;
}

/* Comma-separated numbers, each in [lo, hi]; returns the count or -1. */
static int numlist(const char *s, double lo, double hi, double *out, int max)
{
    if (!s || !*s)
        return -1;
    char buf[4096];
    if (strlen(s) >= sizeof buf)
        return -1;
    strcpy(buf, s);
    int n = 0;
    char *p = buf;
    for (;;) {
        char *comma = strchr(p, ',');
        if (comma)
            *comma = '\0';
        if (n >= max || num(p, lo, hi, &out[n]) != 0)
            return -1;
        n++;
        if (!comma)
            break;
        p = comma + 1;
    }
    return n;
}

enum { MAXANG = 1000 };

int main(int argc, char **argv)
{
    mt_params p = mt_params_default();
    double angles[MAXANG];
    int nangles = 0;
    double x = 0.0, lambda = 550.0;
    int have_x = 0, have_m = 0, have_lambda = 0, have_band = 0, have_reff = 0, have_radius = 0;
    const char *table = NULL;

    enum { O_REFF = 256, O_VEFF, O_LAMBDA, O_ANGLES, O_RADIUS, O_M, O_X, O_TABLE, O_DX, O_BAND, O_THREADS,
           O_TAIL, O_POLES, O_MONO, O_VERSION };
    static const struct option opts[] = {
        {"reff", required_argument, NULL, O_REFF},       {"veff", required_argument, NULL, O_VEFF},
        {"lambda", required_argument, NULL, O_LAMBDA},   {"angles", required_argument, NULL, O_ANGLES},
        {"radius", required_argument, NULL, O_RADIUS},   {"m", required_argument, NULL, O_M},
        {"x", required_argument, NULL, O_X},             {"table", required_argument, NULL, O_TABLE},
        {"dx", required_argument, NULL, O_DX},           {"band", required_argument, NULL, O_BAND},
        {"threads", required_argument, NULL, O_THREADS}, {"tail-stretch", required_argument, NULL, O_TAIL},
        {"poles", required_argument, NULL, O_POLES},     {"monodisperse", no_argument, NULL, O_MONO},
        {"help", no_argument, NULL, 'h'},                {"version", no_argument, NULL, O_VERSION},
        {NULL, 0, NULL, 0}};
    opterr = 0;
    for (int o; (o = getopt_long(argc, argv, ":h", opts, NULL)) != -1;) {
        const char *a = argv[optind - 1], *v = optarg;
        double t[3];
        switch (o) {
        case 'h':
            fputs(USAGE, stdout);
            return 0;
        case O_VERSION:
            printf("cumulo-mie %s (%s)\n", CU_VERSION, CU_GIT_DESCRIBE);
            return 0;
        case ':':
            return bad(a, "missing value", NULL);
        case '?':
            return bad(a, "unknown option (see --help)", NULL);
        case O_MONO:
            p.monodisperse = 1;
            break;
        case O_REFF:
            if (num(v, 1e-3, 50.0, &p.reff_um))
                return bad("--reff", "expected an effective radius in um, 0.001-50", v);
            have_reff = 1;
            break;
        case O_VEFF:
            /* alpha = (1-3v)/v >= 1 keeps n(r) smooth at r = 0, which the trapezoid rule relies on. */
            if (num(v, 1e-4, 0.25, &p.veff))
                return bad("--veff", "expected an effective variance in 0.0001-0.25", v);
            have_reff = 1;
            break;
        case O_LAMBDA:
            /* The Daimon-Masumura fit holds for 182-1129 nm. */
            if (num(v, 200.0, 1100.0, &lambda))
                return bad("--lambda", "expected a wavelength in nm, 200-1100", v);
            have_lambda = 1;
            break;
        case O_ANGLES:
            nangles = numlist(v, 0.0, 180.0, angles, MAXANG);
            if (nangles < 1)
                return bad("--angles", "expected comma-separated angles in degrees, 0-180", v);
            break;
        case O_RADIUS:
            if (num(v, 1e-4, 5000.0, &p.radius_um))
                return bad("--radius", "expected a radius in um, 0.0001-5000", v);
            have_radius = 1;
            break;
        case O_M:
            if (numlist(v, -1e300, 1e300, t, 2) != 2 || !(t[0] > 0.0 && t[0] <= 10.0) ||
                !(t[1] >= 0.0 && t[1] <= 10.0))
                return bad("--m", "expected N,K with 0 < N <= 10 and 0 <= K <= 10 (m = N - iK)", v);
            p.m = t[0] - I * t[1];
            p.use_m = 1;
            have_m = 1;
            break;
        case O_X:
            if (num(v, 1e-6, 1e5, &x))
                return bad("--x", "expected a size parameter, 1e-6-1e5", v);
            have_x = 1;
            break;
        case O_TABLE:
            if (!*v)
                return bad("--table", "expected a file name", v);
            table = v;
            break;
        case O_DX:
            if (num(v, 1e-3, 1.0, &p.dx))
                return bad("--dx", "expected a size-parameter step, 0.001-1", v);
            break;
        case O_TAIL:
            if (num(v, 1.0, 8.0, &p.tail_stretch))
                return bad("--tail-stretch", "expected a step multiplier for the large-radius tail, 1-8", v);
            break;
        case O_POLES:
            if (strcmp(v, "0") && strcmp(v, "1"))
                return bad("--poles", "expected 1 (correct the radius quadrature at narrow resonances) or 0", v);
            p.poles = v[0] == '1';
            break;
        case O_BAND:
            if (numlist(v, 1e-3, 1100.0, t, 3) != 3 || !(t[0] >= 200.0) || !(t[1] > t[0]))
                return bad("--band", "expected LO,HI,STEP in nm with 200 <= LO < HI <= 1100", v);
            p.lambda_min_nm = t[0];
            p.lambda_max_nm = t[1];
            p.dlambda_nm = t[2];
            if (fabs(fmod(t[1] - t[0] + 1e-9, t[2])) > 1e-6)
                return bad("--band", "HI - LO must be a multiple of STEP", v);
            have_band = 1;
            break;
        case O_THREADS:
            if (tool_parse_int(v, 1, 8, &p.threads))
                return bad("--threads", "expected an integer 1-8", v);
            break;
        }
    }
    if (optind < argc)
        return bad(argv[optind], "unexpected argument (cumulo-mie takes only options; see --help)", NULL);
    if (p.monodisperse && !have_radius)
        return bad("--monodisperse", "needs --radius", NULL);
    if (have_radius && !p.monodisperse)
        return bad("--radius", "only with --monodisperse (otherwise give --reff/--veff)", NULL);
    if (p.monodisperse && have_reff)
        return bad("--monodisperse", "cannot be combined with --reff/--veff", NULL);

    if (have_x) {
        if (!have_m)
            return bad("--x", "needs --m N,K", NULL);
        if (table || have_lambda || p.monodisperse || have_reff || have_band)
            return bad("--x", "takes only --m and --angles", NULL);
        mie_work w;
        mie_work_init(&w);
        mie_q q;
        if (mie_solve(p.m, x, &w, &q) != 0) {
            fprintf(stderr, "cumulo-mie: Mie evaluation failed for x = %g\n", x);
            mie_work_free(&w);
            return 1;
        }
        printf("qext %.8g\nqsca %.8g\nqback %.8g\ng %.8g\n", q.qext, q.qsca, q.qback, q.g);
        for (int i = 0; i < nangles; i++) {
            double complex s1, s2;
            mie_amplitude(&w, q.nterms, cos(angles[i] * 3.14159265358979323846 / 180.0), &s1, &s2);
            double s11 = 0.5 * (creal(s1) * creal(s1) + cimag(s1) * cimag(s1) + creal(s2) * creal(s2) +
                                cimag(s2) * cimag(s2));
            printf("%g %.8g\n", angles[i], s11);
        }
        mie_work_free(&w);
        return 0;
    }

    char err[256];
    mt_angles ang;
    mt_result r;
    if (table) {
        if (have_lambda)
            return bad("--lambda", "--table averages over --band; a single wavelength makes no RGB table", NULL);
        if (nangles)
            return bad("--angles", "--table uses its own angle grid", NULL);
        if (mt_angles_table(&ang, 0.05, 10.0, 0.25) != 0) {
            fprintf(stderr, "cumulo-mie: out of memory\n");
            return 1;
        }
        struct timespec t0, t1;
        clock_gettime(CLOCK_MONOTONIC, &t0);
        if (mt_compute(&p, &ang, &r, err, sizeof err) != 0) {
            fprintf(stderr, "cumulo-mie: %s\n", err);
            mt_angles_free(&ang);
            return 1;
        }
        clock_gettime(CLOCK_MONOTONIC, &t1);
        double secs = (t1.tv_sec - t0.tv_sec) + 1e-9 * (t1.tv_nsec - t0.tv_nsec);
        char cmd[2048] = "";
        for (int i = 0; i < argc; i++) {
            if (strlen(cmd) + strlen(argv[i]) + 2 >= sizeof cmd)
                break;
            if (i)
                strcat(cmd, " ");
            strcat(cmd, argv[i]);
        }
        FILE *out = strcmp(table, "-") ? fopen(table, "w") : stdout;
        if (!out) {
            fprintf(stderr, "cumulo-mie: --table: cannot open '%s': %s\n", table, strerror(errno));
            mt_result_free(&r);
            mt_angles_free(&ang);
            return 1;
        }
        int wrc = mt_write_table(out, &r, ang.theta_deg, cmd, &p);
        if (tool_close_output(out))
            wrc = -1;
        if (wrc != 0)
            fprintf(stderr, "cumulo-mie: writing '%s' failed\n", table);
        else {
            double f[3];
            for (int c = 0; c < 3; c++)
                mt_chop(ang.theta_deg, r.p[c], r.nang, 8.0, &f[c], NULL);
            fprintf(stderr, "cumulo-mie: wrote %s: %d angles, %ld Mie evaluations in %.1f s (%d threads)\n", table,
                    r.nang, r.nsolves, secs, p.threads);
            fprintf(stderr, "cumulo-mie: f %.5f %.5f %.5f  g %.5f %.5f %.5f  sigma_ext %.4f %.4f %.4f um^2\n", f[0],
                    f[1], f[2], r.g[0], r.g[1], r.g[2], r.sigma_ext[0], r.sigma_ext[1], r.sigma_ext[2]);
        }
        mt_result_free(&r);
        mt_angles_free(&ang);
        return wrc ? 1 : 0;
    }

    if (have_band)
        return bad("--band", "only with --table (use --lambda here)", NULL);
    p.lambda_min_nm = p.lambda_max_nm = lambda;
    /* Without --angles one direction is still evaluated (and not printed): mt_compute needs an angle set. */
    if (nangles == 0)
        angles[0] = 0.0;
    if (mt_angles_list(&ang, angles, nangles ? nangles : 1) != 0) {
        fprintf(stderr, "cumulo-mie: out of memory\n");
        return 1;
    }
    if (mt_compute(&p, &ang, &r, err, sizeof err) != 0) {
        fprintf(stderr, "cumulo-mie: %s\n", err);
        mt_angles_free(&ang);
        return 1;
    }
    for (int i = 0; i < nangles; i++)
        printf("%g %.7e\n", angles[i], r.p[0][i]);
    printf("g %.8g\nqext %.8g\nsigma_ext_um2 %.7e\n", r.g[0], r.sigma_ext[0] / r.geo[0], r.sigma_ext[0]);
    mt_result_free(&r);
    mt_angles_free(&ang);
    return 0;
}
