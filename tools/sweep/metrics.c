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
        int cloud = sw->v[s].mask && sw->v[s].mask_n > 0;
        agg->cloud_rel_rmse += r->cloud_rel_rmse / sw->nviews;
        agg->ssim += (cloud ? r->ssim : 1.0) / sw->nviews;
        agg->contrast_err += r->contrast_err / sw->nviews;
        agg->error += r->error / sw->nviews;
        if (r->maxabs > agg->maxabs)
            agg->maxabs = r->maxabs;
    }
    agg->ok = 1;
}

/* ---- where the light is: the cloud's pixels, contrast and structure (cumulo-sweep --methods) ---- */

static double luminance(const float *p)
{
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

/* The luminance of img after a 3x3 box filter (the edge rows and columns average what they have), each channel
 * clipped where the display curve saturates (the sun disk) as in sw_compare. */
static void box3_luminance(const sweep *sw, const view *v, const float *img, double *out)
{
    int w = sw->ew, h = sw->eh;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double s = 0;
            int n = 0;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    int xx = x + dx, yy = y + dy;
                    if (xx < 0 || yy < 0 || xx >= w || yy >= h)
                        continue;
                    const float *p = img + 3 * ((size_t)yy * w + xx);
                    float c[3];
                    for (int k = 0; k < 3; k++)
                        c[k] = p[k] < v->clip[k] ? p[k] : (float)v->clip[k];
                    s += luminance(c);
                    n++;
                }
            out[(size_t)y * w + x] = s / n;
        }
}

/* The luminance at 20, 40, 60 and 80 % of the mask's pixels, sorted: where result.fifths splits them. */
static void fifth_edges(view *v, const double *lum, size_t npx)
{
    memset(v->fifth_edge, 0, sizeof v->fifth_edge);
    double *t = malloc(sizeof(double) * (size_t)(v->mask_n > 0 ? v->mask_n : 1));
    if (!t)
        return;
    size_t n = 0;
    for (size_t i = 0; i < npx; i++)
        if (v->mask[i])
            t[n++] = lum[i];
    if (n >= SW_FIFTHS) {
        qsort(t, n, sizeof *t, sw_cmp_double);
        for (int k = 1; k < SW_FIFTHS; k++)
            v->fifth_edge[k - 1] = t[(size_t)((double)k / SW_FIFTHS * (double)(n - 1))];
    }
    free(t);
}

/* p90 / p10 of the filtered luminance over the mask. */
static double contrast_of(const view *v, const double *lum, size_t npx)
{
    double *t = malloc(sizeof(double) * (size_t)(v->mask_n > 0 ? v->mask_n : 1));
    if (!t)
        return 0;
    size_t n = 0;
    for (size_t i = 0; i < npx; i++)
        if (v->mask[i])
            t[n++] = lum[i];
    double c = 0;
    if (n >= 10) {
        qsort(t, n, sizeof *t, sw_cmp_double);
        double p10 = t[(size_t)(0.1 * (double)(n - 1))], p90 = t[(size_t)(0.9 * (double)(n - 1))];
        c = p10 > 0 ? p90 / p10 : 0;
    }
    free(t);
    return c;
}

int sw_view_mask(const sweep *sw, view *v, const float *sky)
{
    size_t npx = (size_t)sw->ew * sw->eh;
    free(v->mask);
    v->mask = calloc(npx, 1);
    double *lum = malloc(sizeof(double) * npx);
    if (!v->mask || !lum)
        return free(lum), fprintf(stderr, "cumulo-sweep: out of memory\n"), 1;
    /* a pixel is the cloud's where the reference differs from the sky alone by more than 2 % of the sky in some
     * channel (and more than the path tracer's noise could make it: 4 mean standard errors) */
    v->mask_n = 0;
    for (size_t p = 0; p < npx; p++) {
        int on = 0;
        for (int c = 0; c < 3; c++) {
            double r = v->ref.pxf[3 * p + c], s = sky[3 * p + c];
            if (fabs(r - s) > 0.02 * fabs(s) + 4 * v->pt_mean_se)
                on = 1;
        }
        v->mask[p] = (unsigned char)on;
        v->mask_n += on;
    }
    box3_luminance(sw, v, v->ref.pxf, lum);
    v->ref_contrast = contrast_of(v, lum, npx);
    fifth_edges(v, lum, npx);
    free(lum);
    return 0;
}

