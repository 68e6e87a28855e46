/* tools/sweep/sweep.h: what the parts of cumulo-sweep share (README "Speed against accuracy").
 *
 * For every view (scene file) and every variant (one knob changed from `high`, or a preset) the sweep measures
 *   - time: median wall-clock frame time (incl. glFinish, as `cumulo bench`) at the timing size, static sun, as a
 *     ratio to `high` timed in the same session (high is timed three times in each view's round, frames pooled);
 *   - error against the reference path tracer's image (tools/pathtrace/pt.c, linked in) of the same view with the
 *     high settings, at the error size: RMSE and PSNR on linear RGB (peak = the reference's 99th-percentile channel
 *     value), max abs error, relative RMSE (RMSE / mean reference radiance) and the share of pixels whose tone-mapped
 *     8-bit sRGB values (src/core/tonemap.c with the scene's exposure and white balance) differ by more than a
 *     threshold.
 * Then it picks the presets greedily and writes DIR/sweep.csv, DIR/sweep.md, DIR/presets.txt and DIR/pareto.dat
 * (plotted by scripts/sweep_plot.sh into DIR/pareto.png).
 *
 * The parts: options.c (command line, views), knobs.c (the knob table; `high` read from the baseline scene),
 * reference.c (path-traced references, cached), metrics.c (error of one image, aggregates), measure.c (timing and
 * rendering one view's variants), choose.c (preset choice), report.c (the output files), sweep.c (the run). */
#ifndef SW_SWEEP_H
#define SW_SWEEP_H
#include "cumulo.h"
#include "image.h"
#include <stddef.h>
#include <stdio.h>

#define SW_MAX_SCENES 16
#define SW_MAX_VALUES 8
#define SW_MAX_SETS 40
#define SW_FIFTHS 5    /* result.fifths: the cloud's pixels by the reference's brightness */
#define SW_NKNOBS 18   /* entries of the knob table (knobs.c checks) */
#define SW_VALUE_LEN 24
#define SW_DEFAULT_BASELINE "scenes/cumulus.scene" /* the default scene: its settings are `high` */
#define SW_MAX_GREEDY 24 /* greedy steps (combinations measured) at most */

/* ---- knobs.c ---- */
typedef struct knob {
    const char *name;   /* scene key, or "output.scale" */
    int high;           /* index of the baseline value in vals */
    int nvals;
    char vals[SW_MAX_VALUES][SW_VALUE_LEN];
    int quick[SW_MAX_VALUES]; /* 1: measured in --quick */
} knob;
/* The knob table, valid after sw_knobs_init. */
extern knob sw_knobs[SW_NKNOBS];
/* Fills sw_knobs: every knob's `high` value is the one the baseline scene file has (read through cu_scene_load and
 * the cu_scene struct); a value not among the listed alternatives is added. 0, or 1 with a message. */
int sw_knobs_init(const char *baseline_path, cu_error *err);
int sw_knob_is(int k, const char *name);

/* A configuration: one value index per knob, then extra "key=value" settings separated by ';', applied after the
 * knobs' (cumulo-sweep --methods: the presets and the uniform ray march; empty in the one-knob sweep). */
#define SW_EXTRA_LEN 600
typedef struct config {
    int v[SW_NKNOBS];
    char extra[SW_EXTRA_LEN];
} config;
void config_high(config *c);
/* --set list ("key=value", all knobs given explicitly) and resolution scale of a configuration; returns the count. */
int config_sets(const config *c, char sets[][64], double *scale);
/* "knob=value" changes from high, joined with sep ("high" when none). */
void config_diff(const config *c, char *out, size_t len, const char *sep);
/* "--set a=b --set c=d ..." (and a note on the scale), as presets.txt writes it. */
void config_sets_line(const config *c, char *out, size_t len);
/* Whether value j of knob k may be part of a preset (it changes precision, not the scene's content). */
int knob_preset_eligible(int k, int j, int sun_timed);

