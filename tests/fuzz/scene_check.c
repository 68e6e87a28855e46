/* tests/fuzz/scene_check.c: invariants of an accepted scene and its round trip through a file (scene_check.h). */
#include "scene_check.h"
#include "fuzz.h"
#include "scene_keys.h"
#include <math.h>

static void check_keys(const void *base, const cu_scene_key *keys, int n, const char *where)
{
    for (int i = 0; i < n; i++) {
        const cu_scene_key *k = &keys[i];
        const char *p = (const char *)base + k->offset;
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
    FUZZ_CHECK(s->n_ellipsoids >= 1 && s->n_ellipsoids <= CU_MAX_ELLIPSOIDS, "%d ellipsoids", s->n_ellipsoids);
    check_keys(s, cu_scene_keys, CU_SCENE_KEY_COUNT, "scene");
    for (int e = 0; e < s->n_ellipsoids; e++)
        check_keys(&s->ell[e], cu_ellipsoid_keys, CU_ELLIPSOID_KEY_COUNT, "ellipsoid");
}

/* Appends "key = value" of every key of keys[0..n-1] held in base. */
static int write_keys(const void *base, const cu_scene_key *keys, int n, const char *section, char **p, char *end)
{
    for (int i = 0; i < n; i++) {
        const cu_scene_key *k = &keys[i];
        if (strcmp(k->section, section) || (k->given && !*(const int *)((const char *)base + k->given)))
            continue; /* another section's, or an optional key the scene does not give */
        const char *v = (const char *)base + k->offset;
        int w = snprintf(*p, (size_t)(end - *p), "%s =", k->name);
        if (w < 0 || w >= end - *p)
            return 1;
        *p += w;
        for (int c = 0; c < (k->values ? 1 : k->count); c++) {
            if (k->values)
                w = snprintf(*p, (size_t)(end - *p), " %s", k->values[*(const int *)v]);
            else if (k->type == CU_KEY_INTEGER)
                w = snprintf(*p, (size_t)(end - *p), " %d", ((const int *)v)[c]);
            else
                w = snprintf(*p, (size_t)(end - *p), " %.17g", ((const double *)v)[c]);
            if (w < 0 || w >= end - *p)
                return 1;
            *p += w;
        }
        if (end - *p < 2)
            return 1;
        *(*p)++ = '\n';
    }
    return 0;
}

size_t fuzz_scene_write(const cu_scene *s, char *buf, size_t cap)
{
    char *p = buf, *end = buf + cap;
    for (int i = 0; i < CU_SCENE_SECTION_COUNT; i++) {
        const cu_scene_section *sec = &cu_scene_sections[i];
        int instances = sec->repeated ? s->n_ellipsoids : 1;
        for (int e = 0; e < instances; e++) {
            int w = snprintf(p, (size_t)(end - p), "[%s]\n", sec->name);
            if (w < 0 || w >= end - p)
                return 0;
            p += w;
            if (sec->repeated ? write_keys(&s->ell[e], cu_ellipsoid_keys, CU_ELLIPSOID_KEY_COUNT, sec->name, &p, end)
                              : write_keys(s, cu_scene_keys, CU_SCENE_KEY_COUNT, sec->name, &p, end))
                return 0;
        }
    }
    return (size_t)(p - buf);
}

/* The parsed copy holds the same values: everything the keys store (the name and the given-flags aside). */
static void check_same(const void *a, const void *b, const cu_scene_key *keys, int n)
{
    for (int i = 0; i < n; i++) {
        const cu_scene_key *k = &keys[i];
        size_t sz = k->values ? sizeof(int) : (k->type == CU_KEY_INTEGER ? sizeof(int) : sizeof(double)) * k->count;
        FUZZ_CHECK(!memcmp((const char *)a + k->offset, (const char *)b + k->offset, sz), "%s.%s reads back changed",
                   k->section, k->name);
    }
}

int fuzz_scene_roundtrip(const cu_scene *s, char *why, size_t whylen)
{
    static char buf[64 * 1024];
    size_t len = fuzz_scene_write(s, buf, sizeof buf);
    FUZZ_CHECK(len > 0, "the scene does not fit in %zu bytes", sizeof buf);
    cu_scene *t;
    cu_error err = {""};
    if (cu_scene_parse(&t, "roundtrip", buf, len, &err)) {
        snprintf(why, whylen, "%s", err.msg);
        return 0;
    }
    FUZZ_CHECK(t->n_ellipsoids == s->n_ellipsoids, "%d ellipsoids read back as %d", s->n_ellipsoids, t->n_ellipsoids);
    check_same(s, t, cu_scene_keys, CU_SCENE_KEY_COUNT);
    for (int e = 0; e < s->n_ellipsoids; e++)
        check_same(&s->ell[e], &t->ell[e], cu_ellipsoid_keys, CU_ELLIPSOID_KEY_COUNT);
    cu_scene_free(t);
    return 1;
}
