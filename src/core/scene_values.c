/* src/core/scene_values.c: the syntax of one scene key's value and the ranges of a scene's (see scene_keys.h); the
 * keys themselves are scene_keys.c's table. */
#include "scene_keys.h"
#include "error.h"
#include "solar.h"
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *cu_number_text(double v, char buf[32])
{
    for (int digits = 6; digits <= 17; digits++) { /* %g's own 6 first: "90", not "9e+01" */
        snprintf(buf, 32, "%.*g", digits, v);
        if (strtod(buf, NULL) == v)
            break;
    }
    return buf;
}

/* One written cloud's ranges (see cu_scene_check_ranges). */
static int check_cloud_ranges(const cu_scene *s, int ci, const char *file, cu_error *err)
{
    cu_cloud_spec spec = cu_scene_cloud(s, ci);
    const cu_cloud_spec *cs = &spec;
    const cu_ellipsoid *ell = &s->ell[cs->first];
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300}, rmin = 1e300;
    for (int i = 0; i < cs->count; i++)
        for (int a = 0; a < 3; a++) {
            lo[a] = fmin(lo[a], ell[i].center[a] - ell[i].radii[a]);
            hi[a] = fmax(hi[a], ell[i].center[a] + ell[i].radii[a]);
            rmin = fmin(rmin, ell[i].radii[a]);
        }
    double R = 0, dc = 0; /* as cu_cloud_build: origin mid-AABB, R over centres plus largest radii */
    for (int i = 0; i < cs->count; i++) {
        const double *c = ell[i].center, *r = ell[i].radii;
        double d2 = 0;
        for (int a = 0; a < 3; a++)
            d2 += (c[a] - 0.5 * (lo[a] + hi[a])) * (c[a] - 0.5 * (lo[a] + hi[a]));
        R = fmax(R, sqrt(d2) + fmax(r[0], fmax(r[1], r[2])));
    }
    for (int a = 0; a < 3; a++)
        dc += (s->cam_pos[a] - 0.5 * (lo[a] + hi[a])) * (s->cam_pos[a] - 0.5 * (lo[a] + hi[a]));
    dc = sqrt(dc);
    char b0[32], b1[32], b2[32], which[40] = "";
    if (s->n_clouds > 1)
        snprintf(which, sizeof which, " #%d", ci + 1);
    if (fmax(dc, 4 * R) > CU_MAX_SCENE_TO_RADIUS * rmin)
        return cu_fail(err,
                       "%s: the scene is too large for its smallest radius, %s m: the camera is %s m from the cloud%s's "
                       "centre, the cloud's radius is %s m; the distance and 4x the radius must each be at most %g "
                       "smallest radii (single-precision positions)",
                       file, cu_number_text(rmin, b0), cu_number_text(dc, b1), which, cu_number_text(R, b2),
                       CU_MAX_SCENE_TO_RADIUS);
    if (s->noise && R * s->noise_scale > CU_MAX_NOISE_EXTENT)
        return cu_fail(err,
                       "%s: [cloud] 'noise_scale' %s is too fine for a cloud of radius %s m: radius x noise_scale "
                       "must be at most %g m for single precision noise coordinates (or quality.noise = off)",
                       file, cu_number_text(s->noise_scale, b0), cu_number_text(R, b1), CU_MAX_NOISE_EXTENT);
    return 0;
}

int cu_scene_check_ranges(const cu_scene *s, const char *file, cu_error *err)
{
    for (int i = 0; i < cu_scene_cloud_count(s); i++)
        if (check_cloud_ranges(s, i, file, err))
            return 1;
    return 0;
}

static int clip40(int n)
{
    return n > 40 ? 40 : n;
}

