/* tools/sweep/fit.c: `cumulo-sweep --fit-octaves` (issue 14): the octave model of multiple scattering (ms.mode =
 * octaves, Wrenninge 2015: octave o attenuates the sunlight by a^o of the optical depth toward the sun and scatters
 * b^o of it with the anisotropy c^o g) fitted to the path tracer instead of the textbook a = b = c = 1/2, which keeps
 * only 13-26 % of the multiple scattering a path tracer finds in a cumulus. The fit is a coordinate descent over a
 * grid of the four parameters (ms.octaves, ms.a, ms.b, ms.c): a line search over the octave count, a search of the
 * whole a x b grid (the two trade against each other: more light per octave against less attenuation), a line
 * search over c, each rendering every candidate with the others held, until a whole pass changes nothing. Its objective is the mean relative RMSE on
 * the clouds' pixels (metrics.c: 3x3 box filter, the reference against the sky alone) over training views whose sky
 * is black (scenes/fit/: nothing but the sunlight the cloud scatters, once and many times), rendered with `high`'s
 * settings otherwise (Kol's method, the baseline's phase function). The views the fit is judged on are others: the
 * sweep's and --methods' views. Writes fit.csv (every configuration rendered, per view), fit.md (the descent and the
 * result against the textbook factors, the slab model and no multiple scattering) and fit.txt (the chosen keys, which
 * src/core/scene_keys.c takes as its defaults; tests/app/test_cli.sh checks that they agree). */
#include "sweep.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { P_N, P_A, P_B, P_C, NPAR };
static const char *const PNAME[NPAR] = {"ms.octaves", "ms.a", "ms.b", "ms.c"};
#define MAXV 12
static const char *const GRID[NPAR][MAXV] = {
    {"2", "3", "4", "5", "6", "8"},
    {"0.02", "0.05", "0.1", "0.15", "0.2", "0.25", "0.3", "0.35", "0.4", "0.5", "0.6", "0.75"},
    {"0.3", "0.35", "0.4", "0.45", "0.5", "0.55", "0.6", "0.65", "0.7", "0.8", "0.9"},
    {"0.1", "0.3", "0.5", "0.7", "0.85", "1"},
};
static const int NVAL[NPAR] = {6, 12, 11, 6};
static const int TEXTBOOK[NPAR] = {2, 9, 4, 2}; /* 4 octaves, a = b = c = 0.5: the start, and the control */
#define MAX_PASSES 6
#define NCELLS (6 * 12 * 11 * 6)
#define MAXBATCH (12 * 11)

typedef struct fitrun {
    sweep *sw;
    double mean[NCELLS]; /* mean cloud relative RMSE over the views; < 0: not rendered */
    result *per_view;    /* [cell * nviews + view] */
    FILE *csv, *trail;   /* fit.csv, and the descent's lines for fit.md (a temporary file) */
    int rendered;
} fitrun;

static int cell(const int *ix)
{
    return ((ix[P_N] * 12 + ix[P_A]) * 11 + ix[P_B]) * 6 + ix[P_C];
}

static void make_config(const int *ix, config *c)
{
    config_high(c);
    snprintf(c->extra, SW_EXTRA_LEN, "ms.mode=octaves;ms.octaves=%s;ms.a=%s;ms.b=%s;ms.c=%s", GRID[P_N][ix[P_N]],
             GRID[P_A][ix[P_A]], GRID[P_B][ix[P_B]], GRID[P_C][ix[P_C]]);
}

