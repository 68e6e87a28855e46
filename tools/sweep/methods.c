/* tools/sweep/methods.c: `cumulo-sweep --methods` (issue 14): Kol's method against the mainstream uniform ray march
 * (quality.method = uniform) on the same axes. On every view both families are timed in one interleaved run
 * (measure.c: round-robin frames, high three times) and compared with the view's path-traced reference on the
 * pixels the cloud changes: relative RMSE after a 3x3 box filter, the contrast p90/p10 against the reference's, and
 * SSIM of the tone-mapped luminance (metrics.c). Then, for each point of one family, the fastest point of the other
 * that is at least as accurate: the "time at equal error" ratios. Writes methods.csv, methods.md, methods.dat
 * (scripts/methods_plot.sh draws methods.png from it). */
#include "sweep.h"
#include "presets.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { FAM_KOL, FAM_UNIFORM };
static const char *const FAMILY[2] = {"kol", "uniform"};

/* Kol's method along its curve: the presets, and the segment count (the knob that moves its error most) about them;
 * then what this work changed in the defaults taken back: the exact noise (quality.noise_baked = off: 10 texture reads
 * a sample, not 2) and Kol's segments on chords that never reach the core (quality.boundary_step = 0). */
static const struct {
    int preset;        /* cu_preset whose settings come first */
    const char *more;  /* then these */
    const char *label;
    int control;       /* 1: what the defaults replaced, shown but not on the curve (fastest_within skips it) */
} KOL[] = {
    {CU_PRESET_HIGH, "", "high", 0}, /* first: the time reference of every ratio (measure.c) */
    {CU_PRESET_HIGH, "quality.segments=8", "high, 8 segments", 0},
    {CU_PRESET_HIGH, "quality.segments=3", "high, 3 segments", 0},
    {CU_PRESET_HIGH, "quality.segments=2", "high, 2 segments", 0},
    {CU_PRESET_MEDIUM, "", "medium", 0},
    {CU_PRESET_MEDIUM, "quality.segments=3", "medium, 3 segments", 0},
    {CU_PRESET_MEDIUM, "quality.segments=2", "medium, 2 segments", 0},
    {CU_PRESET_LOW, "", "low", 0},
    /* medium and low made cheaper still: fewer segments and a coarser hull, the clouds at 1/3 and 1/4 resolution */
    {CU_PRESET_MEDIUM, "quality.segments=2;quality.hull_tessellation=6", "medium, 2 segments, hull 6", 0},
    {CU_PRESET_LOW, "quality.segments=2;quality.hull_tessellation=6", "low, 2 segments, hull 6", 0},
    {CU_PRESET_LOW, "quality.cloud_downsample=3", "low, 1/3 resolution", 0},
    {CU_PRESET_LOW, "quality.cloud_downsample=3;quality.segments=2;quality.hull_tessellation=6",
     "low, 1/3 resolution, 2 segments, hull 6", 0},
    {CU_PRESET_LOW, "quality.cloud_downsample=4;quality.segments=2;quality.hull_tessellation=6",
     "low, 1/4 resolution, 2 segments, hull 6", 0},
    /* the cheapest end: at 1/4 resolution a frame is mostly what every method pays (the sky, the composite) */
    {CU_PRESET_LOW, "quality.cloud_downsample=4;quality.segments=1;quality.hull_tessellation=4",
     "low, 1/4 resolution, 1 segment, hull 4", 0},
    {CU_PRESET_LOW, "ms.mode=octaves;quality.cloud_downsample=4;quality.segments=2;quality.hull_tessellation=6",
     "low, octaves, 1/4 resolution, 2 segments, hull 6", 0},
    {CU_PRESET_LOW, "ms.mode=octaves;quality.cloud_downsample=4;quality.segments=1;quality.hull_tessellation=4",
     "low, octaves, 1/4 resolution, 1 segment, hull 4", 0},
    /* the cheap end with the noisy skin in coarser steps: with one or two segments the chords that never reach the core
     * (quality.boundary_step, up to 32 steps each) take most of a pixel's samples; 30 m steps, or Kol's segments */
    {CU_PRESET_LOW, "quality.segments=2;quality.hull_tessellation=6;quality.boundary_step=30",
     "low, 2 segments, hull 6, boundary step 30 m", 0},
    {CU_PRESET_LOW, "quality.segments=1;quality.hull_tessellation=4", "low, 1 segment, hull 4", 0},
    {CU_PRESET_LOW, "quality.segments=1;quality.hull_tessellation=4;quality.boundary_step=30",
     "low, 1 segment, hull 4, boundary step 30 m", 0},
    {CU_PRESET_LOW, "quality.cloud_downsample=4;quality.segments=1;quality.hull_tessellation=4;quality.boundary_step=30",
     "low, 1/4 resolution, 1 segment, hull 4, boundary step 30 m", 0},
    {CU_PRESET_LOW, "quality.cloud_downsample=4;quality.segments=1;quality.hull_tessellation=4;quality.boundary_step=0",
     "low, 1/4 resolution, 1 segment, hull 4, no boundary knots", 0},
    {CU_PRESET_LOW, "ms.mode=octaves;ms.blur=200;quality.segments=2;quality.hull_tessellation=6;quality.boundary_step=30",
     "low, octaves, 2 segments, hull 6, boundary step 30 m", 0},
    {CU_PRESET_LOW, "ms.mode=octaves;ms.blur=200;quality.segments=1;quality.hull_tessellation=4",
     "low, octaves, 1 segment, hull 4", 0},
    {CU_PRESET_LOW, "ms.mode=octaves;ms.blur=200;quality.segments=1;quality.hull_tessellation=4;quality.boundary_step=30",
     "low, octaves, 1 segment, hull 4, boundary step 30 m", 0},
    {CU_PRESET_LOW, "quality.segments=1;quality.hull_tessellation=4;quality.boundary_step=30;quality.edge_refine=0.6",
     "low, 1 segment, hull 4, boundary step 30 m, edges refined 0.6", 0},
    {CU_PRESET_LOW, "ms.mode=octaves;ms.blur=200;quality.segments=1;quality.hull_tessellation=4;quality.boundary_step=30;"
     "quality.edge_refine=0.6", "low, octaves, 1 segment, hull 4, boundary step 30 m, edges refined 0.6", 0},
    /* half resolution with the pixels whose four texels differ marched again at full resolution (quality.edge_refine):
     * the thin bright rim that half resolution smears */
    {CU_PRESET_LOW, "quality.edge_refine=0.3", "low, edges refined 0.3", 0},
    {CU_PRESET_LOW, "quality.segments=2;quality.hull_tessellation=6;quality.edge_refine=0.3",
     "low, 2 segments, hull 6, edges refined 0.3", 0},
    {CU_PRESET_LOW, "quality.segments=2;quality.hull_tessellation=6;quality.edge_refine=0.6",
     "low, 2 segments, hull 6, edges refined 0.6", 0},
    /* the opacity map read bilinear (high's) instead of at its nearest texel */
    {CU_PRESET_MEDIUM, "light.sun_filter=bilinear", "medium, bilinear sun map", 0},
    /* the fitted octaves in place of the presets' diffusion: the presets before the sweep timed a turning sun
     * (2026-12-06); "low, octaves, 2 segments, hull 6" is that low */
    {CU_PRESET_MEDIUM, "ms.mode=octaves;ms.blur=200", "medium, octaves", 0},
    {CU_PRESET_MEDIUM, "ms.mode=octaves;ms.blur=200;quality.segments=2", "medium, octaves, 2 segments", 0},
    {CU_PRESET_LOW, "ms.mode=octaves;ms.blur=200", "low, octaves", 0},
    {CU_PRESET_LOW, "ms.mode=octaves;ms.blur=200;quality.segments=2;quality.hull_tessellation=6",
     "low, octaves, 2 segments, hull 6", 0},
    /* multiple scattering from each cloud's diffusion solution in place of high's slab model */
    {CU_PRESET_HIGH, "ms.mode=diffusion", "high, diffusion", 0},
    /* the slab model at its cheapest: few segments, small maps, a coarse hull */
    {CU_PRESET_HIGH, "quality.segments=2;quality.sun_map_size=64;quality.hull_tessellation=6", "high, 2 segments, "
     "64^2 maps, hull 6", 0},
    {CU_PRESET_HIGH, "quality.segments=2;quality.sun_map_size=64;quality.hull_tessellation=6;light.sun_samples=16;"
     "light.sun_intervals=2", "high, 2 segments, 64^2 maps, hull 6, 16 sun samples, 2 sun intervals", 0},
    {CU_PRESET_HIGH, "quality.noise_baked=off", "high, exact noise", 1},
    {CU_PRESET_HIGH, "quality.boundary_step=0", "high, no boundary knots", 1},
    {CU_PRESET_HIGH, "quality.noise_baked=off;quality.boundary_step=0",
     "high as before (exact noise, no boundary knots)", 1},
    {CU_PRESET_MEDIUM, "quality.noise_baked=off;quality.boundary_step=0", "medium as before", 1},
    /* diffusion without the forward lobe's own light (ms.lobe = off): what it changes */
    {CU_PRESET_MEDIUM, "ms.lobe=off", "medium without the lobe's light", 1},
    /* the entry ramp marched in 8 m steps (quality.ramp_step): single scattering where the path tracer puts it */
    {CU_PRESET_HIGH, "quality.ramp_step=8", "high, entry ramp 8 m", 0},
    {CU_PRESET_MEDIUM, "quality.ramp_step=8", "medium, entry ramp 8 m", 0},
    {CU_PRESET_MEDIUM, "quality.segments=2;quality.ramp_step=8", "medium, 2 segments, entry ramp 8 m", 0},
    {CU_PRESET_LOW, "quality.ramp_step=8", "low, entry ramp 8 m", 0},
    {CU_PRESET_MEDIUM, "ms.mode=octaves;ms.blur=200;quality.ramp_step=8", "medium, octaves, entry ramp 8 m", 0},
};
#define N_KOL ((int)(sizeof KOL / sizeof KOL[0]))
/* The uniform march: steps along the view x steps toward the sun, with the baked noise (the default; what a
 * real-time march reads) and, for the outside comparison's two settings, the exact noise; its cheapest settings also
 * at half resolution (quality.cloud_downsample = 2, as `low` draws Kol's: Nubis and Frostbite march at reduced
 * resolution too), and the cheapest at a quarter. */
