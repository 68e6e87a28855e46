/* src/cli/cmd_sweep.c: `cumulo sweep`: the speed/accuracy sweep against the reference path tracer (issue 7).
 *
 * For every view (scene file) and every variant (one knob changed from the `high` preset, or a preset) it measures
 *   - time: median wall-clock frame time (incl. glFinish, as `cumulo bench`) at the timing size, static sun, as a
 *     ratio to `high` timed in the same session (high is timed first and last in each view's list, frames pooled);
 *   - error against build/cumulo-pt's reference of the same view with the high settings, at the error size: RMSE and
 *     PSNR on linear RGB (peak = the reference's 99th-percentile channel value), max abs error, relative RMSE
 *     (RMSE / mean reference radiance) and the share of pixels whose tone-mapped 8-bit sRGB values (the exact curve of
 *     shaders_gles/tonemap.frag with the scene's exposure and white balance) differ by more than a threshold.
 * Then it picks the presets greedily (see choose_presets) and writes DIR/sweep.csv, DIR/sweep.md, DIR/presets.txt and
 * DIR/pareto.dat (plotted by scripts/sweep_plot.sh into DIR/pareto.png). */
#include "image.h"
#include "scene.h"
#include "sky.h"
#include "commands.h"
#include "session.h"
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#define SW_MAX_SCENES 16
#define SW_MAX_VALUES 8
#define SW_MAX_SETS 24
#define MIE_G "0.853" /* asymmetry of data/mie_cloud.tbl: hg / cornette-shanks compared at the same g */

/* ---------------------------------------------------------------- knobs ---------------------------------------- */

typedef struct knob {
    const char *name;   /* scene key, or "output.scale" */
    int high;           /* index of the high value in vals */
    int nvals;
    const char *vals[SW_MAX_VALUES];
    int quick[SW_MAX_VALUES]; /* 1: measured in --quick */
} knob;

/* high = the README defaults (first... whichever index `high` names). quality.noise_octaves carries `off` as its
 * cheapest value (quality.noise = off). cloud.phase hg/cs use g = MIE_G. */
static const knob KNOBS[] = {
    {"quality.segments", 2, 6, {"2", "3", "5", "8", "12", "20"}, {1, 0, 1, 0, 1, 0}},
    {"quality.segment_ratio", 2, 4, {"1", "1.3", "1.6", "2.2"}, {0}},
    {"quality.hull_tessellation", 2, 4, {"4", "6", "10", "16"}, {0}},
    {"quality.max_intervals", 3, 4, {"1", "2", "3", "6"}, {0, 1, 0, 1}},
    {"quality.noise_octaves", 5, 6, {"off", "1", "2", "3", "4", "5"}, {0, 0, 1, 0, 0, 1}},
    {"quality.sun_map_size", 1, 4, {"64", "128", "256", "512"}, {0}},
    {"light.shadow", 0, 4, {"peel", "front", "osm", "fom"}, {0}},
    {"light.sun_intervals", 2, 3, {"1", "2", "3"}, {0}},
    {"light.sun_samples", 2, 4, {"8", "16", "32", "64"}, {0}},
    {"ms.mode", 2, 4, {"none", "octaves", "slab", "collector"}, {1, 0, 1, 0}},
    {"ms.blur", 1, 3, {"100", "200", "400"}, {0}},
    {"ms.sky_light", 1, 2, {"off", "on"}, {0}},
    {"ms.closure", 1, 2, {"off", "on"}, {0}},
    {"quality.integration", 0, 2, {"exponential", "kol"}, {0}},
    {"cloud.phase", 0, 3, {"mie", "hg", "cornette-shanks"}, {0}},
    {"output.scale", 2, 3, {"0.5", "0.75", "1"}, {1, 0, 1}},
};
#define NKNOBS ((int)(sizeof KNOBS / sizeof KNOBS[0]))

/* A configuration: one value index per knob. */
typedef struct config {
    int v[NKNOBS];
} config;

static void config_high(config *c)
{
    for (int k = 0; k < NKNOBS; k++)
        c->v[k] = KNOBS[k].high;
}

/* --set list and resolution scale of a configuration (all keys given explicitly, so a view's own quality lines do
 * not leak in; quality.noise stays the view's choice unless the knob says off). Returns the count. */
static int config_sets(const config *c, char sets[][64], double *scale)
{
    int n = 0;
    *scale = 1.0;
    for (int k = 0; k < NKNOBS; k++) {
        const knob *kb = &KNOBS[k];
        const char *val = kb->vals[c->v[k]];
        if (strcmp(kb->name, "output.scale") == 0) {
            *scale = atof(val);
        } else if (strcmp(kb->name, "quality.noise_octaves") == 0 && strcmp(val, "off") == 0) {
            snprintf(sets[n++], 64, "quality.noise=off");
        } else {
            snprintf(sets[n++], 64, "%s=%s", kb->name, val);
            if (strcmp(kb->name, "cloud.phase") == 0 && strcmp(val, "mie") != 0)
                snprintf(sets[n++], 64, "cloud.g=%s", MIE_G);
        }
    }
    return n;
}

/* "knob=value" changes from high, joined with sep ("" for high). */
static void config_diff(const config *c, char *out, size_t len, const char *sep)
{
    out[0] = 0;
    size_t n = 0;
    for (int k = 0; k < NKNOBS; k++)
        if (c->v[k] != KNOBS[k].high) {
            const char *name = KNOBS[k].name, *val = KNOBS[k].vals[c->v[k]];
            if (strcmp(name, "quality.noise_octaves") == 0 && strcmp(val, "off") == 0)
                name = "quality.noise"; /* the key it sets */
            n += (size_t)snprintf(out + n, n < len ? len - n : 0, "%s%s=%s", n ? sep : "", name, val);
        }
    if (n == 0)
        snprintf(out, len, "high");
}

/* ---------------------------------------------------------------- options / state ------------------------------ */

typedef struct result {
    double time_ms, time_ratio;
    double tmin_ms, tmin_ratio; /* fastest frame: on a loaded machine the least disturbed estimate */
    double rmse, psnr, peak, maxabs, visible, mean_ref, rel_rmse;
    double rel_bias;       /* sqrt(max(0, MSE - mean sigma^2 of the reference)) / mean reference: PT noise removed */
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
} view;