/* Renders the cells of cand[0..n-1] not rendered yet on every view, as one batch per view. */
static int evaluate(fitrun *f, int cand[][NPAR], int n)
{
    sweep *sw = f->sw;
    static config cfg[MAXBATCH];
    static result res[MAXBATCH];
    int todo[MAXBATCH], m = 0;
    for (int i = 0; i < n; i++)
        if (f->mean[cell(cand[i])] < 0) {
            make_config(cand[i], &cfg[m]);
            todo[m++] = i;
        }
    if (m == 0)
        return 0;
    for (int s = 0; s < sw->nviews; s++) {
        memset(res, 0, sizeof res);
        if (sw_error_view(sw, &sw->v[s], cfg, m, res, NULL))
            return 1;
        for (int j = 0; j < m; j++)
            f->per_view[(size_t)cell(cand[todo[j]]) * sw->nviews + s] = res[j];
    }
    for (int j = 0; j < m; j++) {
        int c = cell(cand[todo[j]]);
        double sum = 0;
        for (int s = 0; s < sw->nviews; s++) {
            const result *r = &f->per_view[(size_t)c * sw->nviews + s];
            sum += r->cloud_rel_rmse;
            fprintf(f->csv, "%s,%s,%s,%s,%s,%.5f,%.4f,%.4f,%.4f\n", sw->v[s].name, GRID[P_N][cand[todo[j]][P_N]],
                    GRID[P_A][cand[todo[j]][P_A]], GRID[P_B][cand[todo[j]][P_B]], GRID[P_C][cand[todo[j]][P_C]],
                    r->cloud_rel_rmse, r->contrast, sw->v[s].ref_contrast, r->ssim);
        }
        f->mean[c] = sum / sw->nviews;
        f->rendered++;
    }
    return 0;
}

/* One search: every value of parameter p (and, when q >= 0, every pair with parameter q) with the others as in ix;
 * they become the best. Returns 1 when it moved, 0 when not, -1 on a failure. */
static int search(fitrun *f, int *ix, int p, int q, int pass)
{
    static int cand[MAXBATCH][NPAR];
    int n = 0;
    for (int v = 0; v < NVAL[p]; v++)
        for (int w = 0; w < (q < 0 ? 1 : NVAL[q]); w++, n++) {
            memcpy(cand[n], ix, sizeof cand[n]);
            cand[n][p] = v;
            if (q >= 0)
                cand[n][q] = w;
        }
    if (evaluate(f, cand, n))
        return -1;
    int best = -1;
    for (int i = 0; i < n; i++)
        if (best < 0 || f->mean[cell(cand[i])] < f->mean[cell(cand[best])] ||
            (f->mean[cell(cand[i])] == f->mean[cell(cand[best])] && cell(cand[i]) == cell(ix)))
            best = i;
    if (q < 0) {
        fprintf(f->trail, "| %d | %s |", pass, PNAME[p]);
        for (int i = 0; i < n; i++)
            fprintf(f->trail, i == best ? " **%s: %.4f**" : " %s: %.4f", GRID[p][cand[i][p]], f->mean[cell(cand[i])]);
    } else {
        /* the a x b grid: each value of p with its best partner */
        fprintf(f->trail, "| %d | %s x %s (each %s with its best %s) |", pass, PNAME[p], PNAME[q], PNAME[p], PNAME[q]);
        for (int v = 0; v < NVAL[p]; v++) {
            int bv = v * NVAL[q];
            for (int w = 1; w < NVAL[q]; w++)
                if (f->mean[cell(cand[v * NVAL[q] + w])] < f->mean[cell(cand[bv])])
                    bv = v * NVAL[q] + w;
            fprintf(f->trail, cand[bv][p] == cand[best][p] ? " **%s, %s: %.4f**" : " %s, %s: %.4f",
                    GRID[p][cand[bv][p]], GRID[q][cand[bv][q]], f->mean[cell(cand[bv])]);
        }
    }
    fprintf(f->trail, " |\n");
    printf("fit: pass %d, %s = %s", pass, PNAME[p], GRID[p][cand[best][p]]);
    if (q >= 0)
        printf(", %s = %s", PNAME[q], GRID[q][cand[best][q]]);
    printf(" (mean cloud relative RMSE %.4f)\n", f->mean[cell(cand[best])]);
    fflush(stdout);
    int moved = cell(cand[best]) != cell(ix);
    memcpy(ix, cand[best], sizeof cand[best]);
    return moved;
}

