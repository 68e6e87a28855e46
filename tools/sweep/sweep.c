/* tools/sweep/sweep.c: the run of cumulo-sweep (the parts are listed in sweep.h): the knob table from the baseline,
 * references and display constants per view, every one-knob variant on every view, the means over views, the
 * preset choice and the output files. */
#include "sweep.h"
#include "scene.h"
#include "sky.h"
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <time.h>

#define MAX_VARIANTS (SW_NKNOBS * SW_MAX_VALUES + 1)

double sw_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

int sw_cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double sw_median(double *t, int n)
{
    qsort(t, (size_t)n, sizeof *t, sw_cmp_double);
    return n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
}

const char *sw_data_dir(void)
{
    const char *dd = getenv("CUMULO_DATA_DIR");
    struct stat sb;
    if (!dd)
        dd = stat("data/mie_cloud.tbl", &sb) == 0 ? "data" : NULL;
    return dd;
}

int sw_mkdirs(const char *path)
{
    char tmp[1024];
    snprintf(tmp, sizeof tmp, "%s", path);
    for (char *p = tmp + 1; *p; p++)
        if (*p == '/') {
            *p = 0;
            if (mkdir(tmp, 0777) && errno != EEXIST)
                return -1;
            *p = '/';
        }
    return mkdir(tmp, 0777) && errno != EEXIST ? -1 : 0;
}

/* Exposure, white balance and clip level of each view, and its reference. */
static int prepare_views(sweep *sw)
{
    for (int s = 0; s < sw->nviews; s++) {
        view *v = &sw->v[s];
        cu_scene *sc;
        cu_error e;
        if (cu_scene_load(&sc, v->path, &e))
            return fprintf(stderr, "cumulo-sweep: %s\n", e.msg), 1;
        v->exposure = sc->exposure;
        v->noise_on = sc->noise;
        cu_sky_white_balance(sc, v->white);
        cu_scene_free(sc);
        for (int c = 0; c < 3; c++)
            v->clip[c] = v->exposure > 0 ? 16.0 * v->white[c] / v->exposure : 1e30;
        if (sw_load_reference(sw, v))
            return 1;
        printf("sweep: reference %s: PT noise sqrt(mean sigma^2) = %.4g (%.2f%% of the mean radiance), mean standard "
               "error %.4g\n",
               v->name, v->pt_noise, 100 * v->pt_rel_noise, v->pt_mean_se);
    }
    return 0;
}

/* The single-knob variants: index 0 = high; vidx[k * SW_MAX_VALUES + j] = the variant of value j of knob k (0 for
 * the high value, -1 when not measured). Returns the count. */
static int make_variants(const sweep *sw, config *vars, int *vknob, int *vval, int *vidx)
{
    int nv = 0;
    config_high(&vars[nv]);
    vknob[nv] = -1, vval[nv] = -1;
    nv++;
    for (int k = 0; k < SW_NKNOBS; k++)
        for (int j = 0; j < SW_MAX_VALUES; j++) {
            vidx[k * SW_MAX_VALUES + j] = -1;
            if (j >= sw_knobs[k].nvals)
                continue;
            if (j == sw_knobs[k].high) {
                vidx[k * SW_MAX_VALUES + j] = 0;
                continue;
            }
            if (sw->quick && !sw_knobs[k].quick[j])
                continue;
            config_high(&vars[nv]);
            vars[nv].v[k] = j;
            vknob[nv] = k, vval[nv] = j;
            vidx[k * SW_MAX_VALUES + j] = nv;
            nv++;
        }
    return nv;
}

/* All variants on view v into out[0..nv-1]; with the view's noise off the noise knob changes nothing, so only what
 * differs is measured and high copied for the rest. */
static int measure_variants(sweep *sw, view *v, const config *vars, const int *vknob, int nv, result *out)
{
    config sub[MAX_VARIANTS];
    int map[MAX_VARIANTS], ns = 0;
    for (int i = 0; i < nv; i++) {
        if (!v->noise_on && i > 0 && sw_knob_is(vknob[i], "quality.noise_octaves")) {
            map[i] = -1;
            continue;
        }
        map[i] = ns;
        sub[ns++] = vars[i];
    }
    result *r = calloc((size_t)ns, sizeof(result));
    if (!r)
        return fprintf(stderr, "cumulo-sweep: out of memory\n"), 1;
    if (sw_measure_view(sw, v, sub, ns, r)) {
        free(r);
        return 1;
    }
    for (int i = 0; i < nv; i++)
        out[i] = map[i] >= 0 ? r[map[i]] : r[0];
    free(r);
    return 0;
}

static void variant_rows(sweep *sw, const char *scene, const config *vars, const int *vknob, const int *vval, int nv,
                         const result *r, double pt_rel_noise)
{
    for (int i = 0; i < nv; i++)
        sw_csv_row(sw, "variant", scene, i ? sw_knobs[vknob[i]].name : "high", i ? sw_knobs[vknob[i]].vals[vval[i]] : "",
                   &vars[i], &r[i], pt_rel_noise);
    fflush(sw->csv);
}