typedef struct sweep {
    int ew, eh, tw, th;    /* error and timing sizes */
    int spp, frames, warmup, quick, threshold;
    int sun_moving;        /* --sun-every-frame: time frames that redo the sun pass, as `cumulo bench` does */
    double budget_med, budget_low;
    const char *out, *refdir, *pt, *plot;
    int nviews;
    view v[SW_MAX_SCENES];
    FILE *csv;
} sweep;

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *t, int n)
{
    qsort(t, (size_t)n, sizeof *t, cmp_double);
    return n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
}

static int bad(const char *fmt, const char *a)
{
    fprintf(stderr, "cumulo sweep: ");
    fprintf(stderr, fmt, a);
    fprintf(stderr, "\n");
    return 2;
}

static int mkdirs(const char *path)
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

/* ---------------------------------------------------------------- reference ------------------------------------ */

static uint64_t fnv(uint64_t h, const void *data, size_t n)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < n; i++) {
        h ^= p[i];
        h *= 1099511628211ull;
    }
    return h;
}

static int read_file(const char *path, char **buf, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return -1;
    size_t cap = 4096, n = 0;
    char *b = malloc(cap);
    size_t r;
    while (b && (r = fread(b + n, 1, cap - n, f)) > 0) {
        n += r;
        if (n == cap) {
            char *nb = realloc(b, cap *= 2);
            if (!nb) {
                free(b);
                b = NULL;
            }
            b = nb;
        }
    }
    fclose(f);
    if (!b)
        return -1;
    *buf = b;
    *len = n;
    return 0;
}

/* Renders (or finds in the cache) the path-traced reference of view v with the high settings. */
static int load_reference(sweep *sw, view *v)
{
    char *text;
    size_t len;
    if (read_file(v->path, &text, &len))
        return fprintf(stderr, "cumulo sweep: cannot read %s\n", v->path), 1;
    struct stat st;
    char *bin;
    size_t blen;
    if (stat(sw->pt, &st) || read_file(sw->pt, &bin, &blen))
        return free(text),
               fprintf(stderr, "cumulo sweep: reference path tracer %s not found (make %s)\n", sw->pt, sw->pt), 1;
    /* The path tracer's image depends on the scene file, the density knobs (noise octaves; noise on/off stays the
     * view's) and the phase model; the other knobs are the real-time renderer's alone. The reference has the high
     * values of those. */
    config hc;
    config_high(&hc);
    char sets[2][64];
    int ns = 0;
    for (int k = 0; k < NKNOBS; k++)
        if (strcmp(KNOBS[k].name, "quality.noise_octaves") == 0 || strcmp(KNOBS[k].name, "cloud.phase") == 0)
            snprintf(sets[ns++], 64, "%s=%s", KNOBS[k].name, KNOBS[k].vals[hc.v[k]]);
    char key[512];
    snprintf(key, sizeof key, "|%dx%d|spp%d|seed1|", sw->ew, sw->eh, sw->spp);
    uint64_t h = fnv(1469598103934665603ull, text, len);
    h = fnv(h, key, strlen(key));
    h = fnv(h, bin, blen); /* the binary's contents: a relink of the same code keeps the cache */
    free(bin);
    for (int i = 0; i < ns; i++)
        h = fnv(h, sets[i], strlen(sets[i]));
    free(text);
    char out[1024], se[1100];
    snprintf(out, sizeof out, "%s/%s-%016llx.pfm", sw->refdir, v->name, (unsigned long long)h);
    snprintf(se, sizeof se, "%s.stderr.pfm", out);
    if (stat(out, &st) || stat(se, &st)) {
        char size[32], spp[32];
        snprintf(size, sizeof size, "%dx%d", sw->ew, sw->eh);
        snprintf(spp, sizeof spp, "%d", sw->spp);
        const char *argv[16 + 4];
        int a = 0;
        argv[a++] = sw->pt;
        argv[a++] = v->path;
        argv[a++] = "-o";
        argv[a++] = out;
        argv[a++] = "--size";
        argv[a++] = size;
        argv[a++] = "--spp";
        argv[a++] = spp;
        argv[a++] = "--threads";
        argv[a++] = "2";
        argv[a++] = "--quiet";
        for (int i = 0; i < ns; i++) {
            argv[a++] = "--set";
            argv[a++] = sets[i];
        }
        argv[a] = NULL;
        printf("sweep: reference %s: cumulo-pt %s spp (cached as %s)\n", v->name, spp, out);
        fflush(stdout);
        double t0 = now_ms();
        pid_t pid = fork();
        if (pid == 0) {
            execv(sw->pt, (char *const *)argv);
            fprintf(stderr, "cumulo sweep: cannot run %s: %s\n", sw->pt, strerror(errno));
            _exit(127);
        }
        int status = 0;
        if (pid < 0 || waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
            remove(out);
            remove(se);
            return fprintf(stderr, "cumulo sweep: the path tracer failed on %s\n", v->path), 1;
        }
        printf("sweep: reference %s took %.1f s\n", v->name, (now_ms() - t0) / 1e3);
    }
    char err[512];
    cu_image sig;
    if (cu_pfm_read(out, &v->ref, err, sizeof err) || cu_pfm_read(se, &sig, err, sizeof err))
        return fprintf(stderr, "cumulo sweep: %s\n", err), 1;
    if (v->ref.width != sw->ew || v->ref.height != sw->eh || sig.width != sw->ew || sig.height != sw->eh) {
        cu_image_free(&sig);
        return fprintf(stderr, "cumulo sweep: %s has the wrong size\n", out), 1;
    }
    size_t n = (size_t)sw->ew * sw->eh * 3;
    double s2 = 0, s1 = 0, m = 0;
    for (size_t i = 0; i < n; i++) {
        double cl = v->clip[i % 3];
        if (v->ref.pxf[i] < cl) { /* clipped pixels (the sun) carry no error and no noise in the metrics */
            s2 += (double)sig.pxf[i] * sig.pxf[i];
            s1 += sig.pxf[i];
        }
        m += v->ref.pxf[i] < cl ? v->ref.pxf[i] : cl;
    }
    cu_image_free(&sig);
    v->pt_var = s2 / n;
    v->pt_noise = sqrt(s2 / n);
    v->pt_mean_se = s1 / n;
    v->pt_rel_noise = v->pt_noise / (m / n > 0 ? m / n : 1);
    return 0;
}

/* ---------------------------------------------------------------- error ---------------------------------------- */

static double aces(double x)
{
    double t = x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14);
    return t < 0 ? 0 : t > 1 ? 1 : t;
}

static int to8(double c)
{
    /* tonemap.frag in float; the 8-bit target rounds */
    double s = c < 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1.0 / 2.4) - 0.055;
    int q = (int)floor(s * 255.0 + 0.5);
    return q < 0 ? 0 : q > 255 ? 255 : q;
}

