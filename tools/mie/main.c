/* cumulo-mie: command-line front end to the Mie solver (one sphere, a droplet distribution, or the engine table). */
#include "mie.h"
#include "mietable.h"
#include "water.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static const char *USAGE =
    "usage: cumulo-mie [options]\n"
    "  one sphere:   --m N,K --x X [--angles A,B,...]       prints qext qsca qback g, then 'theta S11'\n"
    "  droplets:     [--reff UM --veff V | --monodisperse --radius UM] [--lambda NM] [--angles A,B,...]\n"
    "                prints 'theta p' (sr^-1, normalised), g, qext, sigma_ext_um2\n"
    "  engine table: --table FILE [--reff UM --veff V | --monodisperse --radius UM] [--band LO,HI,STEP]\n"
    "options: --m N,K   refractive index n - ik (K >= 0; overrides water)   --dx D  radius step in size parameter\n"
    "         --tail-stretch S  radius step multiplier past the bulk of the distribution (default 4, 1 = uniform)\n"
    "         --poles 0|1  subtract the quadrature error of resonances narrower than the step (default 1)\n"
    "         --threads T (1-8)   --help\n";

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

    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            fputs(USAGE, stdout);
            return 0;
        }
        if (!strcmp(a, "--monodisperse")) {
            p.monodisperse = 1;
            continue;
        }
        static const char *const valued[] = {"--reff", "--veff",   "--lambda", "--angles", "--radius", "--m",
                                             "--x",    "--table", "--dx",     "--band",   "--threads",
                                             "--tail-stretch", "--poles"};
        int known = 0;
        for (size_t k = 0; k < sizeof valued / sizeof valued[0]; k++)
            known |= !strcmp(a, valued[k]);
        if (!known)
            return bad(a, "unknown option (see --help)", NULL);
        if (i + 1 >= argc)
            return bad(a, "missing value", NULL);
        const char *v = argv[++i];
        double t[3];
        if (!strcmp(a, "--reff")) {
            if (num(v, 1e-3, 50.0, &p.reff_um))
                return bad(a, "expected an effective radius in um, 0.001-50", v);
            have_reff = 1;
        } else if (!strcmp(a, "--veff")) {
            /* alpha = (1-3v)/v >= 1 keeps n(r) smooth at r = 0, which the trapezoid rule relies on. */
            if (num(v, 1e-4, 0.25, &p.veff))
                return bad(a, "expected an effective variance in 0.0001-0.25", v);
            have_reff = 1;
        } else if (!strcmp(a, "--lambda")) {
            /* The Daimon-Masumura fit holds for 182-1129 nm. */
            if (num(v, 200.0, 1100.0, &lambda))
                return bad(a, "expected a wavelength in nm, 200-1100", v);
            have_lambda = 1;
        } else if (!strcmp(a, "--angles")) {
            nangles = numlist(v, 0.0, 180.0, angles, MAXANG);
            if (nangles < 1)
                return bad(a, "expected comma-separated angles in degrees, 0-180", v);
        } else if (!strcmp(a, "--radius")) {
            if (num(v, 1e-4, 5000.0, &p.radius_um))
                return bad(a, "expected a radius in um, 0.0001-5000", v);
            have_radius = 1;
        } else if (!strcmp(a, "--m")) {
            if (numlist(v, -1e300, 1e300, t, 2) != 2 || !(t[0] > 0.0 && t[0] <= 10.0) ||
                !(t[1] >= 0.0 && t[1] <= 10.0))
                return bad(a, "expected N,K with 0 < N <= 10 and 0 <= K <= 10 (m = N - iK)", v);
            p.m = t[0] - I * t[1];
            p.use_m = 1;
            have_m = 1;
        } else if (!strcmp(a, "--x")) {
            if (num(v, 1e-6, 1e5, &x))
                return bad(a, "expected a size parameter, 1e-6-1e5", v);
            have_x = 1;
        } else if (!strcmp(a, "--table")) {
            if (!*v)
                return bad(a, "expected a file name", v);
            table = v;
        } else if (!strcmp(a, "--dx")) {
            if (num(v, 1e-3, 1.0, &p.dx))
                return bad(a, "expected a size-parameter step, 0.001-1", v);
        } else if (!strcmp(a, "--tail-stretch")) {
            if (num(v, 1.0, 8.0, &p.tail_stretch))
                return bad(a, "expected a step multiplier for the large-radius tail, 1-8", v);
        } else if (!strcmp(a, "--poles")) {
            if (strcmp(v, "0") && strcmp(v, "1"))
                return bad(a, "expected 1 (correct the radius quadrature at narrow resonances) or 0", v);
            p.poles = v[0] == '1';
        } else if (!strcmp(a, "--band")) {
            if (numlist(v, 1e-3, 1100.0, t, 3) != 3 || !(t[0] >= 200.0) || !(t[1] > t[0]))
                return bad(a, "expected LO,HI,STEP in nm with 200 <= LO < HI <= 1100", v);
            p.lambda_min_nm = t[0];
            p.lambda_max_nm = t[1];
            p.dlambda_nm = t[2];
            if (fabs(fmod(t[1] - t[0] + 1e-9, t[2])) > 1e-6)
                return bad(a, "HI - LO must be a multiple of STEP", v);
            have_band = 1;
        } else if (!strcmp(a, "--threads")) {
            double th;
            if (num(v, 1.0, 8.0, &th) || th != floor(th))
                return bad(a, "expected an integer 1-8", v);
            p.threads = (int)th;
        }
    }
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
        if (out != stdout && fclose(out) != 0)
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
