/* tools/sweep/reference.c: the path-traced reference of each view, rendered in-process by the path tracer
 * (tools/pathtrace/pt.c, the integrator build/cumulo-pt runs) with the high settings and cached in the reference
 * folder as NAME-HASH.pfm and NAME-HASH.pfm.stderr.pfm (mean and standard error, as cumulo-pt writes them). HASH
 * covers the scene file, the size, spp and seed, the knob values the path tracer sees, and SW_PT_CODE: a checksum
 * of the path tracer's and the core's object code (tools/sweep/sweep.mk), so a rebuild of the same code keeps the
 * cache and any change to the integrator renders anew. */
#include "sweep.h"
#include "pt.h"
#include "scene.h"
#include "sweep_pt_code.h"
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define SW_PT_SEED 1

static uint64_t fnv(uint64_t h, const void *data, size_t n)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < n; i++) {
        h ^= p[i];
        h *= 1099511628211ull;
    }
    return h;
}

static int read_all(const char *path, char **buf, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return -1;
    size_t cap = 4096, n = 0, r;
    char *b = malloc(cap);
    while (b && (r = fread(b + n, 1, cap - n, f)) > 0) {
        n += r;
        if (n == cap) {
            char *nb = realloc(b, cap *= 2);
            if (!nb)
                free(b);
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

/* Path-traces v with sets[0..ns-1] applied into out and se. */
static int render_reference(const sweep *sw, const view *v, char sets[][64], int ns, const char *out, const char *se)
{
    cu_scene *s;
    cu_error e;
    if (cu_scene_load(&s, v->path, &e))
        return fprintf(stderr, "cumulo-sweep: %s\n", e.msg), 1;
    for (int i = 0; i < ns; i++)
        if (cu_scene_set(s, sets[i], &e)) {
            cu_scene_free(s);
            return fprintf(stderr, "cumulo-sweep: %s\n", e.msg), 1;
        }
    size_t n = (size_t)sw->ew * sw->eh * 3;
    float *mean = malloc(sizeof(float) * n), *sig = malloc(sizeof(float) * n);
    pt_render_opts o = {sw->ew, sw->eh, sw->spp, sw->pt_threads, SW_PT_SEED, 0, PT_MODE_RADIANCE, 0};
    const char *dd = sw_data_dir();
    int rc = 0;
    if (!mean || !sig) {
        fprintf(stderr, "cumulo-sweep: out of memory for the reference of %s\n", v->name);
        rc = 1;
    } else if (pt_render_scene(s, dd ? dd : cu_default_data_dir(), &o, mean, sig, NULL, &e)) {
        fprintf(stderr, "cumulo-sweep: the path tracer failed on %s: %s\n", v->path, e.msg);
        rc = 1;
    } else if (cu_write_pfm(out, mean, sw->ew, sw->eh, &e) || cu_write_pfm(se, sig, sw->ew, sw->eh, &e)) {
        fprintf(stderr, "cumulo-sweep: %s\n", e.msg);
        remove(out);
        remove(se);
        rc = 1;
    }
    free(mean);
    free(sig);
    cu_scene_free(s);
    return rc;
}

int sw_load_reference(sweep *sw, view *v)
{
    char *text;
    size_t len;
    if (read_all(v->path, &text, &len))
        return fprintf(stderr, "cumulo-sweep: cannot read %s\n", v->path), 1;
    /* The path tracer's image depends on the scene file, the density knobs (noise octaves; noise on/off stays the
     * view's) and the phase model; the other knobs are the real-time renderer's alone. The reference has the high
     * values of those. */
    config hc;
    config_high(&hc);
    char sets[2][64];
    int ns = 0;
    for (int k = 0; k < SW_NKNOBS; k++)
        if (sw_knob_is(k, "quality.noise_octaves") || sw_knob_is(k, "cloud.phase"))
            snprintf(sets[ns++], 64, "%s=%s", sw_knobs[k].name, sw_knobs[k].vals[hc.v[k]]);
    char key[512];
    snprintf(key, sizeof key, "|%dx%d|spp%d|seed%d|pt %s|", sw->ew, sw->eh, sw->spp, SW_PT_SEED, SW_PT_CODE);
    uint64_t h = fnv(1469598103934665603ull, text, len);
    free(text);
    h = fnv(h, key, strlen(key));
    for (int i = 0; i < ns; i++)
        h = fnv(h, sets[i], strlen(sets[i]));
    char out[1024], se[1100];
    snprintf(out, sizeof out, "%s/%s-%016llx.pfm", sw->refdir, v->name, (unsigned long long)h);
    snprintf(se, sizeof se, "%s.stderr.pfm", out);
    struct stat st;
    if (stat(out, &st) || stat(se, &st)) {
        printf("sweep: reference %s: path tracer, %d spp, %d threads (cached as %s)\n", v->name, sw->spp,
               sw->pt_threads, out);
        fflush(stdout);
        double t0 = sw_now_ms();
        if (render_reference(sw, v, sets, ns, out, se))
            return 1;
        printf("sweep: reference %s took %.1f s\n", v->name, (sw_now_ms() - t0) / 1e3);
    }
    cu_error err;
    cu_image sig;
    if (cu_pfm_read(out, &v->ref, &err))
        return fprintf(stderr, "cumulo-sweep: %s\n", err.msg), 1;
    if (cu_pfm_read(se, &sig, &err))
        return fprintf(stderr, "cumulo-sweep: %s\n", err.msg), 1;
    if (v->ref.width != sw->ew || v->ref.height != sw->eh || sig.width != sw->ew || sig.height != sw->eh) {
        cu_image_free(&sig);
        return fprintf(stderr, "cumulo-sweep: %s has the wrong size\n", out), 1;
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