int cu_scene_key_parse(const cu_scene_key *k, void *dst, const char *text, const char *at, cu_error *err)
{
    if (k->type == CU_KEY_TIME) {
        cu_utc t;
        char msg[sizeof err->msg];
        cu_error e2;
        if (strlen(text) >= CU_TIME_TEXT)
            return cu_fail(err, "%s: '%s' is longer than %d characters", at, k->name, CU_TIME_TEXT - 1);
        if (cu_utc_parse(text, &t, &e2)) {
            snprintf(msg, sizeof msg, "%s", e2.msg);
            return cu_fail(err, "%s: %.400s", at, msg);
        }
        snprintf((char *)dst, CU_TIME_TEXT, "%s", text);
        return 0;
    }
    if (k->values) {
        for (int i = 0; k->values[i]; i++)
            if (strcmp(text, k->values[i]) == 0) {
                *(int *)dst = i;
                return 0;
            }
        char choices[200] = "";
        for (int i = 0; k->values[i]; i++) {
            strncat(choices, i ? " | " : "", sizeof choices - strlen(choices) - 1);
            strncat(choices, k->values[i], sizeof choices - strlen(choices) - 1);
        }
        return cu_fail(err, "%s: '%s' must be one of %s, got '%.40s'", at, k->name, choices, text);
    }
    double vals[4];
    int n = 0;
    const char *p = text;
    while (*p) {
        while (*p == ' ' || *p == '\t' || *p == ',')
            p++;
        if (!*p)
            break;
        if (n == k->count)
            return cu_fail(err, "%s: '%s' needs %d number%s, got more", at, k->name, k->count, k->count > 1 ? "s" : "");
        char *end;
        errno = 0;
        double v = strtod(p, &end);
        if (end == p || (*end && *end != ' ' && *end != '\t' && *end != ','))
            return cu_fail(err, "%s: '%s' expects a number, got '%.*s'", at, k->name, clip40((int)strcspn(p, " \t,")), p);
        if (isnan(v))
            return cu_fail(err, "%s: '%s' is NaN", at, k->name);
        if (isinf(v) || errno == ERANGE) {
            if (isinf(v) || fabs(v) > 1.0)
                return cu_fail(err, "%s: '%s' is out of range (%.*s)", at, k->name, clip40((int)(end - p)), p);
            /* underflow: keep strtod's subnormal or zero, so the smallest positive double stays positive and the
             * range check judges the value written, not a 0 it never said */
        }
        char b0[32];
        if (k->type == CU_KEY_INTEGER && v != floor(v))
            return cu_fail(err, "%s: '%s' must be a whole number, got %s", at, k->name, cu_number_text(v, b0));
        vals[n++] = v;
        p = end;
    }
    if (n != k->count)
        return cu_fail(err, "%s: '%s' needs %d number%s, got %d", at, k->name, k->count, k->count > 1 ? "s" : "", n);
    for (int i = 0; i < n; i++) {
        double v = vals[i];
        int bad = k->lo_open ? !(v > k->lo) : !(v >= k->lo);
        if (bad || v > k->hi) {
            char b0[32], b1[32], b2[32];
            if (k->lo_open && k->lo == 0 && v <= 0)
                return cu_fail(err, "%s: '%s' must be positive, got %s", at, k->name, cu_number_text(v, b0));
            return cu_fail(err, "%s: '%s' must be in %s%s, %s]%s%s, got %s", at, k->name, k->lo_open ? "(" : "[",
                           cu_number_text(k->lo, b0), cu_number_text(k->hi, b1), k->unit[0] ? " " : "", k->unit,
                           cu_number_text(v, b2));
        }
    }
    for (int i = 0; i < n; i++) {
        if (k->type == CU_KEY_INTEGER)
            ((int *)dst)[i] = (int)vals[i];
        else
            ((double *)dst)[i] = vals[i];
    }
    return 0;
}

void cu_scene_keys_defaults(void *base, const cu_scene_key *keys, int n)
{
    /* The defaults are checked by tests/core/test_keys.c, so this cannot fail. */
    for (int i = 0; i < n; i++)
        if (keys[i].def)
            cu_scene_key_parse(&keys[i], (char *)base + keys[i].offset, keys[i].def, "default", NULL);
}
