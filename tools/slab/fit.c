/* cumulo-slab-fit: fits eq. 3.32 (and a log-separable alternative) to cumulo-slab tables, reports fit errors per group. */
#include "fitlib.h"
#include "version.h"
#include "../tool_cli.h"
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A usage error (exit 2) or a failure of the run (exit 1): one line. */
static void die(int code, const char *m, const char *arg)
{
    fprintf(stderr, "cumulo-slab-fit: error: %s%s%s\n", arg ? arg : "", arg ? ": " : "", m);
    exit(code);
}

static const char USAGE[] =
    "usage: cumulo-slab-fit [options] TABLE...\n"
    "Fits eq. 3.32 (Bouthors) and two log-separable forms per (group, thickness) to cumulo-slab --report table files\n"
    "and prints the relative fit errors per group.\n"
    "options:\n"
    "  --model M        bouthors, logsep, logsep2 or all (default all)\n"
    "  --holdout        train on phi_V != 90 and report the errors on the held-out phi_V = 90 cells as well\n"
    "  --frac F         count only cells with C > F times the largest C of their (group, t) slice, (0, 1)\n"
    "                   (default 0.01)\n"
    "  --out PREFIX     write each model's parameters to PREFIX_MODEL.txt (the renderer reads PREFIX_bouthors.txt)\n"
    "  --predict PREFIX write every cell with the model's value to PREFIX_MODEL.txt\n"
    "  -h, --help       this text\n"
    "  --version        the version\n"
    "Argument errors exit 2, unreadable tables and unwritable outputs exit 1.\n";