static const struct {
    int n, m, baked, down;
} UNI[] = {
    {8, 2, 1, 1},  {8, 4, 1, 1},  {16, 2, 1, 1},  {16, 4, 1, 1}, {16, 8, 1, 1}, {32, 2, 1, 1},
    {32, 4, 1, 1}, {32, 8, 1, 1}, {64, 4, 1, 1},  {64, 6, 1, 1}, {64, 8, 1, 1}, {128, 4, 1, 1},
    {128, 8, 1, 1}, {16, 4, 0, 1}, {64, 6, 0, 1}, {8, 2, 1, 2},  {8, 4, 1, 2},  {16, 4, 1, 2},
    {8, 2, 1, 4}, /* the cheapest end, beside Kol's at 1/4 resolution */
};
#define N_UNI ((int)(sizeof UNI / sizeof UNI[0]))
#define N_CFG (N_KOL + N_UNI)

typedef struct mpoint {
    int family, control;
    char label[80];
    config c;
} mpoint;

static void make_points(mpoint *pt)
{
    int n = 0;
    for (int i = 0; i < N_KOL; i++, n++) {
        pt[n].family = FAM_KOL;
        pt[n].control = KOL[i].control;
        snprintf(pt[n].label, sizeof pt[n].label, "%s", KOL[i].label);
        config_high(&pt[n].c);
        snprintf(pt[n].c.extra, SW_EXTRA_LEN, "%s%s%s", cu_preset_settings((cu_preset)KOL[i].preset),
                 *KOL[i].more ? ";" : "", KOL[i].more);
    }
    for (int i = 0; i < N_UNI; i++, n++) {
        pt[n].family = FAM_UNIFORM;
        pt[n].control = !UNI[i].baked; /* the exact noise: the outside comparison's, beside the curve */
        snprintf(pt[n].label, sizeof pt[n].label, "uniform %d / %d%s%s", UNI[i].n, UNI[i].m,
                 UNI[i].baked ? "" : ", exact noise",
                 UNI[i].down == 2 ? ", 1/2 resolution" : UNI[i].down == 4 ? ", 1/4 resolution" : "");
        config_high(&pt[n].c);
        snprintf(pt[n].c.extra, SW_EXTRA_LEN,
                 "ms.mode=octaves;quality.method=uniform;quality.uniform_steps=%d;quality.uniform_sun_steps=%d;"
                 "quality.noise_baked=%s;quality.cloud_downsample=%d",
                 UNI[i].n, UNI[i].m, UNI[i].baked ? "on" : "off", UNI[i].down);
    }
}

