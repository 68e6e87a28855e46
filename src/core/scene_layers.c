/* src/core/scene_layers.c: [layer]s as clouds (see scene_layers.h). */
#include "scene_layers.h"
#include "error.h"
#include "layer.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* 0..1 from a cloud's seed (splitmix64 finaliser): its life phase and noise offset differ from its neighbours'. */
static double seed_unit(uint64_t seed, int k)
{
    uint64_t z = seed + 0x9e3779b97f4a7c15ull * (uint64_t)(k + 1);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return (double)(z >> 11) * (1.0 / 9007199254740992.0);
}

void cu_generated_free(cu_generated *g)
{
    free(g->spec);
    free(g->ell);
    memset(g, 0, sizeof *g);
}

static int append_layer(cu_generated *g, const cu_scene *s, const cu_scene_layer *sl, cu_error *err)
{
    /* The margin: the visible edge sits about half the boundary inside a hull (the density ramps up over h). */
    cu_layer_spec spec = {.type = (cu_cumulus_type)sl->type, .base = sl->base, .thickness = sl->thickness,
                          .coverage = sl->coverage, .extent = sl->extent, .margin = 0.5 * s->boundary_m,
                          .seed = (uint64_t)sl->seed};
    cu_layer l;
    char at[300];
    snprintf(at, sizeof at, "%.256s:%d", s->name, sl->line);
    if (cu_layer_generate(&spec, &l, err)) {
        char msg[sizeof err->msg];
        snprintf(msg, sizeof msg, "%s", err->msg);
        return cu_fail(err, "%.200s: [layer]: %.300s", at, msg);
    }
    int nc = g->n_clouds + l.n_clouds, ne = g->n_ell + l.n_ell;
    cu_cloud_spec *ns = realloc(g->spec, sizeof *ns * (size_t)(nc > 0 ? nc : 1));
    if (ns)
        g->spec = ns;
    cu_ellipsoid *ne_ = realloc(g->ell, sizeof *ne_ * (size_t)(ne > 0 ? ne : 1));
    if (ne_)
        g->ell = ne_;
    if (!ns || !ne_) {
        cu_layer_free(&l);
        return cu_fail(err, "%s: [layer]: out of memory for %d clouds", at, nc);
    }
    for (int i = 0; i < l.n_ell; i++) {
        memcpy(g->ell[g->n_ell + i].center, l.ell[i].center, sizeof l.ell[i].center);
        memcpy(g->ell[g->n_ell + i].radii, l.ell[i].radii, sizeof l.ell[i].radii);
    }
    for (int i = 0; i < l.n_clouds; i++) {
        const cu_layer_cloud *c = &l.clouds[i];
        cu_cloud_spec *o = &g->spec[g->n_clouds + i];
        memset(o, 0, sizeof *o);
        o->first = g->n_ell + c->first;
        o->count = c->count < CU_MAX_ELLIPSOIDS ? c->count : CU_MAX_ELLIPSOIDS;
        o->has_density = o->has_boundary = o->has_wind = o->has_noise_offset = o->has_lifetime = o->has_life_phase = 1;
        o->has_wrap = 1;
        o->wrap = sl->extent;
        o->density_cm3 = s->density_cm3;
        o->boundary_m = s->boundary_m;
        o->wind[0] = sl->wind[0];
        o->wind[1] = sl->wind[1];
        for (int a = 0; a < 3; a++)
            o->noise_offset[a] = floor(seed_unit(c->seed, 1 + a) * 1000.0);
        o->lifetime = sl->lifetime;
        o->life_phase = floor(seed_unit(c->seed, 4) * 1000.0) / 1000.0; /* exact in a file (3 decimals) */
    }
    g->n_clouds = nc;
    g->n_ell = ne;
    cu_layer_free(&l);
    return 0;
}

int cu_scene_generate(const cu_scene *s, cu_generated *out, cu_error *err)
{
    memset(out, 0, sizeof *out);
    for (int i = 0; i < s->n_layers; i++)
        if (append_layer(out, s, &s->layers[i], err)) {
            cu_generated_free(out);
            return 1;
        }
    return 0;
}

int cu_scene_expand(cu_scene *s, cu_error *err)
{
    cu_generated g;
    if (cu_scene_generate(s, &g, err))
        return 1;
    int written = cu_scene_cloud_count(s);
    if (written + g.n_clouds > CU_MAX_CLOUDS || s->n_ellipsoids + g.n_ell > CU_MAX_SCENE_ELLIPSOIDS) {
        int nc = g.n_clouds, ne = g.n_ell;
        cu_generated_free(&g);
        return cu_fail(err, "%s: the layers make %d clouds of %d ellipsoids; a file holds at most %d clouds and %d "
                            "ellipsoids (lower the coverage or the extent)", s->name, nc, ne, CU_MAX_CLOUDS,
                       CU_MAX_SCENE_ELLIPSOIDS);
    }
    if (s->n_clouds == 0 && written == 1) { /* a scene built in code: make its one cloud explicit */
        s->clouds[0] = cu_scene_cloud(s, 0);
        s->n_clouds = 1;
    }
    for (int i = 0; i < g.n_clouds; i++) {
        cu_cloud_spec c = g.spec[i];
        memcpy(&s->ell[s->n_ellipsoids], &g.ell[c.first], sizeof *g.ell * (size_t)c.count);
        c.first = s->n_ellipsoids;
        s->n_ellipsoids += c.count;
        s->clouds[s->n_clouds++] = c;
    }
    s->n_layers = 0;
    cu_generated_free(&g);
    return 0;
}