static int tone8(const view *v, const float *px, int c)
{
    double x = px[c] * v->exposure / v->white[c];
    return to8(aces(x > 0 ? x : 0));
}

static void compare(const sweep *sw, const view *v, const float *img, result *r)
{
    size_t npx = (size_t)sw->ew * sw->eh, n = npx * 3;
    const float *ref = v->ref.pxf;
    double se = 0, mx = 0, mean = 0;
    long vis = 0;
    float *sorted = malloc(sizeof(float) * n);
    for (size_t i = 0; i < n; i++) {
        double cl = v->clip[i % 3];
        double a = img[i] < cl ? img[i] : cl, b = ref[i] < cl ? ref[i] : cl;
        if (img[i] != img[i])
            a = img[i];
        double d = a - b;
        se += d * d;
        if (fabs(d) > mx || d != d)
            mx = fabs(d);
        mean += b;
        if (sorted)
            sorted[i] = (float)b;
    }
    for (size_t p = 0; p < npx; p++)
        for (int c = 0; c < 3; c++)
            if (abs(tone8(v, img + 3 * p, c) - tone8(v, ref + 3 * p, c)) > sw->threshold) {
                vis++;
                break;
            }
    double peak = 1;
    if (sorted) {
        double *d = malloc(sizeof(double) * n);
        if (d) {
            for (size_t i = 0; i < n; i++)
                d[i] = sorted[i];
            qsort(d, n, sizeof *d, cmp_double);
            peak = d[(size_t)(0.99 * (double)(n - 1))];
            free(d);
        }
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

/* Bilinear upsampling of a w x h RGB image (top row first) to W x H (pixel centres aligned). */
static void upsample(const float *src, int w, int h, float *dst, int W, int H)
{
    for (int y = 0; y < H; y++) {
        double fy = (y + 0.5) * h / H - 0.5;
        if (fy < 0) fy = 0;
        if (fy > h - 1) fy = h - 1;
        int y0 = (int)fy, y1 = y0 + 1 < h ? y0 + 1 : y0;
        double ty = fy - y0;
        for (int x = 0; x < W; x++) {
            double fx = (x + 0.5) * w / W - 0.5;
            if (fx < 0) fx = 0;
            if (fx > w - 1) fx = w - 1;
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

/* ---------------------------------------------------------------- measuring ------------------------------------ */

static cu_scene *make_scene(const char *path, const config *c, double *scale)
{
    cu_scene *s;
    cu_error e;
    if (cu_scene_load(&s, path, &e)) {
        fprintf(stderr, "%s\n", e.msg);
        return NULL;
    }
    char sets[SW_MAX_SETS][64];
    int n = config_sets(c, sets, scale);
    for (int i = 0; i < n; i++)
        if (cu_scene_set(s, sets[i], &e)) {
            fprintf(stderr, "%s\n", e.msg);
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
    const char *dd = getenv("CUMULO_DATA_DIR");
    struct stat sb;
    if (!dd)
        dd = stat("data/mie_cloud.tbl", &sb) == 0 ? "data" : NULL;
    d.data_dir = dd;
    *out = NULL;
    if (cu_renderer_create(out, &d, &e) || cu_renderer_set_scene(*out, sc, &e)) {
        fprintf(stderr, "cumulo sweep: %s\n", e.msg);
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
    cu_frame f = {s->fbo, w, h, s->linear};
    if (cu_render(r, &f, &e)) {
        fprintf(stderr, "cumulo: %s\n", e.msg);
        return 1;
    }
    char err[256];
    if (s->be->present(s->disp, err, sizeof err)) {
        fprintf(stderr, "cumulo: %s\n", err);
        return 1;
    }
    return 0;
}

/* Measures configurations cfg[0..n-1] (cfg[0] = high, the time reference) on one view. Time: one renderer per
 * configuration in one context at the timing size, each warmed up, then frames taken round-robin (configuration
 * order rotated every round) so that load changes on a shared machine hit every configuration alike; median per
 * configuration. Error: one linear session at the error size. */
static int measure_view(sweep *sw, view *v, const config *cfg, int n, result *res)
{
    cli_opts o = {0};
    o.scene_path = v->path;
    o.width = sw->tw;
    o.height = sw->th;
    cli_session ts, es;
    memset(&es, 0, sizeof es);
    if (cli_session_open(&ts, &o)) {
        cli_session_close(&ts);
        return 1;
    }
    int rc = 0;
    size_t npx = (size_t)sw->ew * sw->eh;
    float *img = malloc(sizeof(float) * 3 * npx), *up = malloc(sizeof(float) * 3 * npx);
    /* Time slots: every configuration once, high (cfg[0]) three times spread through the round (its frames pooled),
     * since every ratio divides by it. */
    int extra = n > 2 ? 2 : 0, nsl = n + extra;
    int *slot = calloc((size_t)nsl, sizeof(int));
    double *t = malloc(sizeof(double) * (size_t)nsl * (size_t)sw->frames);
    double *pool = malloc(sizeof(double) * (size_t)(extra + 1) * (size_t)sw->frames);
    cu_renderer **rr = calloc((size_t)nsl, sizeof *rr);
    int *tw = calloc((size_t)nsl, sizeof(int)), *th = calloc((size_t)nsl, sizeof(int));
    if (!img || !up || !t || !rr || !tw || !th || !slot || !pool)
        rc = 1;
    for (int k = 0, i = 0; k < nsl && slot; k++) /* high at 0, ~1/3 and ~2/3 */
        slot[k] = (extra && (k == nsl / 3 || k == 2 * nsl / 3)) ? 0 : i++;
    for (int k = 0; k < nsl && rc == 0; k++) {
        double scale;
        int i = slot[k];
        cu_scene *sc = make_scene(v->path, &cfg[i], &scale);
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
            if (sw->sun_moving) {
                double el, az;
                cu_error e;
                cu_renderer_get_sun(rr[k], &el, &az);
                cu_renderer_set_sun(rr[k], el, az + (f % 2 ? 0.01 : -0.01), &e);
            }
            double a = now_ms();
            rc = render_with(&ts, rr[k], tw[k], th[k]);
            t[(size_t)k * sw->frames + f] = now_ms() - a;
        }
    for (int k = 0; k < nsl && rc == 0; k++) {
        int i = slot[k];
        if (i == 0)
            continue;
        res[i].time_ms = median(t + (size_t)k * sw->frames, sw->frames);
        res[i].tmin_ms = t[(size_t)k * sw->frames]; /* sorted by median() */
    }
    if (rc == 0) {
        int np = 0;
        for (int k = 0; k < nsl; k++)
            if (slot[k] == 0)
                for (int f = 0; f < sw->frames; f++)
                    pool[np++] = t[(size_t)k * sw->frames + f];
        res[0].time_ms = median(pool, np);
        res[0].tmin_ms = pool[0];
    }
    for (int k = 0; k < nsl && rr; k++)
        cu_renderer_destroy(rr[k]);
    free(slot);
    free(pool);
    for (int i = 0; i < n && rc == 0; i++) {
        res[i].time_ratio = res[i].time_ms / res[0].time_ms;
        res[i].tmin_ratio = res[i].tmin_ms / res[0].tmin_ms;
    }
    cli_session_close(&ts);
    o.width = sw->ew;
    o.height = sw->eh;
    o.linear = 1;
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
        if (w < 1) w = 1;
        if (h < 1) h = 1;
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
        if (w != sw->ew || h != sw->eh) {
            upsample(img, w, h, up, sw->ew, sw->eh);
            compare(sw, v, up, &res[i]);
        } else {
            compare(sw, v, img, &res[i]);
        }
        res[i].ok = 1;
        char d[512];
        config_diff(&cfg[i], d, sizeof d, " ");
        printf("sweep: %-14s %-40s %8.1f ms %6.3fx  relRMSE %.4f  PSNR %5.1f dB  visible %5.1f%%\n", v->name, d,
               res[i].time_ms, res[i].time_ratio, res[i].rel_rmse, res[i].psnr, res[i].visible);
        fflush(stdout);
    }
    free(img);
    free(up);
    free(t);
    free(rr);
    free(tw);
    free(th);
    if (es.disp || es.r || es.scene)
        cli_session_close(&es);
    return rc;
}

/* ---------------------------------------------------------------- output --------------------------------------- */

static void csv_row(sweep *sw, const char *kind, const char *scene, const char *knob, const char *value,
                    const config *c, const result *r, double pt_rel_noise)
{
    char d[512];
    config_diff(c, d, sizeof d, ";");
    fprintf(sw->csv, "%s,%s,%s,%s,\"%s\",%.3f,%.4f,%.3f,%.4f,%.6g,%.3f,%.6g,%.6g,%.3f,%.6g,%.5f,%.5f,%.5f\n", kind,
            scene, knob,
            value, d, r->time_ms, r->time_ratio, r->tmin_ms, r->tmin_ratio, r->rmse, r->psnr, r->peak, r->maxabs,
            r->visible, r->mean_ref,
            r->rel_rmse, r->rel_bias, pt_rel_noise);
}

/* Aggregate over views: means of the time ratio, relative RMSE, PSNR, visible share. */
static void aggregate(const sweep *sw, result *const *per_view, int idx, result *agg)
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

/* ---------------------------------------------------------------- presets -------------------------------------- */

typedef struct point {
    config c;
    result agg;
} point;

/* Measures one configuration on every view (the high configuration is re-timed in the same session) and returns the
 * aggregate; the per-view rows go to the CSV under `kind`. */
static int measure_config(sweep *sw, const config *c, const char *kind, const char *label, result *agg)
{
    config pair[2];
    config_high(&pair[0]);
    pair[1] = *c;
    result *rows[SW_MAX_SCENES];
    result all[SW_MAX_SCENES][2];
    memset(all, 0, sizeof all);
    for (int s = 0; s < sw->nviews; s++) {
        if (measure_view(sw, &sw->v[s], pair, 2, all[s]))
            return 1;
        rows[s] = all[s];
        csv_row(sw, kind, sw->v[s].name, label, "", c, &all[s][1], sw->v[s].pt_rel_noise);
    }
    aggregate(sw, rows, 1, agg);
    csv_row(sw, kind, "ALL", label, "", c, agg, 0);
    fflush(sw->csv);
    return 0;
}

/* Presets keep the scene's content: a knob value that changes what the cloud is rather than how precisely it is
 * rendered (noise switched off, another phase function) is measured and reported but never chosen for a preset, even
 * when it lowers the error against the reference (the first sweep picked quality.noise = off for medium: smooth
 * clouds are easier to match, but they are not the scene). */
static int preset_eligible(int k, int j)
{
    if (strcmp(KNOBS[k].name, "cloud.phase") == 0)
        return j == KNOBS[k].high;
    if (strcmp(KNOBS[k].name, "quality.noise_octaves") == 0)
        return strcmp(KNOBS[k].vals[j], "off") != 0;
    /* the output resolution is the application's (--size), not a scene key a preset can carry */
    if (strcmp(KNOBS[k].name, "output.scale") == 0)
        return j == KNOBS[k].high;
    return 1;
}

/* Greedy: from high, repeatedly apply the single-knob change with the smallest predicted error increase per unit of
 * time saved (prediction: the one-at-a-time deltas, relative to the value the knob has now), re-measure the
 * combination on every view, until the measured time ratio is within the budget. A change that, measured, does not
 * save at least 1 % of high's time is taken back and not tried again (the first run kept ms.sky_light = off, which
 * cost 0.12 in error and saved nothing once combined). */
static int choose_presets(sweep *sw, const result *single_agg, const int *vidx, double e_high, point *med,
                          point *low, point *trail, int *ntrail)
{
    config cur;
    config_high(&cur);
    double t_cur = 1.0, e_cur = e_high;
    int have_med = 0;
    unsigned char banned[NKNOBS * SW_MAX_VALUES];
    memset(banned, 0, sizeof banned);
    *ntrail = 0;
    for (int step = 0; step < 24; step++) {
        if (!have_med && t_cur <= sw->budget_med) {
            med->c = cur;
            med->agg.time_ratio = t_cur;
            med->agg.rel_rmse = e_cur;
            have_med = 1;
        }
        if (t_cur <= sw->budget_low)
            break;
        int bk = -1, bv = -1;
        double best = 1e300;
        for (int k = 0; k < NKNOBS; k++)
            for (int j = 0; j < KNOBS[k].nvals; j++) {
                if (j == cur.v[k] || vidx[k * SW_MAX_VALUES + j] < 0 || !preset_eligible(k, j) ||
                    banned[k * SW_MAX_VALUES + j])
                    continue;
                int cj = cur.v[k];
                const result *a = &single_agg[vidx[k * SW_MAX_VALUES + j]];
                double ta = a->time_ratio, ea = a->rel_rmse, tc = 1.0, ec = e_high;
                if (cj != KNOBS[k].high) {
                    const result *b = &single_agg[vidx[k * SW_MAX_VALUES + cj]];
                    tc = b->time_ratio;
                    ec = b->rel_rmse;
                }
                double dt = ta - tc, de = ea - ec;
                if (dt > -0.01) /* saves under 1 % of high's time: noise */
                    continue;
                double score = (de > 0 ? de : de * 1e-3) / -dt;
                if (score < best) {
                    best = score;
                    bk = k;
                    bv = j;
                }
            }
        if (bk < 0) {
            printf("sweep: presets: no single-knob change left that saves time (at %.2fx)\n", t_cur);
            break;
        }
        int was = cur.v[bk];
        cur.v[bk] = bv;
        char label[600], d[512];
        config_diff(&cur, d, sizeof d, " ");
        snprintf(label, sizeof label, "greedy%d", step + 1);
        printf("sweep: presets: step %d: %s=%s -> %s\n", step + 1, KNOBS[bk].name, KNOBS[bk].vals[bv], d);
        result agg;
        if (measure_config(sw, &cur, "greedy", label, &agg))
            return 1;
        trail[*ntrail].c = cur;
        trail[*ntrail].agg = agg;
        (*ntrail)++;
        printf("sweep: presets: step %d measured: time %.3fx, relRMSE %.4f\n", step + 1, agg.time_ratio, agg.rel_rmse);
        if (agg.time_ratio > t_cur - 0.01 && agg.rel_rmse > e_cur) {
            printf("sweep: presets: step %d saved no time and cost accuracy: taken back\n", step + 1);
            cur.v[bk] = was;
            banned[bk * SW_MAX_VALUES + bv] = 1;
            continue;
        }
        t_cur = agg.time_ratio;
        e_cur = agg.rel_rmse;
    }
    (void)have_med;
    /* Each preset is the lowest-error measured point (one-knob variant or greedy combination) within its budget; if
     * none is, the fastest measured point (reported as over budget). */
    point *pp[2] = {med, low};
    double budget[2] = {sw->budget_med, sw->budget_low};
    for (int q = 0; q < 2; q++) {
        int found = 0;
        double fastest = 1e300;
        point best = {0}, fast = {0};
        for (int i = -1; i < *ntrail + NKNOBS * SW_MAX_VALUES; i++) {
            point cand;
            if (i < 0) {
                config_high(&cand.c);
                cand.agg.time_ratio = 1.0;
                cand.agg.rel_rmse = e_high;
            } else if (i < *ntrail) {
                cand = trail[i];
            } else {
                int k = (i - *ntrail) / SW_MAX_VALUES, j = (i - *ntrail) % SW_MAX_VALUES;
                if (k >= NKNOBS || j >= KNOBS[k].nvals || vidx[k * SW_MAX_VALUES + j] <= 0 || !preset_eligible(k, j))
                    continue;
                config_high(&cand.c);
                cand.c.v[k] = j;
                cand.agg = single_agg[vidx[k * SW_MAX_VALUES + j]];
            }
            if (cand.agg.time_ratio <= budget[q] && (!found || cand.agg.rel_rmse < best.agg.rel_rmse)) {
                best = cand;
                found = 1;
            }
            if (cand.agg.time_ratio < fastest) {
                fastest = cand.agg.time_ratio;
                fast = cand;
            }
        }
        *pp[q] = found ? best : fast;
        if (!found)
            printf("sweep: presets: nothing measured within %.2fx; taking the fastest point (%.3fx)\n", budget[q],
                   fastest);
    }
    return 0;
}

static void sets_line(const config *c, char *out, size_t len)
{
    char sets[SW_MAX_SETS][64];
    double scale;
    int n = config_sets(c, sets, &scale);
    size_t m = 0;
    out[0] = 0;
    for (int i = 0; i < n; i++)
        m += (size_t)snprintf(out + m, m < len ? len - m : 0, "%s--set %s", i ? " " : "", sets[i]);
    if (scale != 1.0)
        snprintf(out + m, m < len ? len - m : 0, " # and render at %.2f of the output size, upsampled", scale);
}

/* ---------------------------------------------------------------- main ----------------------------------------- */

static int parse_size(const char *v, int *w, int *h)
{
    char tail;
    return sscanf(v, "%dx%d%c", w, h, &tail) == 2 && *w >= 1 && *h >= 1 && *w <= 4096 && *h <= 4096 ? 0 : -1;
}

static int parse_int(const char *v, int lo, int hi, int *out)
{
    char *end;
    long x = strtol(v, &end, 10);
    if (!*v || *end || x < lo || x > hi)
        return -1;
    *out = (int)x;
    return 0;
}

static const char *USAGE =
    "usage: cumulo sweep [--scenes a,b,c] [--out DIR] [--size WxH] [--time-size WxH] [--spp N] [--frames N]\n"
    "                    [--warmup N] [--threshold N] [--budgets M,L] [--ref-dir DIR] [--pt PATH] [--quick]\n"
    "                    [--sun-every-frame] [--refs-only]\n";

int cmd_sweep(int argc, char **argv)
{
    static sweep sw;
    memset(&sw, 0, sizeof sw);
    sw.ew = 160, sw.eh = 120, sw.tw = 640, sw.th = 480;
    sw.spp = 256, sw.frames = 7, sw.warmup = 1, sw.threshold = 3;
    sw.budget_med = 0.5, sw.budget_low = 0.25;
    sw.out = "build/sweep";
    sw.refdir = "build/sweep/ref";
    sw.pt = "build/cumulo-pt";
    sw.plot = "scripts/sweep_plot.sh";
    const char *scenes = NULL;
    int set_size = 0, set_tsize = 0, set_spp = 0, set_frames = 0, refs_only = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int takes = strcmp(a, "--scenes") == 0 || strcmp(a, "--out") == 0 || strcmp(a, "--size") == 0 ||
                    strcmp(a, "--time-size") == 0 || strcmp(a, "--spp") == 0 || strcmp(a, "--frames") == 0 ||
                    strcmp(a, "--warmup") == 0 || strcmp(a, "--threshold") == 0 || strcmp(a, "--budgets") == 0 ||
                    strcmp(a, "--ref-dir") == 0 || strcmp(a, "--pt") == 0;
        if (strcmp(a, "--sun-every-frame") == 0) {
            sw.sun_moving = 1;
            continue;
        }
        if (strcmp(a, "--refs-only") == 0) {
            refs_only = 1;
            continue;
        }
        if (strcmp(a, "--quick") == 0) {
            sw.quick = 1;
            continue;
        }
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            printf("%s", USAGE);
            return 0;
        }
        if (!takes)
            return bad(a[0] == '-' ? "unknown option '%s' (see --help)" : "unexpected argument '%s' (see --help)", a);
        if (i + 1 >= argc)
            return bad("%s needs a value", a);
        const char *v = argv[++i];
        if (strcmp(a, "--scenes") == 0) {
            if (!*v)
                return bad("--scenes expects a comma-separated list of scenes%s", "");
            scenes = v;
        } else if (strcmp(a, "--out") == 0) {
            if (!*v)
                return bad("--out expects a directory%s", "");
            sw.out = v;
        } else if (strcmp(a, "--ref-dir") == 0) {
            if (!*v)
                return bad("--ref-dir expects a directory%s", "");
            sw.refdir = v;
        } else if (strcmp(a, "--pt") == 0) {
            sw.pt = v;
        } else if (strcmp(a, "--size") == 0) {
            if (parse_size(v, &sw.ew, &sw.eh))
                return bad("--size expects WxH with 1..4096, got '%s'", v);
            set_size = 1;
        } else if (strcmp(a, "--time-size") == 0) {
            if (parse_size(v, &sw.tw, &sw.th))
                return bad("--time-size expects WxH with 1..4096, got '%s'", v);
            set_tsize = 1;
        } else if (strcmp(a, "--spp") == 0) {
            if (parse_int(v, 1, 1000000, &sw.spp))
                return bad("--spp expects a count from 1 to 1000000, got '%s'", v);
            set_spp = 1;
        } else if (strcmp(a, "--frames") == 0) {
            if (parse_int(v, 1, 10000, &sw.frames))
                return bad("--frames expects a count from 1 to 10000, got '%s'", v);
            set_frames = 1;
        } else if (strcmp(a, "--warmup") == 0) {
            if (parse_int(v, 0, 10000, &sw.warmup))
                return bad("--warmup expects a count from 0 to 10000, got '%s'", v);
        } else if (strcmp(a, "--threshold") == 0) {
            if (parse_int(v, 0, 255, &sw.threshold))
                return bad("--threshold expects 8-bit levels from 0 to 255, got '%s'", v);
        } else if (strcmp(a, "--budgets") == 0) {
            double m, l;
            char tail;
            if (sscanf(v, "%lf,%lf%c", &m, &l, &tail) != 2 || !(m > 0 && m <= 1) || !(l > 0 && l <= m))
                return bad("--budgets expects MEDIUM,LOW time ratios with 0 < LOW <= MEDIUM <= 1, got '%s'", v);
            sw.budget_med = m;
            sw.budget_low = l;
        }
    }
    if (sw.quick) {
        if (!scenes)
            scenes = "cumulus,silver_lining";
        if (!set_size)
            sw.ew = 80, sw.eh = 60;
        if (!set_tsize)
            sw.tw = 160, sw.th = 120;
        if (!set_spp)
            sw.spp = 16;
        if (!set_frames)
            sw.frames = 3;
        sw.warmup = sw.warmup < 1 ? sw.warmup : 1;
    }
    if (!scenes)
        scenes = "cumulus,silver_lining,sweep_thick_below,glory,inside,low_sun";
    /* views: a name means scenes/NAME.scene, anything with '/' or ending in .scene is a path */
    char list[4096];
    snprintf(list, sizeof list, "%s", scenes);
    for (char *tok = strtok(list, ","); tok; tok = strtok(NULL, ",")) {
        if (sw.nviews == SW_MAX_SCENES)
            return bad("at most 16 scenes%s", "");
        view *v = &sw.v[sw.nviews];
        size_t L = strlen(tok);
        if (strchr(tok, '/') || (L > 6 && strcmp(tok + L - 6, ".scene") == 0))
            snprintf(v->path, sizeof v->path, "%s", tok);
        else
            snprintf(v->path, sizeof v->path, "scenes/%s.scene", tok);
        const char *b = strrchr(v->path, '/');
        snprintf(v->name, sizeof v->name, "%s", b ? b + 1 : v->path);
        char *dot = strstr(v->name, ".scene");
        if (dot)
            *dot = 0;
        struct stat st;
        if (stat(v->path, &st))
            return bad("no scene file '%s'", v->path);
        for (int j = 0; j < sw.nviews; j++)
            if (strcmp(sw.v[j].name, v->name) == 0)
                return bad("scene '%s' given twice", v->name);
        sw.nviews++;
    }
    if (sw.nviews == 0)
        return bad("--scenes names no scene%s", "");
    if (mkdirs(sw.out) || mkdirs(sw.refdir))
        return fprintf(stderr, "cumulo sweep: cannot create %s or %s\n", sw.out, sw.refdir), 1;

    double t_start = now_ms();
    const char *lp = getenv("LP_NUM_THREADS");
    printf("sweep: %d views, error at %dx%d against cumulo-pt %d spp, time at %dx%d (median of %d frames after %d "
           "warm-up, %s), LP_NUM_THREADS=%s%s\n",
           sw.nviews, sw.ew, sw.eh, sw.spp, sw.tw, sw.th, sw.frames, sw.warmup,
           sw.sun_moving ? "sun moved every frame" : "static sun", lp ? lp : "(unset)",
           sw.quick ? ", quick" : "");
    /* references and per-view display constants */
    for (int s = 0; s < sw.nviews; s++) {
        view *v = &sw.v[s];
        cu_scene *sc;
        cu_error e;
        if (cu_scene_load(&sc, v->path, &e))
            return fprintf(stderr, "%s\n", e.msg), 1;
        v->exposure = sc->exposure;
        v->noise_on = sc->noise;
        cu_sky_white_balance(sc, v->white);
        cu_scene_free(sc);
        for (int c = 0; c < 3; c++)
            v->clip[c] = v->exposure > 0 ? 16.0 * v->white[c] / v->exposure : 1e30;
        if (load_reference(&sw, v))
            return 1;
        printf("sweep: reference %s: PT noise sqrt(mean sigma^2) = %.4g (%.2f%% of the mean radiance), mean standard "
               "error %.4g\n",
               v->name, v->pt_noise, 100 * v->pt_rel_noise, v->pt_mean_se);
    }

    if (refs_only)
        return 0;
    /* the single-knob variants: index 0 = high */
    config vars[NKNOBS * SW_MAX_VALUES + 1];
    int vknob[NKNOBS * SW_MAX_VALUES + 1], vval[NKNOBS * SW_MAX_VALUES + 1];
    int vidx[NKNOBS * SW_MAX_VALUES];
    int nv = 0;
    config_high(&vars[nv]);
    vknob[nv] = -1, vval[nv] = -1;
    nv++;
    for (int k = 0; k < NKNOBS; k++)
        for (int j = 0; j < KNOBS[k].nvals; j++) {
            vidx[k * SW_MAX_VALUES + j] = -1;
            if (j == KNOBS[k].high) {
                vidx[k * SW_MAX_VALUES + j] = 0;
                continue;
            }
            if (sw.quick && !KNOBS[k].quick[j])
                continue;
            config_high(&vars[nv]);
            vars[nv].v[k] = j;
            vknob[nv] = k, vval[nv] = j;
            vidx[k * SW_MAX_VALUES + j] = nv;
            nv++;
        }

    char path[1200];
    snprintf(path, sizeof path, "%s/sweep.csv", sw.out);
    sw.csv = fopen(path, "w");
    if (!sw.csv)
        return fprintf(stderr, "cumulo sweep: cannot write %s\n", path), 1;
    fprintf(sw.csv, "# cumulo sweep: error at %dx%d vs cumulo-pt %d spp; time at %dx%d, median of %d frames after %d "
                    "warm-up; psnr peak = reference 99th-percentile channel value; visible = share of pixels with an "
                    "8-bit tone-mapped channel differing by more than %d; both images clipped where the tone curve saturates "
                    "(exposure*L/white = 16); ALL rows = means over views (max_abs: max)\n",
            sw.ew, sw.eh, sw.spp, sw.tw, sw.th, sw.frames, sw.warmup, sw.threshold);
    fprintf(sw.csv, "kind,scene,knob,value,changes,time_ms,time_ratio,time_min_ms,time_min_ratio,rmse,psnr_db,psnr_peak,"
                    "max_abs,visible_pct,"
                    "mean_ref,rel_rmse,rel_rmse_denoised,pt_rel_noise\n");
    result *per_view[SW_MAX_SCENES];
    for (int s = 0; s < sw.nviews; s++) {
        per_view[s] = calloc((size_t)nv, sizeof(result));
        if (!per_view[s])
            return 1;
    }
    for (int s = 0; s < sw.nviews; s++) {
        view *v = &sw.v[s];
        /* with the view's noise off, the noise knob changes nothing: measure only what differs, copy high */
        config sub[NKNOBS * SW_MAX_VALUES + 1];
        int map[NKNOBS * SW_MAX_VALUES + 1], ns = 0;
        for (int i = 0; i < nv; i++) {
            if (!v->noise_on && i > 0 && strcmp(KNOBS[vknob[i]].name, "quality.noise_octaves") == 0) {
                map[i] = -1;
                continue;
            }
            map[i] = ns;
            sub[ns++] = vars[i];
        }
        result *r = calloc((size_t)ns, sizeof(result));
        if (!r || measure_view(&sw, v, sub, ns, r)) {
            free(r);
            return 1;
        }
        for (int i = 0; i < nv; i++)
            per_view[s][i] = map[i] >= 0 ? r[map[i]] : r[0];
        free(r);
        for (int i = 0; i < nv; i++)
            csv_row(&sw, "variant", v->name, i ? KNOBS[vknob[i]].name : "high", i ? KNOBS[vknob[i]].vals[vval[i]] : "",
                    &vars[i], &per_view[s][i], v->pt_rel_noise);
        fflush(sw.csv);
    }
    result *agg = calloc((size_t)nv, sizeof(result));
    if (!agg)
        return 1;
    for (int i = 0; i < nv; i++) {
        aggregate(&sw, per_view, i, &agg[i]);
        csv_row(&sw, "variant", "ALL", i ? KNOBS[vknob[i]].name : "high", i ? KNOBS[vknob[i]].vals[vval[i]] : "",
                &vars[i], &agg[i], 0);
    }
    fflush(sw.csv);

    point med, low, trail[32];
    int ntrail = 0;
    if (choose_presets(&sw, agg, vidx, agg[0].rel_rmse, &med, &low, trail, &ntrail))
        return 1;
    point high;
    config_high(&high.c);
    high.agg = agg[0];
    const point *presets[3] = {&low, &med, &high};
    const char *pnames[3] = {"low", "medium", "high"};
    for (int p = 0; p < 3; p++) {
        result r = presets[p]->agg;
        csv_row(&sw, "preset", "ALL", pnames[p], "", &presets[p]->c, &r, 0);
    }
    fclose(sw.csv);

    /* presets.txt */
    snprintf(path, sizeof path, "%s/presets.txt", sw.out);
    FILE *f = fopen(path, "w");
    if (!f)
        return fprintf(stderr, "cumulo sweep: cannot write %s\n", path), 1;
    fprintf(f, "# cumulo presets from `cumulo sweep` (budgets: medium <= %.2fx, low <= %.2fx of high's frame time;\n"
               "# the lowest-error measured point of a greedy descent within each budget). Time ratio and mean relative\n"
               "# RMSE over %d views against cumulo-pt.\n",
            sw.budget_med, sw.budget_low, sw.nviews);
    for (int p = 2; p >= 0; p--) {
        char line[2048], d[512];
        sets_line(&presets[p]->c, line, sizeof line);
        config_diff(&presets[p]->c, d, sizeof d, " ");
        fprintf(f, "# %s: time %.3fx, relRMSE %.4f (changes from high: %s)\n%s: %s\n", pnames[p],
                presets[p]->agg.time_ratio, presets[p]->agg.rel_rmse, d, pnames[p], line);
        printf("preset %-6s time %.3fx relRMSE %.4f: %s\n", pnames[p], presets[p]->agg.time_ratio,
               presets[p]->agg.rel_rmse, line);
    }
    fclose(f);

    /* pareto.dat: time_ratio rel_rmse kind label */
    snprintf(path, sizeof path, "%s/pareto.dat", sw.out);
    f = fopen(path, "w");
    if (!f)
        return fprintf(stderr, "cumulo sweep: cannot write %s\n", path), 1;
    fprintf(f, "# time_ratio rel_rmse kind label (kind 0 = one knob, 1 = greedy combination, 2 = preset, 9 = mean "
               "relative noise of the references, sqrt(mean sigma^2) / mean radiance)\n");
    for (int i = 1; i < nv; i++)
        fprintf(f, "%.4f %.5f 0 \"%s=%s\"\n", agg[i].time_ratio, agg[i].rel_rmse, KNOBS[vknob[i]].name + 
                (strchr(KNOBS[vknob[i]].name, '.') - KNOBS[vknob[i]].name + 1), KNOBS[vknob[i]].vals[vval[i]]);
    for (int i = 0; i < ntrail; i++)
        fprintf(f, "%.4f %.5f 1 \"g%d\"\n", trail[i].agg.time_ratio, trail[i].agg.rel_rmse, i + 1);
    for (int p = 0; p < 3; p++)
        fprintf(f, "%.4f %.5f 2 \"%s\"\n", presets[p]->agg.time_ratio, presets[p]->agg.rel_rmse, pnames[p]);
    double noise = 0;
    for (int s = 0; s < sw.nviews; s++)
        noise += sw.v[s].pt_rel_noise / sw.nviews;
    fprintf(f, "0 %.5f 9 \"reference noise\"\n", noise);
    fclose(f);

    /* sweep.md */
    snprintf(path, sizeof path, "%s/sweep.md", sw.out);
    f = fopen(path, "w");
    if (!f)
        return fprintf(stderr, "cumulo sweep: cannot write %s\n", path), 1;
    fprintf(f, "<!-- written by `cumulo sweep` (make sweep); do not edit -->\n");
    fprintf(f, "Speed versus accuracy, %d views (%s", sw.nviews, sw.v[0].name);
    for (int s = 1; s < sw.nviews; s++)
        fprintf(f, ", %s", sw.v[s].name);
    fprintf(f, "). Time: median frame time at %dx%d (%d frames after %d warm-up, wall clock incl. glFinish, %s, "
               "LP_NUM_THREADS=%s), as a ratio to `high` timed in the same session (high timed three times among the "
               "variants, frames interleaved round-robin), mean over views. Error: against cumulo-pt (%d spp) at "
               "%dx%d, both images clipped per channel where the display curve saturates (exposure·L/white = 16: the "
               "sun disk); relative RMSE = RMSE / mean reference radiance, mean over views; PSNR "
               "peak = the reference's 99th-percentile channel value; visible = share of pixels whose tone-mapped "
               "8-bit sRGB differs by more than %d/255 in a channel. Each knob is changed alone from `high` "
               "(= the README defaults; quality.noise stays as each view sets it).\n\n",
            sw.tw, sw.th, sw.frames, sw.warmup,
            sw.sun_moving ? "sun moved every frame (the sun pass redone)" : "static sun: the sun pass is not in the frame",
            lp ? lp : "(unset)", sw.spp, sw.ew, sw.eh, sw.threshold);
    fprintf(f, "| knob | value | time ratio | time ratio, fastest frames | rel. RMSE | Δ rel. RMSE "
               "| rel. RMSE, PT noise removed | PSNR dB | visible %% | Δ rel. RMSE per −0.1 time |\n");
    fprintf(f, "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    fprintf(f, "| **high** | | 1.000 | 1.000 | %.4f | | %.4f | %.1f | %.1f | |\n", agg[0].rel_rmse, agg[0].rel_bias, agg[0].psnr,
            agg[0].visible);
    for (int i = 1; i < nv; i++) {
        double dt = agg[i].time_ratio - 1, de = agg[i].rel_rmse - agg[0].rel_rmse;
        char buys[64];
        if (dt < -0.01)
            snprintf(buys, sizeof buys, "%+.4f", de / (-dt / 0.1));
        else
            snprintf(buys, sizeof buys, "%s", dt > 0.01 ? "costs time" : "no saving");
        fprintf(f, "| %s | %s | %.3f | %.3f | %.4f | %+.4f | %.4f | %.1f | %.1f | %s |\n", KNOBS[vknob[i]].name,
                KNOBS[vknob[i]].vals[vval[i]], agg[i].time_ratio, agg[i].tmin_ratio, agg[i].rel_rmse, de, agg[i].rel_bias, agg[i].psnr,
                agg[i].visible, buys);
    }
    fprintf(f, "\nPresets (budgets: medium ≤ %.2f×, low ≤ %.2f× of high's time; greedy descent from high taking the "
               "change with the least error increase per time saved, each combination re-measured):\n\n",
            sw.budget_med, sw.budget_low);
    fprintf(f, "| preset | time ratio | rel. RMSE | rel. RMSE, PT noise removed | changes from high |\n"
               "| --- | ---: | ---: | ---: | --- |\n");
    for (int p = 2; p >= 0; p--) {
        char d[512];
        config_diff(&presets[p]->c, d, sizeof d, ", ");
        fprintf(f, "| %s | %.3f | %.4f | %.4f | %s |\n", pnames[p], presets[p]->agg.time_ratio, presets[p]->agg.rel_rmse,
                presets[p]->agg.rel_bias, d);
    }
    fprintf(f, "\nPer view at `high` (reference noise: sqrt(mean σ²) of cumulo-pt / mean radiance):\n\n");
    fprintf(f, "| view | high ms | rel. RMSE | rel. RMSE, PT noise removed | PSNR dB (peak) | max abs | visible %% | PT "
               "noise (rel.) | PT mean std. error |\n");
    fprintf(f, "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (int s = 0; s < sw.nviews; s++) {
        const result *r = &per_view[s][0];
        fprintf(f, "| %s | %.1f | %.4f | %.4f | %.1f (%.3g) | %.3g | %.1f | %.4f | %.3g |\n", sw.v[s].name, r->time_ms,
                r->rel_rmse, r->rel_bias, r->psnr, r->peak, r->maxabs, r->visible, sw.v[s].pt_rel_noise,
                sw.v[s].pt_mean_se);
    }
    fclose(f);

    printf("sweep: wrote %s/sweep.csv, sweep.md, presets.txt, pareto.dat in %.1f min\n", sw.out,
           (now_ms() - t_start) / 60e3);
    struct stat st;
    if (stat(sw.plot, &st) == 0) {
        char cmd[2600];
        snprintf(cmd, sizeof cmd, "sh '%s' '%s'", sw.plot, sw.out);
        fflush(stdout);
        if (system(cmd) != 0)
            fprintf(stderr, "cumulo sweep: %s did not draw %s/pareto.png (CSV and tables are written)\n", sw.plot,
                    sw.out);
    }
    for (int s = 0; s < sw.nviews; s++) {
        free(per_view[s]);
        cu_image_free(&sw.v[s].ref);
    }
    free(agg);
    return 0;
}
