/* tools/sweep/choose.c: choosing the medium and low presets from the measurements.
 *
 * The error a preset is chosen by is where the light is: the relative RMSE on the cloud's own pixels (result.error,
 * mean over views), not over the whole image, which the sky dominates and a flattened cloud can win. A point that is
 * flatter than high, or less like the truth in structure (sw_flatter: contrast p90/p10 further from the path
 * tracer's, SSIM lower), is never taken, however small its error.
 *
 * Greedy: from high, repeatedly apply the single-knob change with the smallest predicted error increase per unit of
 * time saved (prediction: the one-at-a-time deltas, relative to the value the knob has now), re-measure the
 * combination on every view, until the measured time ratio is within the budget. A change that, measured, does not
 * save at least 1 % of high's time is taken back and not tried again (the first run kept ms.sky_light = off, which
 * cost 0.12 in error and saved nothing once combined). Each preset is then the lowest-error measured point (one-knob
 * variant or greedy combination) within its budget; if none is, the fastest measured point (reported as over
 * budget), never a flatter one. Only knob_preset_eligible() values are taken: with the sun turned every frame
 * (--sun-step of at least half a degree), the maps' and diffusion's costs are in the timed frames and they may be. */
#include "sweep.h"
#include <stdio.h>
#include <string.h>


/* The next change to try from cur: the knob and value with the least predicted error increase per time saved, or
 * -1 in *bk when no change saves time. */
static void best_change(const config *cur, const result *single_agg, const int *vidx, const result *high,
                        const unsigned char *banned, int sun_timed, int *bk, int *bv)
{
    double best = 1e300;
    *bk = *bv = -1;
    for (int k = 0; k < SW_NKNOBS; k++)
        for (int j = 0; j < sw_knobs[k].nvals; j++) {
            if (j == cur->v[k] || vidx[k * SW_MAX_VALUES + j] < 0 || !knob_preset_eligible(k, j, sun_timed) ||
                banned[k * SW_MAX_VALUES + j])
                continue;
            int cj = cur->v[k];
            const result *a = &single_agg[vidx[k * SW_MAX_VALUES + j]];
            if (sw_flatter(a, high))
                continue;
            double ta = a->time_ratio, ea = a->error, tc = 1.0, ec = high->error;
            if (cj != sw_knobs[k].high) {
                const result *b = &single_agg[vidx[k * SW_MAX_VALUES + cj]];
                tc = b->time_ratio;
                ec = b->error;
            }
            double dt = ta - tc, de = ea - ec;
            if (dt > -0.01) /* saves under 1 % of high's time: noise */
                continue;
            double score = (de > 0 ? de : de * 1e-3) / -dt;
            if (score < best) {
                best = score;
                *bk = k;
                *bv = j;
            }
        }
}

int sw_flatter(const result *r, const result *high)
{
    return r->ssim < high->ssim - 0.01 || r->contrast_err > high->contrast_err + 0.02;
}

/* The lowest-error measured point within budget and no flatter than high (or the fastest one no flatter, *found =
 * 0; high itself is never flatter than high). */
static point pick(const result *single_agg, const int *vidx, const result *high, const point *trail, int ntrail,
                  double budget, int sun_timed, int *found, double *fastest)
{
    point best = {0}, fast = {0};
    *found = 0;
    *fastest = 1e300;
    for (int i = -1; i < ntrail + SW_NKNOBS * SW_MAX_VALUES; i++) {
        point cand;
        if (i < 0) {
            config_high(&cand.c);
            cand.agg = *high;
            cand.agg.time_ratio = 1.0;
        } else if (i < ntrail) {
            cand = trail[i];
        } else {
            int k = (i - ntrail) / SW_MAX_VALUES, j = (i - ntrail) % SW_MAX_VALUES;
            if (k >= SW_NKNOBS || j >= sw_knobs[k].nvals || vidx[k * SW_MAX_VALUES + j] <= 0 ||
                !knob_preset_eligible(k, j, sun_timed))
                continue;
            config_high(&cand.c);
            cand.c.v[k] = j;
            cand.agg = single_agg[vidx[k * SW_MAX_VALUES + j]];
        }
        if (cand.agg.time_ratio <= budget && !sw_flatter(&cand.agg, high) &&
            (!*found || cand.agg.error < best.agg.error)) {
            best = cand;
            *found = 1;
        }
        if (cand.agg.time_ratio < *fastest && !sw_flatter(&cand.agg, high)) {
            *fastest = cand.agg.time_ratio;
            fast = cand;
        }
    }
    return *found ? best : fast;
}

int sw_choose_presets(sweep *sw, const result *single_agg, const int *vidx, const result *high, point *med,
                      point *low, point *trail, int *ntrail)
{
    config cur;
    config_high(&cur);
    /* the timed frames hold what a turning sun costs: the maps a band a frame and a diffusion grid solved again every
     * half degree (within ms.frame_work a frame) */
    int sun_timed = sw->sun_step >= 0.5;
    double t_cur = 1.0, e_cur = high->error;
    unsigned char banned[SW_NKNOBS * SW_MAX_VALUES];
    memset(banned, 0, sizeof banned);
    *ntrail = 0;
    for (int step = 0; step < SW_MAX_GREEDY; step++) {
        if (t_cur <= sw->budget_low)
            break;
        int bk, bv;
        best_change(&cur, single_agg, vidx, high, banned, sun_timed, &bk, &bv);
        if (bk < 0) {
            printf("sweep: presets: no single-knob change left that saves time (at %.2fx)\n", t_cur);
            break;
        }
        int was = cur.v[bk];
        cur.v[bk] = bv;
        char label[600], d[512];
        config_diff(&cur, d, sizeof d, " ");
        snprintf(label, sizeof label, "greedy%d", step + 1);
        printf("sweep: presets: step %d: %s=%s -> %s\n", step + 1, sw_knobs[bk].name, sw_knobs[bk].vals[bv], d);
        result agg;
        if (sw_measure_config(sw, &cur, "greedy", label, &agg))
            return 1;
        trail[*ntrail].c = cur;
        trail[*ntrail].agg = agg;
        (*ntrail)++;
        printf("sweep: presets: step %d measured: time %.3fx, cloud relRMSE %.4f, SSIM %.3f, contrast off by %.3f\n",
               step + 1, agg.time_ratio, agg.error, agg.ssim, agg.contrast_err);
        if ((agg.time_ratio > t_cur - 0.01 && agg.error > e_cur) || sw_flatter(&agg, high)) {
            printf("sweep: presets: step %d saved no time and cost accuracy, or flattened the picture: taken back\n",
                   step + 1);
            cur.v[bk] = was;
            banned[bk * SW_MAX_VALUES + bv] = 1;
            continue;
        }
        t_cur = agg.time_ratio;
        e_cur = agg.error;
    }
    point *pp[2] = {med, low};
    double budget[2] = {sw->budget_med, sw->budget_low};
    for (int q = 0; q < 2; q++) {
        int found;
        double fastest;
        *pp[q] = pick(single_agg, vidx, high, trail, *ntrail, budget[q], sun_timed, &found, &fastest);
        if (!found)
            printf("sweep: presets: nothing measured within %.2fx; taking the fastest point (%.3fx)\n", budget[q],
                   fastest);
    }
    return 0;
}
