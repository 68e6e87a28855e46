/* tools/sweep/metrics.c: the error of one rendered image against its view's reference, and the means over views.
 * Both images are clipped per channel where the display curve saturates (v->clip: the sun disk), so the sun's
 * brightness, which no display shows, does not swamp the error of the cloud. "visible" tone-maps both with
 * src/core/tonemap.c (the CPU twin of shaders_gles/tonemap.frag), unclipped, as the screen would show them. */
#include "sweep.h"
#include "tonemap.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Whether any channel of pixel p differs by more than threshold 8-bit levels once tone-mapped. */
static int visible_difference(const view *v, const float *a, const float *b, int threshold)
{
    unsigned char ta[3], tb[3];
    cu_tonemap_rgb8(a, v->exposure, v->white, ta);
    cu_tonemap_rgb8(b, v->exposure, v->white, tb);
    for (int c = 0; c < 3; c++)
        if (abs((int)ta[c] - (int)tb[c]) > threshold)
            return 1;
    return 0;
}

void sw_compare(const sweep *sw, const view *v, const float *img, result *r)
{
    size_t npx = (size_t)sw->ew * sw->eh, n = npx * 3;
    const float *ref = v->ref.pxf;
    double se = 0, mx = 0, mean = 0;
    long vis = 0;
    double *sorted = malloc(sizeof(double) * n);
    for (size_t i = 0; i < n; i++) {
        double cl = v->clip[i % 3];
        double a = img[i] < cl ? img[i] : cl, b = ref[i] < cl ? ref[i] : cl;
        if (img[i] != img[i])
            a = img[i]; /* a NaN stays one */
        double d = a - b;
        se += d * d;
        if (fabs(d) > mx || d != d)
            mx = fabs(d);
        mean += b;
        if (sorted)
            sorted[i] = (float)b;
    }
    for (size_t p = 0; p < npx; p++)
        vis += visible_difference(v, img + 3 * p, ref + 3 * p, sw->threshold);
    double peak = 1;
    if (sorted) {
        qsort(sorted, n, sizeof *sorted, sw_cmp_double);
        peak = sorted[(size_t)(0.99 * (double)(n - 1))];
        free(sorted);
    }
    mean /= (double)n;
    r->rmse = sqrt(se / (double)n);
    r->peak = peak;
    r->psnr = r->rmse > 0 ? 20 * log10(peak / r->rmse) : 999;
    r->maxabs = mx;
    r->visible = 100.0 * (double)vis / (double)npx;
    r->mean_ref = mean;
    r->rel_rmse = r->rmse / (mean > 0 ? mean : 1);
    double b2 = se / (double)n - v->pt_var;
    r->rel_bias = sqrt(b2 > 0 ? b2 : 0) / (mean > 0 ? mean : 1);
}

void sw_upsample(const float *src, int w, int h, float *dst, int W, int H)
{
    for (int y = 0; y < H; y++) {
        double fy = (y + 0.5) * h / H - 0.5;
        if (fy < 0)
            fy = 0;
        if (fy > h - 1)
            fy = h - 1;
        int y0 = (int)fy, y1 = y0 + 1 < h ? y0 + 1 : y0;
        double ty = fy - y0;
        for (int x = 0; x < W; x++) {
            double fx = (x + 0.5) * w / W - 0.5;
            if (fx < 0)
                fx = 0;
            if (fx > w - 1)
                fx = w - 1;
            int x0 = (int)fx, x1 = x0 + 1 < w ? x0 + 1 : x0;
            double tx = fx - x0;
            for (int c = 0; c < 3; c++) {
                double a = src[((size_t)y0 * w + x0) * 3 + c] * (1 - tx) + src[((size_t)y0 * w + x1) * 3 + c] * tx;
                double b = src[((size_t)y1 * w + x0) * 3 + c] * (1 - tx) + src[((size_t)y1 * w + x1) * 3 + c] * tx;
                dst[((size_t)y * W + x) * 3 + c] = (float)(a * (1 - ty) + b * ty);
            }
        }
    }
}

void sw_aggregate(const sweep *sw, result *const *per_view, int idx, result *agg)
{
    memset(agg, 0, sizeof *agg);
    for (int s = 0; s < sw->nviews; s++) {
        const result *r = &per_view[s][idx];
        agg->time_ratio += r->time_ratio / sw->nviews;
        agg->time_ms += r->time_ms / sw->nviews;
        agg->tmin_ratio += r->tmin_ratio / sw->nviews;
        agg->tmin_ms += r->tmin_ms / sw->nviews;
        agg->rel_rmse += r->rel_rmse / sw->nviews;
        agg->rel_bias += r->rel_bias / sw->nviews;
        agg->psnr += r->psnr / sw->nviews;
        agg->visible += r->visible / sw->nviews;
        agg->rmse += r->rmse / sw->nviews;
        agg->mean_ref += r->mean_ref / sw->nviews;
        if (r->maxabs > agg->maxabs)
            agg->maxabs = r->maxabs;
    }
    agg->ok = 1;
}
