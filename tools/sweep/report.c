/* tools/sweep/report.c: the sweep's output files, whose formats docs/sweep.md, docs/sweep_presets.txt,
 * docs/sweep_results.csv, scripts/sweep_plot.sh and tests/app/test_cli.sh read: sweep.csv (every measured row),
 * presets.txt (the chosen presets as --set lines), pareto.dat (the plot's points) and sweep.md (the tables). */
#include "sweep.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *const sw_preset_names[3] = {"low", "medium", "high"};

FILE *sw_open_out(const sweep *sw, const char *name)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/%s", sw->out, name);
    FILE *f = fopen(path, "w");
    if (!f)
        fprintf(stderr, "cumulo-sweep: cannot write %s\n", path);
    return f;
}

int sw_close_out(const sweep *sw, FILE *f, const char *name)
{
    if (ferror(f) | fclose(f))
        return fprintf(stderr, "cumulo-sweep: error writing %s/%s\n", sw->out, name), 1;
    return 0;
}

void sw_csv_header(sweep *sw)
{
    fprintf(sw->csv, "# cumulo sweep: error at %dx%d vs cumulo-pt %d spp; time at %dx%d, median of %d frames after %d "
                     "warm-up; psnr peak = reference 99th-percentile channel value; visible = share of pixels with an "
                     "8-bit tone-mapped channel differing by more than %d; both images clipped where the tone curve "
                     "saturates (exposure*L/white = 16); ALL rows = means over views (max_abs: max); cloud_rel_rmse, "
                     "contrast, ssim on the pixels the cloud changes (contrast_err = |ln(contrast / the reference's)|; "
                     "error = what presets are chosen by)\n",
            sw->ew, sw->eh, sw->spp, sw->tw, sw->th, sw->frames, sw->warmup, sw->threshold);
    fprintf(sw->csv, "kind,scene,knob,value,changes,time_ms,time_ratio,time_min_ms,time_min_ratio,rmse,psnr_db,"
                     "psnr_peak,max_abs,visible_pct,mean_ref,rel_rmse,rel_rmse_denoised,pt_rel_noise,cloud_rel_rmse,"
                     "contrast,ssim,contrast_err,error\n");
}

void sw_csv_row(sweep *sw, const char *kind, const char *scene, const char *knob, const char *value, const config *c,
                const result *r, double pt_rel_noise)
{
    char d[512];
    config_diff(c, d, sizeof d, ";");
    fprintf(sw->csv,
            "%s,%s,%s,%s,\"%s\",%.3f,%.4f,%.3f,%.4f,%.6g,%.3f,%.6g,%.6g,%.3f,%.6g,%.5f,%.5f,%.5f,%.5f,%.4f,%.4f,%.4f,"
            "%.5f\n",
            kind, scene, knob, value, d, r->time_ms, r->time_ratio, r->tmin_ms, r->tmin_ratio, r->rmse, r->psnr,
            r->peak, r->maxabs, r->visible, r->mean_ref, r->rel_rmse, r->rel_bias, pt_rel_noise, r->cloud_rel_rmse,
            r->contrast, r->ssim, r->contrast_err, r->error);
}

int sw_write_presets(const sweep *sw, const point *const presets[3])
{
    FILE *f = sw_open_out(sw, "presets.txt");
    if (!f)
        return 1;
    fprintf(f, "# cumulo presets from `cumulo sweep` (budgets: medium <= %.2fx, low <= %.2fx of high's frame time;\n"
               "# the lowest-error measured point of a greedy descent within each budget, no flatter than high).\n"
               "# Time ratio and mean relative RMSE on the cloud's pixels over %d views against cumulo-pt.\n",
            sw->budget_med, sw->budget_low, sw->nviews);
    for (int p = 2; p >= 0; p--) {
        char line[2048], d[512];
        config_sets_line(&presets[p]->c, line, sizeof line);
        config_diff(&presets[p]->c, d, sizeof d, " ");
        fprintf(f, "# %s: time %.3fx, cloud relRMSE %.4f, SSIM %.3f (changes from high: %s)\n%s: %s\n",
                sw_preset_names[p], presets[p]->agg.time_ratio, presets[p]->agg.error, presets[p]->agg.ssim, d,
                sw_preset_names[p], line);
        printf("preset %-6s time %.3fx cloud relRMSE %.4f: %s\n", sw_preset_names[p], presets[p]->agg.time_ratio,
               presets[p]->agg.error, line);
    }
    return sw_close_out(sw, f, "presets.txt");
}