/* Mean SSIM (Wang et al. 2004: C1 = (0.01 L)^2, C2 = (0.03 L)^2, L = 255) of the two 8-bit luminances over the 7x7
 * windows centred on mask pixels, as the screen shows them (tone-mapped with the view's exposure and white). */
static double ssim_on_mask(const sweep *sw, const view *v, const float *img)
{
    int w = sw->ew, h = sw->eh;
    size_t npx = (size_t)w * h;
    double *a = malloc(sizeof(double) * npx), *b = malloc(sizeof(double) * npx);
    if (!a || !b) {
        free(a);
        free(b);
        return 0;
    }
    for (size_t p = 0; p < npx; p++) {
        unsigned char ta[3], tb[3];
        cu_tonemap_rgb8(img + 3 * p, v->exposure, v->white, ta);
        cu_tonemap_rgb8(v->ref.pxf + 3 * p, v->exposure, v->white, tb);
        a[p] = 0.299 * ta[0] + 0.587 * ta[1] + 0.114 * ta[2];
        b[p] = 0.299 * tb[0] + 0.587 * tb[1] + 0.114 * tb[2];
    }
    const double C1 = (0.01 * 255) * (0.01 * 255), C2 = (0.03 * 255) * (0.03 * 255);
    double sum = 0;
    long n = 0;
    for (int y = 3; y < h - 3; y++)
        for (int x = 3; x < w - 3; x++) {
            if (!v->mask[(size_t)y * w + x])
                continue;
            double ma = 0, mb = 0, saa = 0, sbb = 0, sab = 0;
            for (int dy = -3; dy <= 3; dy++)
                for (int dx = -3; dx <= 3; dx++) {
                    size_t q = (size_t)(y + dy) * w + (x + dx);
                    ma += a[q];
                    mb += b[q];
                    saa += a[q] * a[q];
                    sbb += b[q] * b[q];
                    sab += a[q] * b[q];
                }
            ma /= 49, mb /= 49;
            double va = saa / 49 - ma * ma, vb = sbb / 49 - mb * mb, cov = sab / 49 - ma * mb;
            sum += (2 * ma * mb + C1) * (2 * cov + C2) / ((ma * ma + mb * mb + C1) * (va + vb + C2));
            n++;
        }
    free(a);
    free(b);
    return n ? sum / (double)n : 0;
}

void sw_cloud_metrics(const sweep *sw, const view *v, const float *img, result *r)
{
    r->error = r->rel_rmse; /* a view without cloud pixels: the whole image's */
    if (!v->mask || v->mask_n == 0)
        return;
    size_t npx = (size_t)sw->ew * sw->eh;
    double *li = malloc(sizeof(double) * npx), *lr = malloc(sizeof(double) * npx);
    if (!li || !lr) {
        free(li);
        free(lr);
        return;
    }
    box3_luminance(sw, v, img, li);
    box3_luminance(sw, v, v->ref.pxf, lr);
    double se = 0, m = 0, fi[SW_FIFTHS] = {0}, fr[SW_FIFTHS] = {0};
    for (size_t p = 0; p < npx; p++)
        if (v->mask[p]) {
            double d = li[p] - lr[p];
            se += d * d;
            m += lr[p];
            int k = 0;
            while (k < SW_FIFTHS - 1 && lr[p] > v->fifth_edge[k])
                k++;
            fi[k] += li[p];
            fr[k] += lr[p];
        }
    for (int k = 0; k < SW_FIFTHS; k++)
        r->fifths[k] = fr[k] > 0 ? fi[k] / fr[k] : 0;
    r->cloud_rel_rmse = m > 0 ? sqrt(se / v->mask_n) / (m / v->mask_n) : 0;
    r->contrast = contrast_of(v, li, npx);
    r->contrast_err = r->contrast > 0 && v->ref_contrast > 0 ? fabs(log(r->contrast / v->ref_contrast)) : 0.0;
    r->error = r->cloud_rel_rmse;
    r->ssim = ssim_on_mask(sw, v, img);
    free(li);
    free(lr);
}
