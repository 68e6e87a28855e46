/* tools/sweep/measure.c: measuring configurations on one view with the real-time renderer. Time: one renderer per
 * configuration in one context at the timing size, each warmed up, then frames taken round-robin (configuration
 * order rotated every round) so that load changes on a shared machine hit every configuration alike; median per
 * configuration. Error: one linear session at the error size, each image compared with the view's reference. */
#include "sweep.h"
#include "session.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static cu_scene *make_scene(const char *path, const config *c, double *scale)
{
    cu_scene *s;
    cu_error e;
    if (cu_scene_load(&s, path, &e)) {
        fprintf(stderr, "cumulo-sweep: %s\n", e.msg);
        return NULL;
    }
    char sets[SW_MAX_SETS][64];
    int n = config_sets(c, sets, scale);
    for (int i = 0; i < n; i++)
        if (cu_scene_set(s, sets[i], &e)) {
            fprintf(stderr, "cumulo-sweep: %s\n", e.msg);
            cu_scene_free(s);
            return NULL;
        }
    return s;
}

static void *sw_getproc(void *user, const char *name)
{
    cli_session *s = user;
    return s->be->get_proc_address(s->disp, name);
}

/* A renderer of its own for each configuration, in the session's context (no state carried between variants). */
static int make_renderer(cli_session *s, const cu_scene *sc, cu_renderer **out)
{
    cu_error e;
    cu_desc d = {0};
    d.get_proc_address = sw_getproc;
    d.get_proc_user = s;
    d.data_dir = sw_data_dir();
    *out = NULL;
    if (cu_renderer_create(out, &d, &e) || cu_renderer_set_scene(*out, sc, &e)) {
        fprintf(stderr, "cumulo-sweep: %s\n", e.msg);
        cu_renderer_destroy(*out);
        *out = NULL;
        return 1;
    }
    return 0;
}

/* One frame of renderer r into the session's target, w x h in its lower-left corner, presented (glFinish). */
static int render_with(cli_session *s, cu_renderer *r, int w, int h)
{
    cu_error e;
    cu_frame f = {.fbo = s->fbo, .width = w, .height = h, .linear = s->linear};
    if (cu_render(r, &f, &e)) {
        fprintf(stderr, "cumulo-sweep: %s\n", e.msg);
        return 1;
    }
    char err[256];
    if (s->be->present(s->disp, err, sizeof err)) {
        fprintf(stderr, "cumulo-sweep: %s\n", err);
        return 1;
    }
    return 0;
}

/* A configuration's frame time from its timed frames (sorted on return): the median of still frames; with the sun
 * turning (--sun-step) the mean, since a band of the maps, the energy closure and diffusion's solves come every few
 * frames and the median would leave them out. */
static double frame_time(const sweep *sw, double *t, int n)
{
    double m = sw_median(t, n), sum = 0;
    for (int i = 0; i < n; i++)
        sum += t[i];
    return sw->sun_step > 0 ? sum / n : m;
}

/* The timing half: res[i].time_ms, tmin_ms and the ratios to cfg[0]. */
static int time_view(sweep *sw, view *v, const config *cfg, int n, result *res)
{
    cli_opts o = {0};
    o.scene_path = v->path;
    o.width = sw->tw;
    o.height = sw->th;
    cli_session ts;
    if (cli_session_open(&ts, &o)) {
        cli_session_close(&ts);
        return 1;
    }
    int rc = 0;
    /* Time slots: every configuration once, high (cfg[0]) three times spread through the round (its frames pooled),
     * since every ratio divides by it. */
    int extra = n > 2 ? 2 : 0, nsl = n + extra;
    int *slot = calloc((size_t)nsl, sizeof(int));
    double *t = malloc(sizeof(double) * (size_t)nsl * (size_t)sw->frames);
    double *pool = malloc(sizeof(double) * (size_t)(extra + 1) * (size_t)sw->frames);
    cu_renderer **rr = calloc((size_t)nsl, sizeof *rr);
    int *tw = calloc((size_t)nsl, sizeof(int)), *th = calloc((size_t)nsl, sizeof(int));
    if (!t || !rr || !tw || !th || !slot || !pool)
        rc = 1;
    for (int k = 0, i = 0; k < nsl && slot; k++) /* high at 0, ~1/3 and ~2/3 */
        slot[k] = (extra && (k == nsl / 3 || k == 2 * nsl / 3)) ? 0 : i++;
    for (int k = 0; k < nsl && rc == 0; k++) {
        double scale;
        cu_scene *sc = make_scene(v->path, &cfg[slot[k]], &scale);
        if (!sc || make_renderer(&ts, sc, &rr[k]))
            rc = 1;
        cu_scene_free(sc);
        tw[k] = (int)lround(sw->tw * scale);
        th[k] = (int)lround(sw->th * scale);
        for (int f = 0; f < (sw->warmup > 0 ? sw->warmup : 1) && rc == 0; f++)
            rc = render_with(&ts, rr[k], tw[k], th[k]);
    }
    for (int f = 0; f < sw->frames && rc == 0; f++)
        for (int j = 0; j < nsl && rc == 0; j++) {
            int k = (j + f) % nsl;
            if (sw->sun_moving || sw->sun_step > 0) {
                double el, az;
                cu_error e;
                cu_renderer_get_sun(rr[k], &el, &az);
                cu_renderer_set_sun(rr[k], el, az + (sw->sun_step > 0 ? sw->sun_step : f % 2 ? 0.01 : -0.01), &e);
            }
            double a = sw_now_ms();
            rc = render_with(&ts, rr[k], tw[k], th[k]);
            t[(size_t)k * sw->frames + f] = sw_now_ms() - a;
        }
    for (int k = 0; k < nsl && rc == 0; k++) {
        int i = slot[k];
        if (i == 0)
            continue;
        res[i].time_ms = frame_time(sw, t + (size_t)k * sw->frames, sw->frames);
        res[i].tmin_ms = t[(size_t)k * sw->frames]; /* sorted by sw_median() */
    }
    if (rc == 0) {
        int np = 0;
        for (int k = 0; k < nsl; k++)
            if (slot[k] == 0)
                for (int f = 0; f < sw->frames; f++)
                    pool[np++] = t[(size_t)k * sw->frames + f];
        res[0].time_ms = frame_time(sw, pool, np);
        res[0].tmin_ms = pool[0];
    }
    for (int k = 0; k < nsl && rr; k++)
        cu_renderer_destroy(rr[k]);
    for (int i = 0; i < n && rc == 0; i++) {
        res[i].time_ratio = res[i].time_ms / res[0].time_ms;
        res[i].tmin_ratio = res[i].tmin_ms / res[0].tmin_ms;
    }
    free(slot);
    free(pool);
    free(t);
    free(rr);
    free(tw);
    free(th);
    cli_session_close(&ts);
    return rc;
}