int main(int argc, char **argv)
{
    const char *out = NULL, *predict = NULL;
    int models[3] = { 1, 1, 1 }, holdout = 0, nfiles = 0;
    double frac = 0.01;
    cu_cell *cells = NULL;
    int n = 0;
    setvbuf(stdout, NULL, _IOLBF, 0);   /* reports are long runs: keep the file current line by line */
    char msg[512];
    enum { O_MODEL = 256, O_HOLDOUT, O_FRAC, O_OUT, O_PREDICT, O_VERSION };
    static const struct option opts[] = {
        {"model", required_argument, NULL, O_MODEL}, {"holdout", no_argument, NULL, O_HOLDOUT},
        {"frac", required_argument, NULL, O_FRAC},   {"out", required_argument, NULL, O_OUT},
        {"predict", required_argument, NULL, O_PREDICT}, {"help", no_argument, NULL, 'h'},
        {"version", no_argument, NULL, O_VERSION},   {NULL, 0, NULL, 0}};
    opterr = 0;
    for (int o; (o = getopt_long(argc, argv, ":h", opts, NULL)) != -1;) {
        const char *a = argv[optind - 1], *v = optarg;
        char *end;
        switch (o) {
        case 'h':
            fputs(USAGE, stdout);
            return 0;
        case O_VERSION:
            printf("cumulo-slab-fit %s (%s)\n", CU_VERSION, CU_GIT_DESCRIBE);
            return 0;
        case ':':
            die(2, "needs a value (see --help)", a);
            break;
        case '?':
            die(2, "unknown option (see --help)", a);
            break;
        case O_MODEL:
            models[0] = models[1] = models[2] = 0;
            if (!strcmp(v, "bouthors")) models[0] = 1;
            else if (!strcmp(v, "logsep")) models[1] = 1;
            else if (!strcmp(v, "logsep2")) models[2] = 1;
            else if (!strcmp(v, "all") || !strcmp(v, "both")) models[0] = models[1] = models[2] = 1;
            else die(2, "must be bouthors, logsep, logsep2 or all", "--model");
            break;
        case O_HOLDOUT:
            holdout = 1;
            break;
        case O_FRAC:
            errno = 0;
            frac = strtod(v, &end);
            if (end == v || *end || errno || !(frac > 0 && frac < 1))
                die(2, "must be a number in (0,1)", "--frac");
            break;
        case O_OUT:
            out = v;
            break;
        case O_PREDICT:
            predict = v;
            break;
        }
    }
    if (optind == argc)
        die(2, "no TABLE given (see --help)", NULL);
    for (; optind < argc; optind++, nfiles++)
        if (cu_cells_read(argv[optind], &cells, &n, msg, sizeof msg))
            die(1, msg, NULL);
    if (n <= 0)
        die(1, "no table rows in the given files", NULL);
    int *use = NULL;
    if (holdout) {
        use = malloc(sizeof(int) * n);
        for (int i = 0; i < n; i++) use[i] = fabs(cells[i].phv - 90) > 1e-6;
    }
    double ts[256];
    int nt = 0;
    for (int i = 0; i < n; i++) {
        int k;
        for (k = 0; k < nt; k++) if (fabs(ts[k] - cells[i].t) <= 1e-6 * ts[k]) break;
        if (k == nt && nt < 256) ts[nt++] = cells[i].t;
    }
    for (int a = 0; a < nt; a++) for (int b = a + 1; b < nt; b++) if (ts[b] < ts[a]) { double x = ts[a]; ts[a] = ts[b]; ts[b] = x; }
    double *err = malloc(sizeof(double) * n), *all = malloc(sizeof(double) * n), *allh = malloc(sizeof(double) * n);
    static const char *gname[] = { "", "1", "2", "3", "4", "5-6", "7-9", "10-15", "16+" };
    printf("# cumulo-slab-fit: %d rows from %d table(s), %d thicknesses; relative error |M-C|/C over cells with C > %.3g * max "
           "of the (group, t) slice%s\n", n, nfiles, nt, frac, holdout ? "; training phi_V != 90, held-out phi_V = 90" : "");
    for (int mdl = 0; mdl < 3; mdl++) {
        if (!models[mdl]) continue;
        const char *mname = mdl == CU_MODEL_BOUTHORS ? "bouthors" : mdl == CU_MODEL_LOGSEP ? "logsep" : "logsep2";
        FILE *fo = NULL;
        if (out) {
            char path[4096];
            snprintf(path, sizeof path, "%s_%s.txt", out, mname);
            if (!(fo = fopen(path, "w"))) die(1, "cannot write the output table", path);
            fprintf(fo, "# %s fit of cumulo-slab C tables (C = I/F_sun, sr^-1; lengths in metres). %s\n", mname,
                    mdl == CU_MODEL_BOUTHORS ? "C = P*(Theta) A1*(thV) A2*(thL) cos thL log^2(d+D*)/log^2(B*+D*) "
                                              "exp(-(d-B*)^2/(2 C*^2)), B* = B1*(thV) - B2*(thL)  (eq. 3.32)"
                                            : mdl == CU_MODEL_LOGSEP ? "C = cos thL P*(Theta) H(d/t, thV) K(d/t, thL), log-linear in d between rows"
                                            : "C = cos thL P*(Theta, d/t) H(d/t, thV) K(d/t, thL), log-linear in d between rows");
            fprintf(fo, "# name group t_m node value\n");
        }
        FILE *fpred = NULL;
        if (predict) {
            char path[4096];
            snprintf(path, sizeof path, "%s_%s.txt", predict, mname);
            if (!(fpred = fopen(path, "w"))) die(1, "cannot write the prediction file", path);
            fprintf(fpred, "# group t_m d_m thetaV phiV thetaL C C_se model_%s\n", mname);
        }
        printf("\n## model %s\n# group  t_m  cells  median_rel  p90_rel  mc_noise_median%s  lm_iter status\n", mname,
               holdout ? "  heldout_cells heldout_median heldout_p90" : "");
        for (int g = 1; g <= 8; g++) {
            int na = 0, nh = 0;
            for (int it = 0; it < nt; it++) {
                cu_fit f;
                if (cu_fit_slice(&f, mdl, g, ts[it], cells, n, use)) continue;
                double noise;
                int k = cu_fit_errors(&f, cells, n, use, 1, frac, err, n, &noise);
                printf("%-5s %8.4g %6d %9.4f %9.4f %9.4f", gname[g], ts[it], k, cu_quantile(err, k, 0.5),
                       cu_quantile(err, k, 0.9), noise);
                memcpy(all + na, err, sizeof(double) * k); na += k;
                if (holdout) {
                    int kh = cu_fit_errors(&f, cells, n, use, 0, frac, err, n, NULL);
                    printf("  %6d %9.4f %9.4f", kh, cu_quantile(err, kh, 0.5), cu_quantile(err, kh, 0.9));
                    memcpy(allh + nh, err, sizeof(double) * kh); nh += kh;
                }
                printf("  %4d %d\n", f.iter, f.status);
                if (fo) cu_fit_write(fo, &f);
                for (int i = 0; fpred && i < n; i++)
                    if (cells[i].group == g && fabs(cells[i].t - ts[it]) <= 1e-6 * ts[it])
                        fprintf(fpred, "%d %g %g %g %g %g %.6e %.3e %.6e\n", g, cells[i].t, cells[i].d, cells[i].thv,
                                cells[i].phv, cells[i].thl, cells[i].C, cells[i].Cse,
                                cu_fit_eval(&f, cells[i].d, cells[i].thv, cells[i].phv, cells[i].thl));
            }
            int cmp(const void *x, const void *y);
            qsort(all, na, sizeof(double), cmp);
            printf("GROUP %s %s all-t: cells %d median %.4f p90 %.4f", mname, gname[g], na, cu_quantile(all, na, 0.5),
                   cu_quantile(all, na, 0.9));
            if (holdout) {
                qsort(allh, nh, sizeof(double), cmp);
                printf(" | held-out cells %d median %.4f p90 %.4f", nh, cu_quantile(allh, nh, 0.5), cu_quantile(allh, nh, 0.9));
            }
            printf("\n");
        }
        if (fo && tool_close_output(fo)) die(1, "writing the output table failed", out);
        if (fpred && tool_close_output(fpred)) die(1, "writing the prediction file failed", predict);
    }
    free(err); free(all); free(allh); free(use); free(cells);
    return 0;
}

int cmp(const void *x, const void *y)
{
    double a = *(const double *)x, b = *(const double *)y;
    return a < b ? -1 : a > b;
}