int sw_view_cloud_mask(sweep *sw, view *v)
{
    config sky;
    config_high(&sky);
    snprintf(sky.extra, SW_EXTRA_LEN, "cloud.density=0");
    float *img = malloc(sizeof(float) * 3 * (size_t)sw->ew * sw->eh);
    result r;
    memset(&r, 0, sizeof r);
    int rc = !img || sw_error_view(sw, v, &sky, 1, &r, img) || sw_view_mask(sw, v, img);
    free(img);
    if (rc == 0)
        printf("sweep: %s: %d cloud pixels of %d; the reference's contrast p90/p10 %.3f\n", v->name, v->mask_n,
               sw->ew * sw->eh, v->ref_contrast);
    return rc;
}

/* The fastest point of family fam (controls aside) at least as accurate as error e (cloud relative RMSE): the
 * family's speed/accuracy curve at e. -1 if none is. */
static int fastest_within(const mpoint *pt, const result *r, int fam, double e)
{
    int best = -1;
    for (int i = 0; i < N_CFG; i++)
        if (pt[i].family == fam && !pt[i].control && r[i].cloud_rel_rmse <= e &&
            (best < 0 || r[i].time_ms < r[best].time_ms))
            best = i;
    return best;
}

static void write_csv(FILE *f, const sweep *sw, const mpoint *pt, result *const *res)
{
    fprintf(f, "# cumulo-sweep --methods: error at %dx%d vs cumulo-pt %d spp on the cloud's pixels; time at %dx%d, "
               "median of %d frames after %d warm-up, interleaved\n",
            sw->ew, sw->eh, sw->spp, sw->tw, sw->th, sw->frames, sw->warmup);
    fprintf(f, "view,family,label,changes,time_ms,time_ratio,cloud_rel_rmse,contrast,ref_contrast,ssim,rel_rmse,"
               "psnr_db,fifth1,fifth2,fifth3,fifth4,fifth5\n");
    for (int s = 0; s < sw->nviews; s++)
        for (int i = 0; i < N_CFG; i++) {
            const result *r = &res[s][i];
            fprintf(f, "%s,%s,\"%s\",\"%s\",%.3f,%.4f,%.5f,%.4f,%.4f,%.4f,%.5f,%.3f,%.4f,%.4f,%.4f,%.4f,%.4f\n",
                    sw->v[s].name, FAMILY[pt[i].family], pt[i].label, pt[i].c.extra, r->time_ms, r->time_ratio,
                    r->cloud_rel_rmse, r->contrast, sw->v[s].ref_contrast, r->ssim, r->rel_rmse, r->psnr,
                    r->fifths[0], r->fifths[1], r->fifths[2], r->fifths[3], r->fifths[4]);
        }
}