/* The result against its controls on every view (rendered anew, so every row comes from one batch). */
static int write_md(fitrun *f, const int *ix, FILE *md)
{
    sweep *sw = f->sw;
    static const char *const LABEL[4] = {"fitted octaves", "textbook octaves (4, a = b = c = 0.5)",
                                         "slab model (`high`)", "no multiple scattering"};
    config cfg[4];
    make_config(ix, &cfg[0]);
    make_config(TEXTBOOK, &cfg[1]);
    config_high(&cfg[2]);
    config_high(&cfg[3]);
    snprintf(cfg[3].extra, SW_EXTRA_LEN, "ms.mode=none");
    fprintf(md, "\n## The fit against its controls\n\nWhere the light goes: the cloud's pixels in fifths by the path "
                "tracer's brightness, darkest first, and in each the light rendered over the path tracer's.\n\n"
                "| view | configuration | rel. RMSE (cloud) | contrast / the path tracer's | SSIM | light by "
                "brightness fifth |\n| --- | --- | ---: | ---: | ---: | --- |\n");
    double mean[4] = {0};
    for (int s = 0; s < sw->nviews; s++) {
        result res[4];
        memset(res, 0, sizeof res);
        if (sw_error_view(sw, &sw->v[s], cfg, 4, res, NULL))
            return 1;
        for (int i = 0; i < 4; i++) {
            mean[i] += res[i].cloud_rel_rmse / sw->nviews;
            fprintf(md, "| %s | %s | %.4f | %.2f | %.3f | %.2f %.2f %.2f %.2f %.2f |\n", sw->v[s].name, LABEL[i],
                    res[i].cloud_rel_rmse, sw->v[s].ref_contrast > 0 ? res[i].contrast / sw->v[s].ref_contrast : 0,
                    res[i].ssim, res[i].fifths[0], res[i].fifths[1], res[i].fifths[2], res[i].fifths[3],
                    res[i].fifths[4]);
        }
    }
    fprintf(md, "\nMean relative RMSE over the views: ");
    for (int i = 0; i < 4; i++)
        fprintf(md, "%s%s %.4f", i ? ", " : "", LABEL[i], mean[i]);
    fprintf(md, ".\n");
    return 0;
}

static int copy_rest(FILE *from, FILE *to)
{
    char buf[4096];
    size_t n;
    rewind(from);
    while ((n = fread(buf, 1, sizeof buf, from)) > 0)
        if (fwrite(buf, 1, n, to) != n)
            return 1;
    return ferror(from);
}

