/* tools/sweep/knobs.c: the knobs the sweep turns, their values, and `high`, the configuration every variant changes
 * one knob of. `high` is not written down here: it is what the baseline scene file (scenes/cumulus.scene, the default
 * scene, unless --baseline names another) has after cu_scene_load, read from the cu_scene struct of src/core/scene.h,
 * so the sweep follows the library's defaults and presets.c's `high` without restating them. */
#include "sweep.h"
#include "scene.h"
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MIE_G "0.853" /* asymmetry of data/mie_cloud.tbl: hg / cornette-shanks compared at the same g */

typedef enum field_kind { KF_INT, KF_DOUBLE, KF_ENUM, KF_SCALE } field_kind;

typedef struct knob_spec {
    const char *name;   /* scene key, or "output.scale" (render smaller and upsample: not a scene key) */
    field_kind kind;    /* how the cu_scene field at offset is read: int, double, or an int-sized enum */
    size_t offset;
    int nvals;
    const char *vals[SW_MAX_VALUES];
    int quick[SW_MAX_VALUES]; /* 1: measured in --quick */
} knob_spec;

/* The values swept, cheapest first. quality.noise_octaves carries `off` as its cheapest value (quality.noise =
 * off). cloud.phase hg/cs use g = MIE_G. output.scale's baseline is 1: the application's output size. */
#define F(f) offsetof(cu_scene, f)
static const knob_spec SPECS[] = {
    {"quality.segments", KF_INT, F(segments), 6, {"2", "3", "5", "8", "12", "20"}, {1, 0, 1, 0, 1, 0}},
    {"quality.segment_ratio", KF_DOUBLE, F(segment_ratio), 4, {"1", "1.3", "1.6", "2.2"}, {0}},
    {"quality.hull_tessellation", KF_INT, F(hull_tessellation), 4, {"4", "6", "10", "16"}, {0}},
    {"quality.max_intervals", KF_INT, F(max_intervals), 4, {"1", "2", "3", "6"}, {0, 1, 0, 1}},
    {"quality.noise_octaves", KF_INT, F(noise_octaves), 6, {"off", "1", "2", "3", "4", "5"}, {0, 0, 1, 0, 0, 1}},
    {"quality.sun_map_size", KF_INT, F(sun_map_size), 4, {"64", "128", "256", "512"}, {0}},
    {"light.shadow", KF_ENUM, F(shadow), 4, {"peel", "front", "osm", "fom"}, {0}},
    {"light.sun_intervals", KF_INT, F(sun_intervals), 3, {"1", "2", "3"}, {0}},
    {"light.sun_samples", KF_INT, F(sun_samples), 4, {"8", "16", "32", "64"}, {0}},
    {"light.sun_filter", KF_ENUM, F(sun_filter), 2, {"nearest", "bilinear"}, {0}},
    {"ms.mode", KF_ENUM, F(ms_mode), 5, {"none", "octaves", "slab", "collector", "diffusion"}, {1, 0, 1, 0, 0}},
    {"ms.blur", KF_DOUBLE, F(ms_blur_m), 3, {"100", "200", "400"}, {0}},
    {"ms.sky_light", KF_ENUM, F(sky_light), 2, {"off", "on"}, {0}},
    {"ms.closure", KF_ENUM, F(ms_closure), 2, {"off", "on"}, {0}},
    {"quality.integration", KF_ENUM, F(integration), 2, {"exponential", "kol"}, {0}},
    {"cloud.phase", KF_ENUM, F(phase), 3, {"mie", "hg", "cornette-shanks"}, {0}},
    {"quality.cloud_downsample", KF_INT, F(cloud_downsample), 3, {"4", "2", "1"}, {1, 0, 1}},
    {"output.scale", KF_SCALE, 0, 3, {"0.5", "0.75", "1"}, {1, 0, 1}},
};
#undef F
typedef char knob_table_size_matches[(int)(sizeof SPECS / sizeof SPECS[0]) == SW_NKNOBS ? 1 : -1];

knob sw_knobs[SW_NKNOBS];

static int fail(cu_error *err, const char *msg, const char *a, const char *b)
{
    snprintf(err->msg, sizeof err->msg, msg, a, b);
    return 1;
}

static double field_value(const knob_spec *k, const cu_scene *s)
{
    const char *p = (const char *)s + k->offset;
    if (k->kind == KF_DOUBLE) {
        double d;
        memcpy(&d, p, sizeof d);
        return d;
    }
    int i;
    memcpy(&i, p, sizeof i);
    return i;
}

