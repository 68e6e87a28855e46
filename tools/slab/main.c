/* cumulo-slab: command-line front end of the slab Monte Carlo (totals, radiance, orders, interior BSDF tables). */
#include "slab.h"
#include "version.h"
#include "../tool_cli.h"
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif
#ifdef CU_SLAB_MPI
#include <mpi.h>
#endif

static int g_rank_silent;  /* set once before any output; only rank 0 of an MPI job prints */

static void finish(int code)
{
#ifdef CU_SLAB_MPI
    MPI_Finalize();
#endif
    exit(code);
}

/* One line on stderr, then exit: 2 for a usage error (the line names the option), 1 for a run that failed with good
 * arguments (a table that cannot be read, an output that cannot be written, memory). */
static void quit(int code, const char *fmt, va_list ap)
{
    fprintf(stderr, "cumulo-slab: error: ");
    vfprintf(stderr, fmt, ap);
    fprintf(stderr, "%s\n", code == 2 ? " (see --help)" : "");
    finish(code);
}

static void die(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    quit(2, fmt, ap);
    va_end(ap);
}

static void fail(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    quit(1, fmt, ap);
    va_end(ap);
}

static void usage(void)
{
    printf("usage: cumulo-slab (--tau T | --thickness METRES [--ke PER_METRE]) [options]\n"
           "Monte Carlo transport in a non-absorbing plane-parallel slab lit by a collimated sun at\n"
           "cos(theta_L) = mu0.\n"
           "See tools/slab/README.md for the geometry, the estimators and the output formats.\n"
           "options:\n"
           "  --tau T              optical thickness, (0, 1e4]\n"
           "  --thickness METRES   geometric thickness instead; tau = ke * METRES\n"
           "  --ke PER_METRE       extinction coefficient for --thickness (default 0.0905)\n"
           "  --mu0 C              cosine of the sun's zenith angle, (0, 1] (default 1)\n"
           "  --phase P            hg:G (-1 < G < 1), iso, or mie:FILE[:r|g|b], a chopped Mie table and its channel\n"
           "                       (default hg:0.85; channel g)\n"
           "  --photons N          photons to trace, 1..1e13 (default 1e5)\n"
           "  --threads N          worker threads, 1..256 (default 2)\n"
           "  --seed S             random seed, a non-negative integer (default 1)\n"
           "  --batches B          batches for the standard errors, 2..100000 (default 100)\n"
           "  --report LIST        comma-separated: totals, radiance, orders, table (default totals)\n"
           "  --mu C1,C2,..        view cosines (0, 1] for the radiance report\n"
           "  --phi DEG            relative azimuth for the radiance report, [0, 360) (default: azimuth average)\n"
           "  --depths N           table: depths, equally spaced 0..t, 1..%d (default 11)\n"
           "  --thetav DEG,..      table: view zenith angles, [0, 180] and not within 1 deg of 90\n"
           "                       (default 0,20,40,..,180)\n"
           "  --phiv DEG,..        table: view azimuths, [0, 180] (default 0,45,90,135,180)\n"
           "  --out FILE           table: write it to FILE instead of stdout\n"
           "  --quiet              no progress bar and no run summary on stderr\n"
           "  -h, --help           this text\n"
           "  --version            the version\n"
           "Argument errors exit 2, failures while running (unreadable table, unwritable output) exit 1.\n",
           CU_MAXGRID);
}

static double num(const char *opt, const char *v)
{
    char *end;
    errno = 0;
    double x = strtod(v, &end);
    if (errno || end == v || *end || !isfinite(x)) die("%s expects a number, got '%s'", opt, v);
    return x;
}

static int list(const char *opt, const char *v, double *out, int max)
{
    int n = 0;
    char buf[1024];
    if (strlen(v) >= sizeof buf) die("%s: list too long", opt);
    strcpy(buf, v);
    for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
        if (n >= max) die("%s: at most %d values", opt, max);
        out[n++] = num(opt, tok);
    }
    if (n == 0) die("%s expects a comma-separated list", opt);
    return n;
}

int main(int argc, char **argv)
{
    int rank = 0, nranks = 1;
#ifdef CU_SLAB_MPI
    MPI_Init(&argc, &argv);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &nranks);