int sw_run(sweep *sw)
{
    cu_error e;
    if (sw_knobs_init(sw->baseline, &e))
        return fprintf(stderr, "%s\n", e.msg), 1;
    const char *dirs[2] = {sw->out, sw->refdir};
    for (int i = 0; i < 2; i++)
        if (sw_mkdirs(dirs[i]))
            return fprintf(stderr, "cumulo-sweep: cannot create %s: %s\n", dirs[i], strerror(errno)), 1;
    double t_start = sw_now_ms();
    const char *lp = getenv("LP_NUM_THREADS");
    printf("sweep: %d views, error at %dx%d against the path tracer at %d spp, time at %dx%d (%s of %d frames "
           "after %d warm-up, %s), LP_NUM_THREADS=%s%s; high = %s\n",
           sw->nviews, sw->ew, sw->eh, sw->spp, sw->tw, sw->th, sw->sun_step > 0 ? "mean" : "median", sw->frames,
           sw->warmup, sw->sun_step > 0 ? "the sun turned every frame" : sw->sun_moving ? "sun moved every frame"
                                                                            : "static sun",
           lp ? lp : "(unset)", sw->quick ? ", quick" : "", sw->baseline);
    if (prepare_views(sw))
        return 1;
    if (sw->refs_only)
        return 0;
    if (sw->score)
        return sw_score_run(sw, sw->score);
    if (sw->methods)
        return sw_methods_run(sw);
    if (sw->fit)
        return sw_fit_run(sw);

    static config vars[MAX_VARIANTS];
    static int vknob[MAX_VARIANTS], vval[MAX_VARIANTS], vidx[SW_NKNOBS * SW_MAX_VALUES];
    int nv = make_variants(sw, vars, vknob, vval, vidx);
    char path[1200];
    snprintf(path, sizeof path, "%s/sweep.csv", sw->out);
    sw->csv = fopen(path, "w");
    if (!sw->csv)
        return fprintf(stderr, "cumulo-sweep: cannot write %s\n", path), 1;
    sw_csv_header(sw);
    result *per_view[SW_MAX_SCENES] = {0}, *agg = calloc((size_t)nv, sizeof(result));
    int rc = !agg;
    for (int s = 0; s < sw->nviews && rc == 0; s++)
        rc = !(per_view[s] = calloc((size_t)nv, sizeof(result)));
    if (rc)
        fprintf(stderr, "cumulo-sweep: out of memory\n");
    for (int s = 0; s < sw->nviews && rc == 0; s++) {
        rc = sw_view_cloud_mask(sw, &sw->v[s]) || measure_variants(sw, &sw->v[s], vars, vknob, nv, per_view[s]);
        if (rc == 0)
            variant_rows(sw, sw->v[s].name, vars, vknob, vval, nv, per_view[s], sw->v[s].pt_rel_noise);
    }
    for (int i = 0; i < nv && rc == 0; i++)
        sw_aggregate(sw, per_view, i, &agg[i]);
    if (rc == 0)
        variant_rows(sw, "ALL", vars, vknob, vval, nv, agg, 0);

    point med, low, high, trail[SW_MAX_GREEDY];
    int ntrail = 0;
    if (rc == 0)
        rc = sw_choose_presets(sw, agg, vidx, &agg[0], &med, &low, trail, &ntrail);
    const point *presets[3] = {&low, &med, &high};
    if (rc == 0) {
        config_high(&high.c);
        high.agg = agg[0];
        for (int p = 0; p < 3; p++)
            sw_csv_row(sw, "preset", "ALL", sw_preset_names[p], "", &presets[p]->c, &presets[p]->agg, 0);
    }
    if ((ferror(sw->csv) | fclose(sw->csv)) && rc == 0) {
        fprintf(stderr, "cumulo-sweep: error writing %s\n", path);
        rc = 1;
    }
    if (rc == 0)
        rc = sw_write_presets(sw, presets) || sw_write_pareto(sw, agg, vknob, vval, nv, trail, ntrail, presets) ||
             sw_write_md(sw, agg, vknob, vval, nv, presets, per_view);
    if (rc == 0) {
        printf("sweep: wrote %s/sweep.csv, sweep.md, presets.txt, pareto.dat in %.1f min\n", sw->out,
               (sw_now_ms() - t_start) / 60e3);
        struct stat st;
        if (stat(sw->plot, &st) == 0) {
            char cmd[2600];
            snprintf(cmd, sizeof cmd, "sh '%s' '%s'", sw->plot, sw->out);
            fflush(stdout);
            if (system(cmd) != 0)
                fprintf(stderr, "cumulo-sweep: %s did not draw %s/pareto.png (CSV and tables are written)\n",
                        sw->plot, sw->out);
        }
    }
    for (int s = 0; s < sw->nviews; s++) {
        free(per_view[s]);
        free(sw->v[s].mask);
        sw->v[s].mask = NULL;
        cu_image_free(&sw->v[s].ref);
    }
    free(agg);
    return rc;
}