/* Index of the baseline value of knob k: the listed value whose --set leaves the baseline's field as it is. A
 * number the list lacks is inserted in order. */
static int find_high(knob *kb, const knob_spec *k, const cu_scene *base, cu_error *err)
{
    if (k->kind == KF_SCALE) {
        for (int j = 0; j < kb->nvals; j++)
            if (atof(kb->vals[j]) == 1.0)
                return j;
        return fail(err, "cumulo-sweep: knob %s lists no scale 1%s", k->name, ""), -1;
    }
    double want = field_value(k, base);
    for (int j = 0; j < kb->nvals; j++) {
        if (strcmp(kb->vals[j], "off") == 0 && strcmp(k->name, "quality.noise_octaves") == 0)
            continue; /* quality.noise = off: not a value of the field */
        cu_scene probe = *base;
        char set[96];
        snprintf(set, sizeof set, "%s=%s", k->name, kb->vals[j]);
        cu_error e;
        if (cu_scene_set(&probe, set, &e))
            return fail(err, "cumulo-sweep: the knob table's value is not a scene value: %.400s%s", e.msg, ""), -1;
        if (field_value(k, &probe) == want)
            return j;
    }
    if (k->kind == KF_ENUM)
        return fail(err, "cumulo-sweep: %s: the baseline's %s is none of the values swept", base->name, k->name), -1;
    if (kb->nvals == SW_MAX_VALUES)
        return fail(err, "cumulo-sweep: %s: no room for the baseline's %s among the values swept", base->name,
                    k->name),
               -1;
    int at = 0; /* after the non-numbers (off) and the smaller numbers */
    while (at < kb->nvals && (strcmp(kb->vals[at], "off") == 0 || atof(kb->vals[at]) < want))
        at++;
    for (int j = kb->nvals; j > at; j--) {
        memcpy(kb->vals[j], kb->vals[j - 1], SW_VALUE_LEN);
        kb->quick[j] = kb->quick[j - 1];
    }
    if (k->kind == KF_INT)
        snprintf(kb->vals[at], SW_VALUE_LEN, "%d", (int)want);
    else
        snprintf(kb->vals[at], SW_VALUE_LEN, "%.17g", want);
    kb->quick[at] = 1;
    kb->nvals++;
    return at;
}

int sw_knobs_init(const char *baseline_path, cu_error *err)
{
    cu_scene *base;
    cu_error e;
    if (cu_scene_load(&base, baseline_path, &e))
        return fail(err, "cumulo-sweep: baseline scene: %.400s%s", e.msg, "");
    int rc = 0;
    for (int k = 0; k < SW_NKNOBS && rc == 0; k++) {
        knob *kb = &sw_knobs[k];
        memset(kb, 0, sizeof *kb);
        kb->name = SPECS[k].name;
        kb->nvals = SPECS[k].nvals;
        for (int j = 0; j < kb->nvals; j++) {
            snprintf(kb->vals[j], SW_VALUE_LEN, "%s", SPECS[k].vals[j]);
            kb->quick[j] = SPECS[k].quick[j];
        }
        kb->high = find_high(kb, &SPECS[k], base, err);
        rc = kb->high < 0;
    }
    cu_scene_free(base);
    return rc;
}

int sw_knob_is(int k, const char *name)
{
    return strcmp(sw_knobs[k].name, name) == 0;
}

void config_high(config *c)
{
    for (int k = 0; k < SW_NKNOBS; k++)
        c->v[k] = sw_knobs[k].high;
    c->extra[0] = 0;
}

/* The next of a configuration's extra "key=value;..." settings at *p: where it starts (*at), its length, *p past it. */
static size_t next_extra(const char **p, const char **at)
{
    size_t len = strcspn(*p, ";");
    *at = *p;
    *p += len + ((*p)[len] == ';');
    return len;
}

/* All keys given explicitly, so a view's own quality lines do not leak in; quality.noise stays the view's choice
 * unless the knob says off. */
