/* cumulo-slab-fit: fits eq. 3.32 (and a log-separable alternative) to cumulo-slab tables, reports fit errors per group. */
#include "fitlib.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

static void die(const char *m)
{
    fprintf(stderr, "cumulo-slab-fit: error: %s\n", m);
    exit(2);
}

int main(int argc, char **argv)
{
    const char *out = NULL, *predict = NULL;
    int models[3] = { 1, 1, 1 }, holdout = 0, nfiles = 0;
    double frac = 0.01;
    cu_cell *cells = NULL;
    int n = 0;
    setvbuf(stdout, NULL, _IOLBF, 0);   /* reports are long runs: keep the file current line by line */
    char msg[512];
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--help")) {
            printf("usage: cumulo-slab-fit [--model bouthors|logsep|logsep2|all] [--holdout] [--frac F] [--out PREFIX] [--predict FILE] TABLE...\n"
                   "Fits per (group, thickness); --holdout trains on phi_V != 90 and reports errors on phi_V = 90.\n");
            return 0;
        } else if (!strcmp(argv[i], "--model") && i + 1 < argc) {
            const char *m = argv[++i];
            models[0] = models[1] = models[2] = 0;
            if (!strcmp(m, "bouthors")) models[0] = 1;
            else if (!strcmp(m, "logsep")) models[1] = 1;
            else if (!strcmp(m, "logsep2")) models[2] = 1;
            else if (!strcmp(m, "all") || !strcmp(m, "both")) models[0] = models[1] = models[2] = 1;
            else die("--model must be bouthors, logsep, logsep2 or all");
        } else if (!strcmp(argv[i], "--holdout")) holdout = 1;
        else if (!strcmp(argv[i], "--frac") && i + 1 < argc) frac = atof(argv[++i]);
        else if (!strcmp(argv[i], "--out") && i + 1 < argc) out = argv[++i];
        else if (!strcmp(argv[i], "--predict") && i + 1 < argc) predict = argv[++i];
        else if (argv[i][0] == '-') die("unknown option (see --help)");
        else {
            if (cu_cells_read(argv[i], &cells, &n, msg, sizeof msg)) die(msg);
            nfiles++;
        }
    }
    if (!nfiles || n == 0) die("no table rows given");
    if (!(frac > 0 && frac < 1)) die("--frac must be in (0,1)");
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
            if (!(fo = fopen(path, "w"))) die("cannot write output table");
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
            if (!(fpred = fopen(path, "w"))) die("cannot write prediction file");
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
        if (fo) fclose(fo);
        if (fpred) fclose(fpred);
    }
    free(err); free(all); free(allh); free(use); free(cells);
    return 0;
}

int cmp(const void *x, const void *y)
{
    double a = *(const double *)x, b = *(const double *)y;
    return a < b ? -1 : a > b;
}
