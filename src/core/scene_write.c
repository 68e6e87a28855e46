/* src/core/scene_write.c: a scene as scene-file text (see scene_write.h), through the key table. */
#include "scene_write.h"
#include "scene_keys.h"
#include <stdio.h>
#include <string.h>

typedef struct out {
    char *p, *end;
    int full;
} out;


static void put(out *o, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

#include <stdarg.h>
static void put(out *o, const char *fmt, ...)
{
    if (o->full)
        return;
    va_list ap;
    va_start(ap, fmt);
    int w = vsnprintf(o->p, (size_t)(o->end - o->p), fmt, ap);
    va_end(ap);
    if (w < 0 || w >= o->end - o->p) {
        o->full = 1;
        return;
    }
    o->p += w;
}

/* "key = value" of every key of keys[0..n-1] of section held in base; `given` flags (offsets into base) leave out
 * what the instance does not give, and no_angles the sun's angles (with a time and place they follow from those,
 * and a file may not give both). */
static void keys_of(out *o, const void *base, const cu_scene_key *keys, int n, const char *section, int no_angles)
{
    for (int i = 0; i < n; i++) {
        const cu_scene_key *k = &keys[i];
        if (strcmp(k->section, section) || (k->given && !*(const int *)((const char *)base + k->given)))
            continue;
        if (no_angles && strcmp(section, "sun") == 0 &&
            (strcmp(k->name, "elevation") == 0 || strcmp(k->name, "azimuth") == 0))
            continue;
        const char *v = (const char *)base + k->offset;
        put(o, "%s =", k->name);
        for (int c = 0; c < (k->values ? 1 : k->count); c++) {
            if (k->type == CU_KEY_TIME)
                put(o, " %s", v);
            else if (k->values)
                put(o, " %s", k->values[*(const int *)v]);
            else if (k->type == CU_KEY_INTEGER)
                put(o, " %d", ((const int *)v)[c]);
            else
                put(o, " %.17g", ((const double *)v)[c]);
        }
        put(o, "\n");
    }
}

static void ellipsoids(out *o, const cu_scene *s, int first, int count)
{
    for (int e = first; e < first + count; e++) {
        put(o, "[ellipsoid]\n");
        keys_of(o, &s->ell[e], cu_ellipsoid_keys, CU_ELLIPSOID_KEY_COUNT, "ellipsoid", 0);
    }
}

static int gives_own(const cu_cloud_spec *c)
{
    return c->has_density || c->has_boundary || c->has_wind || c->has_noise_offset || c->has_lifetime ||
           c->has_life_phase || c->has_wrap;
}

size_t cu_scene_format(const cu_scene *s, char *buf, size_t cap)
{
    if (cap == 0)
        return 0;
    out o = {buf, buf + cap, 0};
    for (int i = 0; i < CU_SCENE_SECTION_COUNT; i++) {
        const cu_scene_section *sec = &cu_scene_sections[i];
        if (sec->repeated || strcmp(sec->name, "cloud") == 0)
            continue;
        put(&o, "[%s]\n", sec->name);
        keys_of(&o, s, cu_scene_keys, CU_SCENE_KEY_COUNT, sec->name, s->has_time_utc);
    }
    for (int l = 0; l < s->n_layers; l++) {
        put(&o, "[layer]\n");
        keys_of(&o, &s->layers[l], cu_layer_keys, CU_LAYER_KEY_COUNT, "layer", 0);
    }
    /* The first [cloud] holds every cloud's defaults; cloud 1's ellipsoids follow it unless cloud 1 gives values
     * of its own, which only a [cloud] of its own can say. */
    put(&o, "[cloud]\n");
    keys_of(&o, s, cu_scene_keys, CU_SCENE_KEY_COUNT, "cloud", 0);
    int n = cu_scene_cloud_count(s);
    for (int c = 0; c < n; c++) {
        cu_cloud_spec spec = s->n_clouds ? s->clouds[c] : cu_scene_cloud(s, c);
        if (c > 0 || gives_own(&spec)) {
            put(&o, "[cloud]\n");
            keys_of(&o, &spec, cu_cloud_keys, CU_CLOUD_KEY_COUNT, "cloud", 0);
        }
        ellipsoids(&o, s, spec.first, spec.count);
    }
    return o.full ? 0 : (size_t)(o.p - buf);
}