int config_sets(const config *c, char sets[][64], double *scale)
{
    int n = 0;
    *scale = 1.0;
    for (int k = 0; k < SW_NKNOBS; k++) {
        const knob *kb = &sw_knobs[k];
        const char *val = kb->vals[c->v[k]];
        if (sw_knob_is(k, "output.scale")) {
            *scale = atof(val);
        } else if (sw_knob_is(k, "quality.noise_octaves") && strcmp(val, "off") == 0) {
            snprintf(sets[n++], 64, "quality.noise=off");
        } else {
            snprintf(sets[n++], 64, "%s=%s", kb->name, val);
            if (sw_knob_is(k, "cloud.phase") && strcmp(val, "mie") != 0)
                snprintf(sets[n++], 64, "cloud.g=%s", MIE_G);
        }
    }
    for (const char *p = c->extra, *at; *p && n < SW_MAX_SETS;) { /* the extra settings, after the knobs' */
        size_t len = next_extra(&p, &at);
        if (len > 0 && len < 64)
            snprintf(sets[n++], 64, "%.*s", (int)len, at);
    }
    return n;
}

void config_diff(const config *c, char *out, size_t len, const char *sep)
{
    out[0] = 0;
    size_t n = 0;
    for (int k = 0; k < SW_NKNOBS; k++)
        if (c->v[k] != sw_knobs[k].high) {
            const char *name = sw_knobs[k].name, *val = sw_knobs[k].vals[c->v[k]];
            if (sw_knob_is(k, "quality.noise_octaves") && strcmp(val, "off") == 0)
                name = "quality.noise"; /* the key it sets */
            n += (size_t)snprintf(out + n, n < len ? len - n : 0, "%s%s=%s", n ? sep : "", name, val);
        }
    for (const char *p = c->extra, *at; *p;) {
        size_t l = next_extra(&p, &at);
        n += (size_t)snprintf(out + n, n < len ? len - n : 0, "%s%.*s", n ? sep : "", (int)l, at);
    }
    if (n == 0)
        snprintf(out, len, "high");
}

void config_sets_line(const config *c, char *out, size_t len)
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

/* Presets keep the scene's content: a knob value that changes what the cloud is rather than how precisely it is
 * rendered (noise switched off, another phase function) is measured and reported but never chosen for a preset, even
 * when it lowers the error against the reference (the first sweep picked quality.noise = off for medium: smooth
 * clouds are easier to match, but they are not the scene). sun_timed: the timed frames turn the sun every frame
 * (cumulo-sweep --sun-step 0.5 or more), so they hold what the sun's maps and diffusion's solves cost. */
int knob_preset_eligible(int k, int j, int sun_timed)
{
    if (sw_knob_is(k, "cloud.phase"))
        return j == sw_knobs[k].high;
    if (sw_knob_is(k, "quality.noise_octaves"))
        return strcmp(sw_knobs[k].vals[j], "off") != 0;
    /* one interval per pixel cuts a cloud where the ray leaves it and enters it again: seams across a field's clouds
     * (scenes/field_noon.scene), content lost rather than precision; the sweep's views did not punish it */
    if (sw_knob_is(k, "quality.max_intervals"))
        return atoi(sw_knobs[k].vals[j]) >= 2;
    /* a diffusion grid's solve runs on the CPU when a cloud's maps are made and again as the sun turns: every cloud of
     * a field in its first frame (scenes/field_noon.scene: 35 solves, seconds), later up to ms.frame_work a frame and
     * a coarse grid for each cloud new to the view (pass_msd.h). Static frames hold none of it: a preset chosen on
     * them would hide that cost, so there it is measured and reported but not chosen (README "Speed against
     * accuracy"); frames that turn the sun hold the solves a turning sun brings */
    if (sw_knob_is(k, "ms.mode"))
        return sun_timed || strcmp(sw_knobs[k].vals[j], "diffusion") != 0;
    /* the sun's maps are made outside static frames (once for a still sun, a band a frame while it moves): a value
     * that makes them dearer than high's looks free there (the 2026-12-06 sweep took 64 sun samples for low, twice
     * its maps' cost, on a timing difference within the noise), so only high's or a cheaper one, unless the frames
     * turn the sun */
    if (sw_knob_is(k, "light.sun_samples") || sw_knob_is(k, "light.sun_intervals") ||
        sw_knob_is(k, "quality.sun_map_size") || sw_knob_is(k, "ms.blur"))
        return sun_timed || j <= sw_knobs[k].high;
    /* the output resolution is the application's (--size), not a scene key a preset can carry */
    if (sw_knob_is(k, "output.scale"))
        return j == sw_knobs[k].high;
    return 1;
}