/* ---- the run's state ---- */
typedef struct result {
    double time_ms, time_ratio;
    double tmin_ms, tmin_ratio; /* fastest frame: on a loaded machine the least disturbed estimate */
    double rmse, psnr, peak, maxabs, visible, mean_ref, rel_rmse;
    double rel_bias;       /* sqrt(max(0, MSE - mean sigma^2 of the reference)) / mean reference: PT noise removed */
    /* on the pixels the cloud changes (view.mask; --methods): where the light is, not only how much */
    double cloud_rel_rmse; /* RMSE / mean reference after a 3x3 box filter of both (jitter and PT noise averaged) */
    double contrast;       /* p90 / p10 of the 3x3-filtered luminance */
    double ssim;           /* mean SSIM of the tone-mapped 8-bit luminance, 7x7 windows centred on cloud pixels */
    double contrast_err;   /* |ln(contrast / the reference's)|: flatter or steeper than the truth (0: as contrasted) */
    double error;          /* what presets are chosen by: cloud_rel_rmse, or rel_rmse on a view without cloud pixels */
    /* where the light goes: the cloud's pixels in fifths by the reference's filtered luminance, darkest first; in
     * each, the image's light over the reference's (1: right; > 1 in the darkest fifth and < 1 in the brightest is a
     * flattened picture, whatever the mean error) */
    double fifths[SW_FIFTHS];
    int ok;
} result;

typedef struct view {
    char path[512], name[128];
    cu_image ref;          /* linear RGB */
    double pt_noise;       /* sqrt(mean sigma^2) of the reference: its expected contribution to an RMSE */
    double pt_mean_se;     /* mean standard error per pixel and channel */
    double pt_rel_noise;   /* pt_noise / mean reference radiance */
    double pt_var;         /* mean sigma^2 */
    double exposure, white[3];
    double clip[3];        /* radiance the display curve saturates at (exposure * L / white = 16): the sun disk */
    int noise_on;
    unsigned char *mask;   /* --methods: 1 where the reference differs from the sky alone (the cloud), error size */
    int mask_n;            /* pixels in it */
    double ref_contrast;   /* the reference's contrast over the mask (result.contrast's definition) */
    double fifth_edge[SW_FIFTHS - 1]; /* the reference's filtered luminance at 20, 40, 60, 80 % of the mask */
} view;

typedef struct sweep {
    int ew, eh, tw, th;    /* error and timing sizes */
    int spp, frames, warmup, quick, threshold, pt_threads;
    int sun_moving;        /* --sun-every-frame: time frames that redo the sun pass, as `cumulo bench` does */
    double sun_step;       /* --sun-step DEG: every timed frame turns the sun DEG further (the maps made again a band a
                            * frame, diffusion's grids solved again within ms.frame_work); the mean frame is timed */
    int refs_only;
    int methods;           /* --methods: Kol's method against the uniform ray march (methods.c) */
    int fit;               /* --fit-octaves: the octave model fitted to the path tracer (fit.c) */
    const char *score;     /* --score DIR: images rendered elsewhere scored against the references (score.c) */
    double budget_med, budget_low;
    const char *out, *refdir, *plot, *baseline;
    int nviews;
    view v[SW_MAX_SCENES];
    FILE *csv;
} sweep;

typedef struct point {
    config c;
    result agg;
} point;

/* ---- options.c ---- */
/* Parses the command line into sw (defaults first). Returns 0 to run, 2 after printing a one-line usage error, or
 * -1 after printing --help or --version (exit 0). */
int sw_parse_options(sweep *sw, int argc, char **argv);

/* ---- sweep.c: small helpers ---- */
double sw_now_ms(void);
int sw_cmp_double(const void *a, const void *b);
double sw_median(double *t, int n); /* sorts t */
/* The tables' folder: $CUMULO_DATA_DIR, ./data in a source tree, else NULL (the library's default). */
const char *sw_data_dir(void);
int sw_mkdirs(const char *path);
/* The whole sweep after option parsing: 0, or 1 on a runtime failure (message printed). */
int sw_run(sweep *sw);

/* ---- reference.c ---- */
/* Renders with the path tracer (or finds in sw->refdir) the reference of v with the high settings, and its noise. */
int sw_load_reference(sweep *sw, view *v);