int sw_write_pareto(const sweep *sw, const result *agg, const int *vknob, const int *vval, int nv, const point *trail,
                    int ntrail, const point *const presets[3])
{
    FILE *f = sw_open_out(sw, "pareto.dat");
    if (!f)
        return 1;
    fprintf(f, "# time_ratio error kind label (error: relative RMSE on the cloud's pixels, mean over views; kind 0 = "
               "one knob, 1 = greedy combination, 2 = preset, 9 = mean relative noise of the references over the "
               "whole image, sqrt(mean sigma^2) / mean radiance)\n");
    for (int i = 1; i < nv; i++) {
        const knob *kb = &sw_knobs[vknob[i]];
        const char *dot = strchr(kb->name, '.');
        fprintf(f, "%.4f %.5f 0 \"%s=%s\"\n", agg[i].time_ratio, agg[i].error, dot ? dot + 1 : kb->name,
                kb->vals[vval[i]]);
    }
    for (int i = 0; i < ntrail; i++)
        fprintf(f, "%.4f %.5f 1 \"g%d\"\n", trail[i].agg.time_ratio, trail[i].agg.error, i + 1);
    for (int p = 0; p < 3; p++)
        fprintf(f, "%.4f %.5f 2 \"%s\"\n", presets[p]->agg.time_ratio, presets[p]->agg.error, sw_preset_names[p]);
    double noise = 0;
    for (int s = 0; s < sw->nviews; s++)
        noise += sw->v[s].pt_rel_noise / sw->nviews;
    fprintf(f, "0 %.5f 9 \"reference noise\"\n", noise);
    return sw_close_out(sw, f, "pareto.dat");
}

