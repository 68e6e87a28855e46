/* tools/sweep/score.c: cumulo-sweep --score DIR: images rendered elsewhere (another build's `cumulo render`, another
 * renderer) scored against each view's path-traced reference with the sweep's own metrics, so that two builds, or
 * cumulo and another program, are compared on one scale. DIR holds NAME.pfm for every view NAME, linear radiance at
 * the error size (--size), as `cumulo render SCENE --size WxH -o DIR/NAME.pfm` writes it. */
#include "sweep.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The image of view v from dir, checked: the error size, every value finite and not negative. 0, or 1 (printed). */
static int read_image(const sweep *sw, const char *dir, const view *v, cu_image *img)
{
    char path[1200];
    cu_error e;
    snprintf(path, sizeof path, "%s/%s.pfm", dir, v->name);
    if (cu_pfm_read(path, img, &e))
        return fprintf(stderr, "cumulo-sweep: --score: %s\n", e.msg), 1;
    if (img->width != sw->ew || img->height != sw->eh) {
        fprintf(stderr, "cumulo-sweep: --score: %s is %dx%d; the references are %dx%d (--size)\n", path, img->width,
                img->height, sw->ew, sw->eh);
        cu_image_free(img);
        return 1;
    }
    size_t n = (size_t)img->width * img->height * 3;
    for (size_t i = 0; i < n; i++)
        if (!isfinite(img->pxf[i]) || img->pxf[i] < 0) {
            size_t p = i / 3, w = (size_t)img->width;
            fprintf(stderr, "cumulo-sweep: --score: %s: pixel x %zu, y %zu (from the top), channel %zu is %g "
                    "(radiance is finite and not negative)\n", path, p % w, p / w, i % 3, (double)img->pxf[i]);
            cu_image_free(img);
            return 1;
        }
    return 0;
}

int sw_score_run(sweep *sw, const char *dir)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/score.md", sw->out);
    FILE *md = fopen(path, "w");
    if (!md)
        return fprintf(stderr, "cumulo-sweep: cannot write %s\n", path), 1;
    fprintf(md, "Images in %s against cumulo-pt at %d spp, %dx%d (cloud: the pixels the cloud changes, 3x3 box "
                "filtered; contrast p90/p10 of their luminance)\n\n", dir, sw->spp, sw->ew, sw->eh);
    fprintf(md, "| view | cloud rel. RMSE | contrast | reference's | SSIM | rel. RMSE (image) | PSNR dB |\n");
    fprintf(md, "| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    double sum = 0;
    int rc = 0;
    for (int s = 0; s < sw->nviews && rc == 0; s++) {
        view *v = &sw->v[s];
        cu_image img;
        result r;
        memset(&r, 0, sizeof r);
        rc = sw_view_cloud_mask(sw, v) || read_image(sw, dir, v, &img);
        if (rc)
            break;
        sw_compare(sw, v, img.pxf, &r);
        sw_cloud_metrics(sw, v, img.pxf, &r);
        cu_image_free(&img);
        sum += r.error;
        fprintf(md, "| %s | %.4f | %.3f | %.3f | %.4f | %.4f | %.2f |\n", v->name, r.cloud_rel_rmse, r.contrast,
                v->ref_contrast, r.ssim, r.rel_rmse, r.psnr);
        printf("score: %s: cloud rel. RMSE %.4f, contrast %.3f (reference %.3f), SSIM %.4f, image rel. RMSE %.4f\n",
               v->name, r.cloud_rel_rmse, r.contrast, v->ref_contrast, r.ssim, r.rel_rmse);
    }
    if (rc == 0) {
        fprintf(md, "\nMean error over the views (cloud rel. RMSE, the image's where a view has no cloud): %.4f\n",
                sum / sw->nviews);
        printf("score: mean error over %d views %.4f; wrote %s\n", sw->nviews, sum / sw->nviews, path);
    }
    if ((ferror(md) | fclose(md)) && rc == 0)
        return fprintf(stderr, "cumulo-sweep: error writing %s\n", path), 1;
    for (int s = 0; s < sw->nviews; s++) {
        free(sw->v[s].mask);
        sw->v[s].mask = NULL;
        cu_image_free(&sw->v[s].ref);
    }
    return rc;
}