/* ---- metrics.c ---- */
/* Errors of img (linear RGB at the error size) against v's reference. */
void sw_compare(const sweep *sw, const view *v, const float *img, result *r);
/* Bilinear upsampling of a w x h RGB image (top row first) to W x H (pixel centres aligned). */
void sw_upsample(const float *src, int w, int h, float *dst, int W, int H);
/* The cloud mask of v from an image of its sky alone (the cloud's density 0), and the reference's contrast on it. */
int sw_view_mask(const sweep *sw, view *v, const float *sky);
/* cloud_rel_rmse, contrast, contrast_err and ssim of img against v's reference on v's mask, and error (after
 * sw_compare: without a mask, the whole image's rel_rmse). */
void sw_cloud_metrics(const sweep *sw, const view *v, const float *img, result *r);
/* Means over views of result idx (max_abs: the max). */
void sw_aggregate(const sweep *sw, result *const *per_view, int idx, result *agg);

/* ---- measure.c ---- */
/* Measures cfg[0..n-1] (cfg[0] = high, the time reference) on one view. */
int sw_measure_view(sweep *sw, view *v, const config *cfg, int n, result *res);
/* The error half alone: cfg[0..n-1] rendered linear at the error size and compared; the first image also into
 * first (when not NULL). */
int sw_error_view(sweep *sw, view *v, const config *cfg, int n, result *res, float *first);
/* One configuration on every view (high re-timed alongside); per-view and ALL rows go to the CSV under kind. */
int sw_measure_config(sweep *sw, const config *c, const char *kind, const char *label, result *agg);

/* ---- methods.c ---- */
/* cumulo-sweep --methods: Kol's method (presets and segment counts) against the uniform ray march (steps along the
 * view and toward the sun) on every view, timed in one interleaved run; writes methods.csv, methods.md, methods.dat. */
int sw_methods_run(sweep *sw);
/* The view's cloud mask (v->mask, mask_n, ref_contrast): its sky alone (every cloud's density 0) rendered at the
 * error size, against the reference. 0, or 1 with a message. */
int sw_view_cloud_mask(sweep *sw, view *v);
/* ---- score.c ---- */
/* --score: DIR/NAME.pfm of every view against its reference; writes sw->out/score.md. 0, or 1 (printed). */
int sw_score_run(sweep *sw, const char *dir);

/* ---- fit.c ---- */
/* cumulo-sweep --fit-octaves: the octave model's count and factors fitted to the views' references; writes fit.csv,
 * fit.md and fit.txt. */
int sw_fit_run(sweep *sw);

/* ---- choose.c ---- */
/* Greedy preset choice from the one-knob aggregates (vidx maps knob * SW_MAX_VALUES + value to a variant, -1 if not
 * measured; high the aggregate of high); trail gets the greedy combinations measured (at most SW_MAX_GREEDY). */
int sw_choose_presets(sweep *sw, const result *single_agg, const int *vidx, const result *high, point *med,
                      point *low, point *trail, int *ntrail);
/* Whether r is flatter or less like the truth in structure than high: SSIM more than 0.01 lower, or the contrast
 * more than 0.02 further off (in |ln|). Such a point is measured but never a preset. */
int sw_flatter(const result *r, const result *high);

/* ---- report.c ---- */
/* DIR/name opened for writing (NULL with a message), and closed with its write errors reported (1 with a message). */
FILE *sw_open_out(const sweep *sw, const char *name);
int sw_close_out(const sweep *sw, FILE *f, const char *name);
/* sweep.csv: the two header lines, then rows. */
void sw_csv_header(sweep *sw);
void sw_csv_row(sweep *sw, const char *kind, const char *scene, const char *knob, const char *value, const config *c,
                const result *r, double pt_rel_noise);
/* presets.txt, pareto.dat and sweep.md; each 0, or 1 with a message. presets[] = low, medium, high. */
int sw_write_presets(const sweep *sw, const point *const presets[3]);
int sw_write_pareto(const sweep *sw, const result *agg, const int *vknob, const int *vval, int nv, const point *trail,
                    int ntrail, const point *const presets[3]);
int sw_write_md(const sweep *sw, const result *agg, const int *vknob, const int *vval, int nv,
                const point *const presets[3], result *const *per_view);
extern const char *const sw_preset_names[3]; /* low, medium, high */
#endif