int sw_write_md(const sweep *sw, const result *agg, const int *vknob, const int *vval, int nv,
                const point *const presets[3], result *const *per_view)
{
    FILE *f = sw_open_out(sw, "sweep.md");
    if (!f)
        return 1;
    const char *lp = getenv("LP_NUM_THREADS");
    int default_high = strcmp(sw->baseline, SW_DEFAULT_BASELINE) == 0;
    fprintf(f, "<!-- written by `cumulo sweep` (make sweep); do not edit -->\n");
    fprintf(f, "Speed versus accuracy, %d views (%s", sw->nviews, sw->v[0].name);
    for (int s = 1; s < sw->nviews; s++)
        fprintf(f, ", %s", sw->v[s].name);
    char sun[160];
    if (sw->sun_step > 0)
        snprintf(sun, sizeof sun, "the sun turned %g degrees every frame: the sun's maps, the energy closure and "
                 "diffusion's solves in the frames", sw->sun_step);
    else
        snprintf(sun, sizeof sun, "%s", sw->sun_moving ? "sun moved every frame (the sun pass redone)"
                                                       : "static sun: the sun pass is not in the frame");
    fprintf(f, "). Time: %s frame time at %dx%d (%d frames after %d warm-up, wall clock incl. glFinish, %s, "
               "LP_NUM_THREADS=%s), as a ratio to `high` timed in the same session (high timed three times among the "
               "variants, frames interleaved round-robin), mean over views. Error: against cumulo-pt (%d spp) at "
               "%dx%d, both images clipped per channel where the display curve saturates (exposure·L/white = 16: the "
               "sun disk). On the cloud's pixels (those where the reference differs from the sky alone), what presets "
               "are chosen by: relative RMSE of the luminance after a 3x3 box filter of both images (RMSE / mean "
               "reference), how far the contrast p90/p10 is from the reference's (|ln| of their ratio; 0.1 is 10 %%), "
               "SSIM of the tone-mapped luminance; a point flatter than high (contrast 0.02 further off, or SSIM 0.01 "
               "lower) is never a preset. Over the whole image: relative RMSE = RMSE / mean reference radiance; PSNR "
               "peak = the reference's 99th-percentile channel value; visible = share of pixels whose tone-mapped "
               "8-bit sRGB differs by more than %d/255 in a channel. All means over views. Each knob is changed alone "
               "from `high` (= %s%s; quality.noise stays as each view sets it).\n\n",
            sw->sun_step > 0 ? "mean" : "median", sw->tw, sw->th, sw->frames, sw->warmup, sun,
            lp ? lp : "(unset)", sw->spp, sw->ew, sw->eh, sw->threshold, default_high ? "the README defaults" :
            "the settings of ", default_high ? "" : sw->baseline);
    fprintf(f, "| knob | value | time ratio | time ratio, fastest frames | cloud rel. RMSE | Δ cloud rel. RMSE "
               "| contrast off | SSIM | rel. RMSE (image) | rel. RMSE, PT noise removed | PSNR dB | visible %% "
               "| Δ cloud rel. RMSE per −0.1 time |\n");
    fprintf(f, "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    fprintf(f, "| **high** | | 1.000 | 1.000 | %.4f | | %.3f | %.3f | %.4f | %.4f | %.1f | %.1f | |\n", agg[0].error,
            agg[0].contrast_err, agg[0].ssim, agg[0].rel_rmse, agg[0].rel_bias, agg[0].psnr, agg[0].visible);
    for (int i = 1; i < nv; i++) {
        double dt = agg[i].time_ratio - 1, de = agg[i].error - agg[0].error;
        char buys[64];
        if (dt < -0.01)
            snprintf(buys, sizeof buys, "%+.4f", de / (-dt / 0.1));
        else
            snprintf(buys, sizeof buys, "%s", dt > 0.01 ? "costs time" : "no saving");
        fprintf(f, "| %s | %s | %.3f | %.3f | %.4f | %+.4f | %.3f%s | %.3f | %.4f | %.4f | %.1f | %.1f | %s |\n",
                sw_knobs[vknob[i]].name, sw_knobs[vknob[i]].vals[vval[i]], agg[i].time_ratio, agg[i].tmin_ratio,
                agg[i].error, de, agg[i].contrast_err, sw_flatter(&agg[i], &agg[0]) ? " (flatter)" : "", agg[i].ssim,
                agg[i].rel_rmse, agg[i].rel_bias, agg[i].psnr, agg[i].visible, buys);
    }
    fprintf(f, "\nPresets (budgets: medium ≤ %.2f×, low ≤ %.2f× of high's time; greedy descent from high taking the "
               "change with the least increase of the cloud's error per time saved, each combination re-measured):\n\n",
            sw->budget_med, sw->budget_low);
    fprintf(f, "| preset | time ratio | cloud rel. RMSE | contrast off | SSIM | rel. RMSE (image) | changes from high "
               "|\n| --- | ---: | ---: | ---: | ---: | ---: | --- |\n");
    for (int p = 2; p >= 0; p--) {
        char d[512];
        config_diff(&presets[p]->c, d, sizeof d, ", ");
        const result *a = &presets[p]->agg;
        fprintf(f, "| %s | %.3f | %.4f | %.3f | %.3f | %.4f | %s |\n", sw_preset_names[p], a->time_ratio, a->error,
                a->contrast_err, a->ssim, a->rel_rmse, d);
    }
    fprintf(f, "\nPer view at `high` (reference noise: sqrt(mean σ²) of cumulo-pt / mean radiance):\n\n");
    fprintf(f, "| view | high ms | cloud pixels | cloud rel. RMSE | contrast (PT) | SSIM | rel. RMSE (image) | rel. "
               "RMSE, PT noise removed | PSNR dB (peak) | max abs | visible %% | PT noise (rel.) | PT mean std. error "
               "|\n");
    fprintf(f, "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (int s = 0; s < sw->nviews; s++) {
        const result *r = &per_view[s][0];
        fprintf(f, "| %s | %.1f | %d | %.4f | %.2f (%.2f) | %.3f | %.4f | %.4f | %.1f (%.3g) | %.3g | %.1f | %.4f | "
                   "%.3g |\n",
                sw->v[s].name, r->time_ms, sw->v[s].mask_n, r->cloud_rel_rmse, r->contrast, sw->v[s].ref_contrast,
                r->ssim, r->rel_rmse, r->rel_bias, r->psnr, r->peak, r->maxabs, r->visible, sw->v[s].pt_rel_noise,
                sw->v[s].pt_mean_se);
    }
    return sw_close_out(sw, f, "sweep.md");
}