static void write_dat(FILE *f, const sweep *sw, const mpoint *pt, result *const *res)
{
    fprintf(f, "# view_index family(0 kol, 1 uniform; 2, 3 their controls) time_ratio cloud_rel_rmse contrast_ratio "
               "ssim \"label\" \"view\"\n");
    for (int s = 0; s < sw->nviews; s++)
        for (int i = 0; i < N_CFG; i++) {
            const result *r = &res[s][i];
            fprintf(f, "%d %d %.5f %.5f %.4f %.4f \"%s\" \"%s\"\n", s, pt[i].family + 2 * pt[i].control,
                    r->time_ratio, r->cloud_rel_rmse,
                    sw->v[s].ref_contrast > 0 ? r->contrast / sw->v[s].ref_contrast : 0, r->ssim, pt[i].label,
                    sw->v[s].name);
        }
}

/* One view's "time at equal error" (rows into f, unless NULL): at the error of every point on either curve (controls
 * aside), each family's fastest point at least that accurate, and the ratio of their times where both reach it.
 * Returns how many error levels both reach; *worst gets the largest Kol / uniform ratio among them. */
static int equal_error_rows(FILE *f, const mpoint *pt, const result *r, double *worst)
{
    int order[N_CFG], n = 0, both = 0;
    for (int i = 0; i < N_CFG; i++)
        if (!pt[i].control)
            order[n++] = i;
    for (int a = 1; a < n; a++) /* by error, the most accurate first */
        for (int b = a; b > 0 && r[order[b - 1]].cloud_rel_rmse > r[order[b]].cloud_rel_rmse; b--) {
            int t = order[b];
            order[b] = order[b - 1];
            order[b - 1] = t;
        }
    *worst = 0;
    for (int a = 0; a < n; a++) {
        double e = r[order[a]].cloud_rel_rmse;
        int k = fastest_within(pt, r, FAM_KOL, e), u = fastest_within(pt, r, FAM_UNIFORM, e);
        if (!f && (k < 0 || u < 0))
            continue;
        char kt[120], ut[120];
        snprintf(kt, sizeof kt, k < 0 ? "none as accurate" : "%s (%.3f)", k < 0 ? "" : pt[k].label,
                 k < 0 ? 0.0 : r[k].cloud_rel_rmse);
        snprintf(ut, sizeof ut, u < 0 ? "none as accurate" : "%s (%.3f)", u < 0 ? "" : pt[u].label,
                 u < 0 ? 0.0 : r[u].cloud_rel_rmse);
        if (k >= 0 && u >= 0) {
            double q = r[k].time_ms / r[u].time_ms;
            *worst = both++ ? fmax(*worst, q) : q;
            if (f)
                fprintf(f, "| %.3f | %s | %.3f | %s | %.3f | **%.2f** |\n", e, kt, r[k].time_ratio, ut,
                        r[u].time_ratio, q);
        } else if (f) {
            fprintf(f, "| %.3f | %s | %s | %s | %s | only %s |\n", e, kt, k < 0 ? "" : "", ut, "",
                    k < 0 ? "the uniform march" : "Kol's method");
        }
    }
    return both;
}

