/* tests/fuzz/scene_check.c: invariants of an accepted scene and its round trip through a file (scene_check.h). */
#include "scene_check.h"
#include "fuzz.h"
#include "scene_keys.h"
#include "scene_write.h"
#include <math.h>

static void check_keys(const void *base, const cu_scene_key *keys, int n, const char *where)
{
    for (int i = 0; i < n; i++) {
        const cu_scene_key *k = &keys[i];
        const char *p = (const char *)base + k->offset;
        if (k->type == CU_KEY_TIME) {
            FUZZ_CHECK(memchr(p, 0, CU_TIME_TEXT) != NULL, "%s %s.%s not terminated", where, k->section, k->name);
            continue;
        }
        if (k->values) {
            int v = *(const int *)p, nv = 0;
            while (k->values[nv])
                nv++;
            FUZZ_CHECK(v >= 0 && v < nv, "%s %s.%s = index %d of %d", where, k->section, k->name, v, nv);
            continue;
        }
        for (int c = 0; c < k->count; c++) {
            double v = k->type == CU_KEY_INTEGER ? ((const int *)p)[c] : ((const double *)p)[c];
            FUZZ_CHECK(isfinite(v), "%s %s.%s[%d] = %g", where, k->section, k->name, c, v);
            FUZZ_CHECK(k->lo_open ? v > k->lo : v >= k->lo, "%s %s.%s[%d] = %.17g below %.17g", where, k->section,
                       k->name, c, v, k->lo);
            FUZZ_CHECK(v <= k->hi, "%s %s.%s[%d] = %.17g above %.17g", where, k->section, k->name, c, v, k->hi);
            if (k->type == CU_KEY_INTEGER && k->multiple)
                FUZZ_CHECK(((const int *)p)[c] % k->multiple == 0, "%s %s.%s = %d not a multiple of %d", where,
                           k->section, k->name, ((const int *)p)[c], k->multiple);
        }
    }
}

void fuzz_scene_check(const cu_scene *s)
{
    FUZZ_CHECK(memchr(s->name, 0, sizeof s->name), "name not terminated");
    FUZZ_CHECK(s->n_ellipsoids >= 0 && s->n_ellipsoids <= CU_MAX_SCENE_ELLIPSOIDS, "%d ellipsoids", s->n_ellipsoids);
    FUZZ_CHECK(s->n_clouds >= 0 && s->n_clouds <= CU_MAX_CLOUDS, "%d clouds", s->n_clouds);
    FUZZ_CHECK(s->n_layers >= 0 && s->n_layers <= CU_MAX_LAYERS, "%d layers", s->n_layers);
    int next = 0;
    for (int c = 0; c < s->n_clouds; c++) { /* the clouds partition the ellipsoids, in order, none empty */
        FUZZ_CHECK(s->clouds[c].first == next && s->clouds[c].count >= 1 && s->clouds[c].count <= CU_MAX_ELLIPSOIDS,
                   "cloud %d: ellipsoids %d+%d after %d", c, s->clouds[c].first, s->clouds[c].count, next);
        next += s->clouds[c].count;
        check_keys(&s->clouds[c], cu_cloud_keys, CU_CLOUD_KEY_COUNT, "cloud");
    }
    FUZZ_CHECK(next == s->n_ellipsoids, "clouds hold %d of %d ellipsoids", next, s->n_ellipsoids);
    check_keys(s, cu_scene_keys, CU_SCENE_KEY_COUNT, "scene");
    for (int e = 0; e < s->n_ellipsoids; e++)
        check_keys(&s->ell[e], cu_ellipsoid_keys, CU_ELLIPSOID_KEY_COUNT, "ellipsoid");
    for (int l = 0; l < s->n_layers; l++)
        check_keys(&s->layers[l], cu_layer_keys, CU_LAYER_KEY_COUNT, "layer");
}

size_t fuzz_scene_write(const cu_scene *s, char *buf, size_t cap)
{
    return cu_scene_format(s, buf, cap);
}

/* The parsed copy holds the same values: everything the keys store (the name and the given-flags aside). */
static void check_same(const void *a, const void *b, const cu_scene_key *keys, int n)
{
    for (int i = 0; i < n; i++) {
        const cu_scene_key *k = &keys[i];
        size_t sz = k->type == CU_KEY_TIME ? CU_TIME_TEXT
                    : k->values ? sizeof(int) : (k->type == CU_KEY_INTEGER ? sizeof(int) : sizeof(double)) * k->count;
        FUZZ_CHECK(!memcmp((const char *)a + k->offset, (const char *)b + k->offset, sz), "%s.%s reads back changed",
                   k->section, k->name);
    }
}

int fuzz_scene_roundtrip(const cu_scene *s, char *why, size_t whylen)
{
    static char buf[4 << 20];
    size_t len = fuzz_scene_write(s, buf, sizeof buf);
    FUZZ_CHECK(len > 0, "the scene does not fit in %zu bytes", sizeof buf);
    cu_scene *t;
    cu_error err = {""};
    if (cu_scene_parse(&t, "roundtrip", buf, len, &err)) {
        snprintf(why, whylen, "%s", err.msg);
        return 0;
    }
    FUZZ_CHECK(t->n_ellipsoids == s->n_ellipsoids, "%d ellipsoids read back as %d", s->n_ellipsoids, t->n_ellipsoids);
    FUZZ_CHECK(t->n_clouds == s->n_clouds && t->n_layers == s->n_layers, "%d clouds, %d layers read back as %d, %d",
               s->n_clouds, s->n_layers, t->n_clouds, t->n_layers);
    check_same(s, t, cu_scene_keys, CU_SCENE_KEY_COUNT);
    for (int e = 0; e < s->n_ellipsoids; e++)
        check_same(&s->ell[e], &t->ell[e], cu_ellipsoid_keys, CU_ELLIPSOID_KEY_COUNT);
    for (int l = 0; l < s->n_layers; l++)
        check_same(&s->layers[l], &t->layers[l], cu_layer_keys, CU_LAYER_KEY_COUNT);
    for (int c = 0; c < s->n_clouds; c++) { /* resolved: a value given twice the same way reads back the same */
        cu_cloud_spec a = cu_scene_cloud(s, c), b = cu_scene_cloud(t, c);
        FUZZ_CHECK(a.first == b.first && a.count == b.count, "cloud %d's ellipsoids change", c);
        check_same(&a, &b, cu_cloud_keys, CU_CLOUD_KEY_COUNT);
    }
    cu_scene_free(t);
    return 1;
}