/* The error half: every configuration rendered linear at the error size (scaled ones upsampled) and compared. */
int sw_error_view(sweep *sw, view *v, const config *cfg, int n, result *res, float *first)
{
    cli_opts o = {0};
    o.scene_path = v->path;
    o.width = sw->ew;
    o.height = sw->eh;
    o.linear = 1;
    cli_session es;
    memset(&es, 0, sizeof es);
    size_t npx = (size_t)sw->ew * sw->eh;
    float *img = malloc(sizeof(float) * 3 * npx), *up = malloc(sizeof(float) * 3 * npx);
    int rc = !img || !up;
    if (rc == 0 && cli_session_open(&es, &o))
        rc = 1;
    for (int i = 0; i < n && rc == 0; i++) {
        double scale;
        cu_renderer *r = NULL;
        cu_scene *sc = make_scene(v->path, &cfg[i], &scale);
        if (!sc || make_renderer(&es, sc, &r)) {
            cu_scene_free(sc);
            rc = 1;
            break;
        }
        cu_scene_free(sc);
        int w = (int)lround(sw->ew * scale), h = (int)lround(sw->eh * scale);
        if (w < 1)
            w = 1;
        if (h < 1)
            h = 1;
        int W = es.width, H = es.height;
        rc = render_with(&es, r, w, h);
        if (rc == 0) {
            es.width = w;
            es.height = h;
            rc = cli_session_read_rgbf(&es, img);
            es.width = W;
            es.height = H;
        }
        cu_renderer_destroy(r);
        if (rc)
            break;
        const float *full = img;
        if (w != sw->ew || h != sw->eh) {
            sw_upsample(img, w, h, up, sw->ew, sw->eh);
            full = up;
        }
        sw_compare(sw, v, full, &res[i]);
        sw_cloud_metrics(sw, v, full, &res[i]);
        if (i == 0 && first)
            memcpy(first, full, sizeof(float) * 3 * npx);
        res[i].ok = 1;
        char d[512];
        config_diff(&cfg[i], d, sizeof d, " ");
        printf("sweep: %-14s %-40s %8.1f ms %6.3fx  relRMSE %.4f  PSNR %5.1f dB  visible %5.1f%%", v->name, d,
               res[i].time_ms, res[i].time_ratio, res[i].rel_rmse, res[i].psnr, res[i].visible);
        if (v->mask)
            printf("  cloud relRMSE %.4f  contrast %.2f (PT %.2f)  SSIM %.3f", res[i].cloud_rel_rmse,
                   res[i].contrast, v->ref_contrast, res[i].ssim);
        printf("\n");
        fflush(stdout);
    }
    free(img);
    free(up);
    if (es.disp || es.r || es.scene)
        cli_session_close(&es);
    return rc;
}

int sw_measure_view(sweep *sw, view *v, const config *cfg, int n, result *res)
{
    return time_view(sw, v, cfg, n, res) || sw_error_view(sw, v, cfg, n, res, NULL);
}

int sw_measure_config(sweep *sw, const config *c, const char *kind, const char *label, result *agg)
{
    config pair[2];
    config_high(&pair[0]);
    pair[1] = *c;
    result *rows[SW_MAX_SCENES];
    result all[SW_MAX_SCENES][2];
    memset(all, 0, sizeof all);
    for (int s = 0; s < sw->nviews; s++) {
        if (sw_measure_view(sw, &sw->v[s], pair, 2, all[s]))
            return 1;
        rows[s] = all[s];
        sw_csv_row(sw, kind, sw->v[s].name, label, "", c, &all[s][1], sw->v[s].pt_rel_noise);
    }
    sw_aggregate(sw, rows, 1, agg);
    sw_csv_row(sw, kind, "ALL", label, "", c, agg, 0);
    fflush(sw->csv);
    return 0;
}