#endif
    g_rank_silent = rank != 0;
    cu_slab_cfg c;
    memset(&c, 0, sizeof c);
    double tau = 0, thick = 0, ke = 0.0905, mu0 = 1.0, photons = 1e5;
    const char *phase = "hg:0.85", *report = "totals", *out = NULL;
    int threads = 2, batches = 100, quiet = 0, nd = 11, have_tau = 0, have_thick = 0;
    unsigned long long seed = 1;
    c.phi_deg = -1;
    /* default table grid: theta_V avoids 90 deg where the interior point estimator has no finite variance */
    double thv[] = { 0, 20, 40, 60, 80, 100, 120, 140, 160, 180 }, phv[] = { 0, 45, 90, 135, 180 };
    c.nv = 10; memcpy(c.thv_deg, thv, sizeof thv);
    c.nphi = 5; memcpy(c.phv_deg, phv, sizeof phv);
    enum { O_TAU = 256, O_THICK, O_KE, O_MU0, O_PHASE, O_PHOTONS, O_THREADS, O_SEED, O_BATCHES, O_REPORT, O_MU, O_PHI,
           O_DEPTHS, O_THETAV, O_PHIV, O_OUT, O_QUIET, O_VERSION };
    static const struct option opts[] = {
        {"tau", required_argument, NULL, O_TAU},         {"thickness", required_argument, NULL, O_THICK},
        {"ke", required_argument, NULL, O_KE},           {"mu0", required_argument, NULL, O_MU0},
        {"phase", required_argument, NULL, O_PHASE},     {"photons", required_argument, NULL, O_PHOTONS},
        {"threads", required_argument, NULL, O_THREADS}, {"seed", required_argument, NULL, O_SEED},
        {"batches", required_argument, NULL, O_BATCHES}, {"report", required_argument, NULL, O_REPORT},
        {"mu", required_argument, NULL, O_MU},           {"phi", required_argument, NULL, O_PHI},
        {"depths", required_argument, NULL, O_DEPTHS},   {"thetav", required_argument, NULL, O_THETAV},
        {"phiv", required_argument, NULL, O_PHIV},       {"out", required_argument, NULL, O_OUT},
        {"quiet", no_argument, NULL, O_QUIET},           {"help", no_argument, NULL, 'h'},
        {"version", no_argument, NULL, O_VERSION},       {NULL, 0, NULL, 0}};
    opterr = 0;
    for (int o; (o = getopt_long(argc, argv, ":h", opts, NULL)) != -1;) {
        const char *a = argv[optind - 1], *v = optarg;
        switch (o) {
        case 'h': usage(); finish(0); break;
        case O_VERSION: printf("cumulo-slab %s (%s)\n", CU_VERSION, CU_GIT_DESCRIBE); finish(0); break;
        case ':': die("%s needs a value", a); break;
        case '?': die("unknown option '%s'", a); break;
        case O_QUIET: quiet = 1; break;
        case O_TAU: tau = num("--tau", v); have_tau = 1; break;
        case O_THICK: thick = num("--thickness", v); have_thick = 1; break;
        case O_KE: ke = num("--ke", v); break;
        case O_MU0: mu0 = num("--mu0", v); break;
        case O_PHASE: phase = v; break;
        case O_PHOTONS: photons = num("--photons", v); break;
        case O_THREADS:
            if (tool_parse_int(v, 1, 256, &threads)) die("--threads must be in 1..256, got '%s'", v);
            break;
        case O_SEED:
            if (tool_parse_uints(v, 0, 1, 0, UINT64_MAX, &seed)) die("--seed must be a non-negative 64-bit integer, got '%s'", v);
            break;
        case O_BATCHES:
            if (tool_parse_int(v, 2, 100000, &batches)) die("--batches must be in 2..100000, got '%s'", v);
            break;
        case O_REPORT: report = v; break;
        case O_MU: c.nmu = list("--mu", v, c.mu, CU_MAXMU); break;
        case O_PHI: c.phi_deg = num("--phi", v); break;
        case O_DEPTHS:
            if (tool_parse_int(v, 1, CU_MAXGRID, &nd)) die("--depths must be in 1..%d, got '%s'", CU_MAXGRID, v);
            break;
        case O_THETAV: c.nv = list("--thetav", v, c.thv_deg, CU_MAXGRID); break;
        case O_PHIV: c.nphi = list("--phiv", v, c.phv_deg, CU_MAXGRID); break;
        case O_OUT: out = v; break;
        }
    }
    if (optind < argc) die("unexpected argument '%s'", argv[optind]);
    int want_tot = 0, want_rad = 0, want_ord = 0, want_tab = 0;
    {
        char buf[256];
        if (strlen(report) >= sizeof buf) die("--report too long");
        strcpy(buf, report);
        for (char *t = strtok(buf, ","); t; t = strtok(NULL, ",")) {
            if (!strcmp(t, "totals")) want_tot = 1;
            else if (!strcmp(t, "radiance")) want_rad = 1;
            else if (!strcmp(t, "orders")) want_ord = 1;
            else if (!strcmp(t, "table")) want_tab = 1;
            else die("--report: unknown report '%s' (totals, radiance, orders, table)", t);
        }
    }
    if (have_tau == have_thick) die("give exactly one of --tau or --thickness");
    if (!(ke > 0)) die("--ke must be > 0");
    if (have_thick && !(thick > 0)) die("--thickness must be > 0, got %g", thick);
    if (have_thick) tau = ke * thick;
    if (!(tau > 0) || tau > 1e4) die("optical thickness must be in (0, 1e4], got %g", tau);
    if (!(mu0 > 0 && mu0 <= 1)) die("--mu0 must be in (0, 1], got %g", mu0);
    if (!(photons >= 1 && photons <= 1e13) || photons != floor(photons)) die("--photons must be a positive integer");
    if (want_rad && c.nmu == 0) die("--report radiance needs --mu");
    for (int j = 0; j < c.nmu; j++)
        if (!(c.mu[j] > 0 && c.mu[j] <= 1)) die("--mu values must be in (0, 1], got %g", c.mu[j]);
    if (c.phi_deg >= 360) die("--phi must be in [0, 360)");
    if (want_tab) {
        if (nd < 1 || nd > CU_MAXGRID) die("--depths must be in 1..%d", CU_MAXGRID);
        for (int k = 0; k < c.nv; k++)
            if (!(c.thv_deg[k] >= 0 && c.thv_deg[k] <= 180) || fabs(c.thv_deg[k] - 90) < 1) die("--thetav values must be in [0,180] and not within 1 deg of 90");
        for (int k = 0; k < c.nphi; k++)
            if (!(c.phv_deg[k] >= 0 && c.phv_deg[k] <= 180)) die("--phiv values must be in [0,180]");
    }
    cu_phase ph;
    memset(&ph, 0, sizeof ph);
    if (!strcmp(phase, "iso")) ph.kind = CU_PH_ISO;
    else if (!strncmp(phase, "hg:", 3)) {
        ph.kind = CU_PH_HG; ph.g = num("--phase hg:", phase + 3);
        if (!(ph.g > -1 && ph.g < 1)) die("--phase hg:G needs -1 < G < 1");
    } else if (!strncmp(phase, "mie:", 4)) {
        char path[4096]; int ch = 1;
        if (strlen(phase + 4) >= sizeof path) die("--phase: path too long");
        strcpy(path, phase + 4);
        size_t L = strlen(path);
        if (L > 2 && path[L - 2] == ':' && strchr("rgb", path[L - 1])) { ch = (int)(strchr("rgb", path[L - 1]) - "rgb"); path[L - 2] = 0; }
        char msg[512];
        if (cu_phase_read_mie(&ph, path, ch, msg, sizeof msg)) fail("%s", msg);
        if (!(ph.f >= 0 && ph.f < 0.99)) fail("%s: chopped fraction f = %g out of range", path, ph.f);
    } else die("--phase must be hg:G, iso or mie:FILE[:r|g|b], got '%s'", phase);
    /* chopped-peak equivalence: the removed peak f is treated as unscattered, so the transported extinction is
     * (1-f) k_e with the renormalised chopped phase function (README, "Chopped Mie phase function") */
    c.tau = (1.0 - ph.f) * tau;
    c.mu0 = mu0; c.ph = &ph;
    c.metres_per_tau = 1.0 / ((1.0 - ph.f) * ke);
    c.photons = (long long)photons; c.nbatch = batches; c.threads = threads; c.seed = (uint64_t)seed;
    c.quiet = quiet || g_rank_silent; c.rank = rank; c.nranks = nranks;
    if (!want_rad) c.nmu = 0;
    if (want_tab) {
        c.table = 1; c.nd = nd;
        for (int j = 0; j < nd; j++) c.d_tau[j] = nd == 1 ? 0 : c.tau * j / (nd - 1);
    }
    if (c.photons < c.nbatch) c.nbatch = (int)(c.photons < 2 ? 2 : c.photons);
    cu_slab_result r;
    if (cu_slab_run(&c, &r)) fail("out of memory");
    if (g_rank_silent) { cu_slab_result_free(&r); cu_phase_free(&ph);
#ifdef CU_SLAB_MPI
        MPI_Finalize();
#endif
        return 0; }
    if (!quiet)
        fprintf(stderr, "cumulo-slab: tau=%g (transported %g, f=%.4f) mu0=%g phase=%s photons=%lld collisions=%lld %.2fs "
                "threads=%d ranks=%d seed=%llu\n", tau, c.tau, ph.f, mu0, phase, c.photons, r.collisions, r.seconds,
                threads, nranks, (unsigned long long)c.seed);
    double m, se;
    if (want_tot) {
        cu_acc_stats(&r.R, r.photons, &m, &se);
        printf("R %.5f +- %.5f\n", m, se);
        cu_acc_stats(&r.T, r.photons, &m, &se);
        printf("T %.5f +- %.5f\n", m + r.t_unscat, se);
    }
    if (want_ord) {
        double m2, se2;
        printf("# diffuse flux per scattering-order group: analog exit count, then escape-probability estimator\n");
        printf("T0 %.6f\n", r.t_unscat);
        for (int g = 0; g < CU_NGROUP; g++) {
            cu_acc_stats(&r.Rn[g], r.photons, &m, &se);
            cu_acc_stats(&r.Ren[g], r.photons, &m2, &se2);
            printf("R n=%s %.6f +- %.6f escape %.6f +- %.6f\n", cu_slab_group_name(g), m, se, m2, se2);
        }
        for (int g = 0; g < CU_NGROUP; g++) {
            cu_acc_stats(&r.Tn[g], r.photons, &m, &se);
            cu_acc_stats(&r.Ten[g], r.photons, &m2, &se2);
            printf("T n=%s %.6f +- %.6f escape %.6f +- %.6f\n", cu_slab_group_name(g), m, se, m2, se2);
        }
        cu_acc_stats(&r.RTe, r.photons, &m, &se);
        printf("R+T escape %.6f +- %.6f\n", m + r.t_unscat, se);
    }
    if (want_rad) {
        for (int j = 0; j < c.nmu; j++) {
            cu_acc_stats(&r.rad_r[j], r.photons, &m, &se);
            printf("reflect mu=%g %.4f +- %.4f\n", c.mu[j], m, se);
        }
        for (int j = 0; j < c.nmu; j++) {
            cu_acc_stats(&r.rad_t[j], r.photons, &m, &se);
            printf("transmit mu=%g %.4f +- %.4f\n", c.mu[j], m, se);
        }
        if (want_ord)
            for (int j = 0; j < c.nmu; j++)
                for (int g = 0; g < CU_NGROUP; g++) {
                    double m2, se2;
                    cu_acc_stats(&r.rad_rn[j][g], r.photons, &m, &se);
                    cu_acc_stats(&r.rad_tn[j][g], r.photons, &m2, &se2);
                    printf("radiance n=%s mu=%g reflect %.6f +- %.6f transmit %.6f +- %.6f\n", cu_slab_group_name(g),
                           c.mu[j], m, se, m2, se2);
                }
    }
    if (want_tab) {
        FILE *fo = stdout;
        if (out && !(fo = fopen(out, "w"))) fail("cannot write '%s': %s", out, strerror(errno));
        double mpt = c.metres_per_tau, thl = acos(mu0) * 180.0 / M_PI;
        fprintf(fo, "# cumulo-slab table: C = I/F_sun (sr^-1) at depth d toward s_V (Bouthors eq. 3.25); collector (eqs. 3.29-3.31)\n");
        fprintf(fo, "# tau=%.9g thickness_m=%.9g ke=%.9g f=%.6f mu0=%.9g phase=%s photons=%lld batches=%d seed=%llu\n",
                tau, c.tau * mpt, ke, ph.f, mu0, phase, c.photons, c.nbatch, (unsigned long long)c.seed);
        fprintf(fo, "# angles: theta_V from -y (0 = looking up at the slab from below / light going down), phi_V from -z "
                    "(0 = forward azimuth); lengths in metres; entry point relative to p: cx, cz; sigma = sqrt((sx^2+sz^2)/2)\n");
        fprintf(fo, "# group t_m d_m thetaV_deg phiV_deg thetaL_deg C C_se cx_m cx_se cz_m cz_se sigma_m sigma_se\n");
        for (int g = 0; g < CU_NGROUP; g++)
            for (int jd = 0; jd < c.nd; jd++)
                for (int iv = 0; iv < c.nv; iv++)
                    for (int ip = 0; ip < c.nphi; ip++) {
                        cu_cell_stats st;
                        cu_slab_cell_stats(&c, &r, cu_slab_cell(&c, g, jd, iv, ip), &st);
                        fprintf(fo, "%d %.6g %.6g %g %g %.6g %.6e %.3e %.5g %.3g %.5g %.3g %.5g %.3g\n", g + 1, c.tau * mpt,
                                c.d_tau[jd] * mpt, c.thv_deg[iv], c.phv_deg[ip], thl, st.C, st.C_se, st.cx, st.cx_se,
                                st.cz, st.cz_se, st.sigma, st.sigma_se);
                    }
        if (tool_close_output(fo)) fail("writing '%s' failed", out ? out : "stdout");
    }
    cu_slab_result_free(&r);
    cu_phase_free(&ph);
#ifdef CU_SLAB_MPI
    MPI_Finalize();
#endif
    return 0;
}