static void write_md(FILE *f, const sweep *sw, const mpoint *pt, result *const *res)
{
    const char *lp = getenv("LP_NUM_THREADS");
    fprintf(f, "# Kol's method against the uniform ray march\n\n"
               "Written by `cumulo-sweep --methods` (`make sweep-methods`). Each view: every configuration of both "
               "families timed at %dx%d in one interleaved run (median of %d frames after %d warm-up; `high` timed "
               "three times, times as ratios to it), LP_NUM_THREADS=%s; rendered linear at %dx%d and compared with the "
               "path tracer at %d spp on the pixels the cloud changes (the reference against the sky alone): relative "
               "RMSE of the luminance after a 3x3 box filter of both images (the uniform march's jitter and the path "
               "tracer's noise averaged), contrast p90/p10 of that luminance (the reference's in the heading), SSIM of "
               "the tone-mapped luminance, and where the light goes: the cloud's pixels in fifths by the reference's "
               "filtered luminance, darkest first, and in each the image's light over the reference's (1 is right; "
               "above 1 in the dark fifths and below in the bright ones is a flattened picture, whatever the mean "
               "error). Kol's family: the presets and segment counts about them; the uniform march: "
               "N steps along the view x M toward the sun, octaves for multiple scattering.\n\n",
            sw->tw, sw->th, sw->frames, sw->warmup, lp ? lp : "(unset)", sw->ew, sw->eh, sw->spp);
    fprintf(f, "## Summary: Kol's time / the uniform march's time at equal error\n\n"
               "Each family's curve at an error level: its fastest point at least that accurate (cloud relative "
               "RMSE), controls aside (what this work's defaults replaced, and the uniform march with the exact "
               "noise). At the error of every point of either curve that both curves reach, Kol's time over the "
               "uniform march's; the largest of them and where. Below 1: Kol's curve lies left of the uniform "
               "march's over the whole range both reach.\n\n"
               "| view | error levels both reach | largest Kol / uniform | Kol's best error | uniform's best error |\n"
               "| --- | ---: | ---: | ---: | ---: |\n");
    for (int s = 0; s < sw->nviews; s++) {
        double worst = 0;
        int levels = equal_error_rows(NULL, pt, res[s], &worst);
        double best[2] = {1e30, 1e30};
        for (int i = 0; i < N_CFG; i++)
            if (!pt[i].control && res[s][i].cloud_rel_rmse < best[pt[i].family])
                best[pt[i].family] = res[s][i].cloud_rel_rmse;
        if (levels)
            fprintf(f, "| %s | %d | %.2f | %.3f | %.3f |\n", sw->v[s].name, levels, worst, best[0], best[1]);
        else
            fprintf(f, "| %s | 0 | (no error level both reach) | %.3f | %.3f |\n", sw->v[s].name, best[0], best[1]);
    }
    for (int s = 0; s < sw->nviews; s++) {
        const view *v = &sw->v[s];
        fprintf(f, "\n## %s (the path tracer's contrast %.2f; %d cloud pixels)\n\n", v->name, v->ref_contrast,
                v->mask_n);
        fprintf(f, "| family | configuration | time (ms) | time / high | rel. RMSE (cloud) | contrast | SSIM | "
                   "rel. RMSE (image) | light by brightness fifth, darkest first |\n"
                   "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | --- |\n");
        for (int i = 0; i < N_CFG; i++) {
            const result *r = &res[s][i];
            fprintf(f, "| %s | %s | %.1f | %.3f | %.4f | %.2f | %.3f | %.4f | %.2f %.2f %.2f %.2f %.2f |\n",
                    FAMILY[pt[i].family], pt[i].label, r->time_ms, r->time_ratio, r->cloud_rel_rmse, r->contrast,
                    r->ssim, r->rel_rmse, r->fifths[0], r->fifths[1], r->fifths[2], r->fifths[3], r->fifths[4]);
        }
        double w;
        fprintf(f, "\nAt equal error (times / high; the last column Kol's time over the uniform march's):\n\n"
                   "| error level | Kol's fastest as accurate (its error) | its time | the uniform march's (its error) | "
                   "its time | Kol / uniform |\n| ---: | --- | ---: | --- | ---: | ---: |\n");
        equal_error_rows(f, pt, res[s], &w);
    }
}