int sw_fit_run(sweep *sw)
{
    static fitrun f;
    memset(&f, 0, sizeof f);
    f.sw = sw;
    for (int i = 0; i < NCELLS; i++)
        f.mean[i] = -1;
    int rc = 0;
    double t0 = sw_now_ms();
    for (int s = 0; s < sw->nviews && rc == 0; s++)
        rc = sw_view_cloud_mask(sw, &sw->v[s]);
    if (rc == 0 && !(f.per_view = calloc((size_t)NCELLS * sw->nviews, sizeof(result)))) {
        fprintf(stderr, "cumulo-sweep: out of memory\n");
        rc = 1;
    }
    if (rc == 0 && !(f.csv = sw_open_out(sw, "fit.csv")))
        rc = 1;
    if (rc == 0 && !(f.trail = tmpfile())) {
        fprintf(stderr, "cumulo-sweep: cannot make a temporary file\n");
        rc = 1;
    }
    int ix[NPAR];
    memcpy(ix, TEXTBOOK, sizeof ix);
    int pass = 0;
    if (rc == 0) {
        fprintf(f.csv, "# cumulo-sweep --fit-octaves: Kol's method with high's settings and ms.mode = octaves, at "
                       "%dx%d against cumulo-pt at %d spp, on the cloud's pixels\n"
                       "view,octaves,a,b,c,cloud_rel_rmse,contrast,ref_contrast,ssim\n",
                sw->ew, sw->eh, sw->spp);
        for (int moved = 1; moved && pass < MAX_PASSES && rc == 0; pass++) {
            moved = 0;
            static const int MOVES[3][2] = {{P_N, -1}, {P_A, P_B}, {P_C, -1}};
            for (int k = 0; k < 3 && rc == 0; k++) {
                int m = search(&f, ix, MOVES[k][0], MOVES[k][1], pass + 1);
                if (m < 0)
                    rc = 1;
                moved |= m > 0;
            }
        }
    }
    FILE *md = NULL, *txt = NULL;
    if (rc == 0 && (!(md = sw_open_out(sw, "fit.md")) || !(txt = sw_open_out(sw, "fit.txt"))))
        rc = 1;
    if (rc == 0) {
        const char *lp = getenv("LP_NUM_THREADS");
        fprintf(md, "# The octave model of multiple scattering, fitted to the path tracer\n\n"
                    "Written by `cumulo-sweep --fit-octaves` (`make fit-octaves`), LP_NUM_THREADS=%s. Training views "
                    "(black sky: the sunlight the cloud scatters alone):",
                lp ? lp : "(unset)");
        for (int s = 0; s < sw->nviews; s++)
            fprintf(md, "%s %s (the path tracer's contrast %.2f, %d cloud pixels)", s ? "," : "", sw->v[s].name,
                    sw->v[s].ref_contrast, sw->v[s].mask_n);
        fprintf(md, ". Rendered with Kol's method and `high`'s settings, ms.mode = octaves, at %dx%d against "
                    "cumulo-pt at %d spp; the objective is the mean relative RMSE on the clouds' pixels after a 3x3 "
                    "box filter. Coordinate descent from the textbook factors (4 octaves, a = b = c = 0.5), the octave "
                    "count, the a x b grid, then c, until a pass changes nothing: %d passes, %d configurations rendered "
                    "(fit.csv), %.1f min.\n\n"
                    "**Result: ms.octaves = %s, ms.a = %s, ms.b = %s, ms.c = %s** (mean relative RMSE %.4f).\n\n"
                    "## The descent (mean relative RMSE of each value; the chosen one in bold)\n\n"
                    "| pass | parameter | values |\n| ---: | --- | --- |\n",
                sw->ew, sw->eh, sw->spp, pass, f.rendered, (sw_now_ms() - t0) / 60e3, GRID[P_N][ix[P_N]],
                GRID[P_A][ix[P_A]], GRID[P_B][ix[P_B]], GRID[P_C][ix[P_C]], f.mean[cell(ix)]);
        rc = copy_rest(f.trail, md) || write_md(&f, ix, md);
        fprintf(txt, "# the octave model's keys from `cumulo-sweep --fit-octaves` (docs/ms_octaves_fit.md): the defaults "
                     "in src/core/scene_keys.c\n%s=%s\n%s=%s\n%s=%s\n%s=%s\n",
                PNAME[P_N], GRID[P_N][ix[P_N]], PNAME[P_A], GRID[P_A][ix[P_A]], PNAME[P_B], GRID[P_B][ix[P_B]],
                PNAME[P_C], GRID[P_C][ix[P_C]]);
    }
    if (f.csv)
        rc |= sw_close_out(sw, f.csv, "fit.csv");
    if (md)
        rc |= sw_close_out(sw, md, "fit.md");
    if (txt)
        rc |= sw_close_out(sw, txt, "fit.txt");
    if (f.trail)
        fclose(f.trail);
    free(f.per_view);
    for (int s = 0; s < sw->nviews; s++) {
        free(sw->v[s].mask);
        sw->v[s].mask = NULL;
    }
    if (rc == 0)
        printf("sweep: wrote %s/fit.csv, fit.md, fit.txt in %.1f min\n", sw->out, (sw_now_ms() - t0) / 60e3);
    return rc;
}