static int write_file(const sweep *sw, const char *name, void (*fn)(FILE *, const sweep *, const mpoint *,
                                                                      result *const *),
                      const mpoint *pt, result *const *res)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/%s", sw->out, name);
    FILE *f = fopen(path, "w");
    if (!f)
        return fprintf(stderr, "cumulo-sweep: cannot write %s\n", path), 1;
    fn(f, sw, pt, res);
    if (ferror(f) | fclose(f))
        return fprintf(stderr, "cumulo-sweep: error writing %s\n", path), 1;
    return 0;
}

int sw_methods_run(sweep *sw)
{
    static mpoint pt[N_CFG];
    static config cfg[N_CFG];
    make_points(pt);
    for (int i = 0; i < N_CFG; i++)
        cfg[i] = pt[i].c;
    result *res[SW_MAX_SCENES] = {0};
    int rc = 0;
    double t0 = sw_now_ms();
    for (int s = 0; s < sw->nviews && rc == 0; s++) {
        if (!(res[s] = calloc(N_CFG, sizeof(result)))) {
            fprintf(stderr, "cumulo-sweep: out of memory\n");
            rc = 1;
        } else {
            rc = sw_view_cloud_mask(sw, &sw->v[s]) || sw_measure_view(sw, &sw->v[s], cfg, N_CFG, res[s]);
        }
    }
    if (rc == 0)
        rc = write_file(sw, "methods.csv", write_csv, pt, res) || write_file(sw, "methods.dat", write_dat, pt, res) ||
             write_file(sw, "methods.md", write_md, pt, res);
    if (rc == 0)
        printf("sweep: wrote %s/methods.csv, methods.md, methods.dat in %.1f min\n", sw->out,
               (sw_now_ms() - t0) / 60e3);
    for (int s = 0; s < sw->nviews; s++) {
        free(res[s]);
        free(sw->v[s].mask);
        sw->v[s].mask = NULL;
    }
    return rc;
}
