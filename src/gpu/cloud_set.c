/* src/gpu/cloud_set.c: the renderer's clouds (see cloud_set.h): written ones from the scene, generated ones from its
 * [layer]s, and where each is and how dense at a scene time. */
#include "cloud_set.h"
#include "error.h"
#include "scene_layers.h"
#include <stdlib.h>
#include <string.h>

int cu_cloud_set_build(cu_cloud_set *cs, const cu_scene *s, const cu_noise *noise, cu_error *err)
{
    memset(cs, 0, sizeof *cs);
    cs->num_ell = 1;
    int written = cu_scene_cloud_count(s), cap = written > 0 ? written : 1;
    cs->slot = calloc((size_t)cap, sizeof *cs->slot);
    if (!cs->slot)
        return cu_fail(err, "clouds: out of memory");
    for (int i = 0; i < written; i++) {
        cu_cloud_spec c = cu_scene_cloud(s, i);
        cu_cloud_slot *sl = &cs->slot[cs->n++];
        cu_cloud_build_spec(&sl->cloud, s, &c, noise);
        sl->wind = v3(c.wind[0], 0, -c.wind[1]); /* east, north -> x, -z */
        sl->lifetime = c.lifetime;
        sl->life_phase = c.life_phase;
        sl->wrap = c.wrap;
        if (c.count > cs->num_ell)
            cs->num_ell = c.count;
    }
    cu_generated g;
    if (cu_scene_generate(s, &g, err)) {
        free(cs->slot);
        memset(cs, 0, sizeof *cs);
        return 1;
    }
    if (g.n_clouds > 0) {
        cu_cloud_slot *ns = realloc(cs->slot, sizeof *ns * (size_t)(cs->n + g.n_clouds));
        if (!ns) {
            cu_generated_free(&g);
            free(cs->slot);
            memset(cs, 0, sizeof *cs);
            return cu_fail(err, "[layer]: out of memory for %d clouds", g.n_clouds);
        }
        cs->slot = ns;
    }
    for (int i = 0; i < g.n_clouds; i++) {
        const cu_cloud_spec *c = &g.spec[i];
        cu_cloud_slot *sl = &cs->slot[cs->n++];
        memset(sl, 0, sizeof *sl);
        cu_cloud_build_ellipsoids(&sl->cloud, s, &g.ell[c->first], c->count, c->density_cm3, c->boundary_m,
                                  c->noise_offset, noise);
        sl->wind = v3(c->wind[0], 0, -c->wind[1]);
        sl->wrap = c->wrap;
        sl->lifetime = c->lifetime;
        sl->life_phase = c->life_phase;
        if (c->count > cs->num_ell)
            cs->num_ell = c->count;
    }
    cu_generated_free(&g);
    cs->boil = s->boil;
    for (int i = 0; i < cs->n; i++) {
        cu_cloud_slot *sl = &cs->slot[i];
        sl->rest = sl->cloud.origin;
        sl->ke_rest = sl->cloud.ke;
        for (int e = 0; e < sl->cloud.n; e++) {
            vec3 c = sl->cloud.c[e], r = sl->cloud.r[e];
            sl->radius_xz = fmax(sl->radius_xz, sqrt(c.x * c.x + c.z * c.z) + fmax(r.x, r.z));
        }
        sl->noise_rest = sl->cloud.noise_offset;
        sl->factor = 1;
    }
    cu_cloud_set_at_time(cs, s->time);
    return 0;
}

void cu_cloud_slot_free_maps(cu_cloud_slot *sl, const cu_gl *gl)
{
    cu_target_delete(&sl->sun_map, gl);
    cu_target_delete(&sl->slab_map[0], gl);
    cu_target_delete(&sl->slab_map[1], gl);
    cu_target_delete(&sl->next_sun_map, gl);
    cu_target_delete(&sl->next_slab_map[0], gl);
    cu_target_delete(&sl->next_slab_map[1], gl);
    cu_target_delete(&sl->shadow, gl);
    sl->maps_valid = sl->zenith_valid = 0;
    sl->next_band = 0;
    sl->has_shadow = 0;
    sl->shadow_sig = 0;
}

void cu_cloud_set_free(cu_cloud_set *cs, const cu_gl *gl)
{
    for (int i = 0; i < cs->n; i++)
        cu_pass_msd_free(&cs->slot[i].msd, gl);
    for (int i = 0; gl && i < cs->n; i++) {
        cu_cloud_slot *sl = &cs->slot[i];
        if (sl->vao)
            gl->DeleteVertexArrays(1, &sl->vao);
        if (sl->inst_vbo)
            gl->DeleteBuffers(1, &sl->inst_vbo);
        cu_cloud_slot_free_maps(sl, gl);
        cu_impostor_free(&sl->imp, gl);
    }
    free(cs->slot);
    memset(cs, 0, sizeof *cs);
}

static double smooth01(double x)
{
    x = x < 0 ? 0 : x > 1 ? 1 : x;
    return x * x * (3 - 2 * x);
}

double cu_cloud_life(double t, double lifetime, double phase, int *cycle)
{
    if (cycle)
        *cycle = 0;
    if (!(lifetime > 0))
        return 1.0;
    double u = t / lifetime + phase, k = floor(u), f = u - k;
    if (cycle)
        *cycle = (int)fmod(k, 1e6);
    /* forms over the first fifth, dissolves over the last: smoothstep ramps, 0 with zero slope at the ends */
    return smooth01(f / 0.2) * smooth01((1.0 - f) / 0.2);
}

double cu_cloud_fade_density(double r, double tau0)
{
    if (!(r > 0))
        return 0;
    if (r >= 1)
        return 1;
    /* The density at which a chord of optical depth tau0 has the opacity r (1 - e^-tau0): -ln(1 - r (1 - e^-tau0))
     * / tau0 (log1p and expm1 keep both ends' digits). tau0 is capped at 4: matched to a cloud's full optical depth
     * (90 for a 1 km cumulus) the density would sit near 0.1 at 99.9 % of the opacity and then leap to 1 at the end of
     * the ramp, and the light inside a cloud follows its density, not only its opacity (measured: a 6x-median jump in
     * the ten-minute run of tests/gpu/test_sky_field.c). */
    tau0 = tau0 < 4.0 ? tau0 : 4.0;
    if (!(tau0 > 1e-6))
        return r;
    return -log1p(r * expm1(-tau0)) / tau0;
}

double cu_cloud_border_fade(vec3 p, double wrap, double w)
{
    if (!(wrap > 0))
        return 1.0;
    double half = 0.5 * wrap, d = fmin(half - fabs(p.x), half - fabs(p.z));
    return w > 0 ? smooth01(d / w) : 1.0;
}

/* x wrapped into [-half, half) */
static double wrap_coord(double x, double wrap)
{
    return x - wrap * floor(x / wrap + 0.5);
}

void cu_cloud_set_at_time(cu_cloud_set *cs, double t)
{
    for (int i = 0; i < cs->n; i++) {
        cu_cloud_slot *sl = &cs->slot[i];
        vec3 p = v3_add(sl->rest, v3_scale(sl->wind, t));
        double fade = 1;
        if (sl->wrap > 0) {
            /* about the set's centre: the layer is a torus, so any square of its side shows all of it once */
            p.x = wrap_coord(p.x - cs->wrap_cx, sl->wrap);
            p.z = wrap_coord(p.z - cs->wrap_cz, sl->wrap);
            /* Kol fades clouds by the distance to the sky dome; a wrapping layer fades them out before its border
             * and in after it, over at least the cloud's size, so a cloud crossing it never pops. */
            double w = fmax(2.0 * sl->cloud.bound_radius, 0.05 * sl->wrap);
            fade = cu_cloud_border_fade(p, sl->wrap, fmin(w, 0.25 * sl->wrap));
            p.x += cs->wrap_cx;
            p.z += cs->wrap_cz;
        }
        int cycle;
        double life = cu_cloud_life(t, sl->lifetime, sl->life_phase, &cycle);
        sl->cloud.origin = p;
        sl->factor = cu_cloud_fade_density(fade * life, sl->ke_rest * sl->cloud.bound_radius);
        if (cycle != sl->cycle) { /* a new life looks like a new cloud: another part of the noise */
            sl->cycle = cycle;
            sl->maps_valid = 0;
            sl->zenith_valid = 0;
        }
        /* The boil (after Schpok et al., Kol 3.4.7): the noise drifts through the cloud at cs->boil m/s, rising a
         * little and turning once in ten minutes, so the edges evolve while the cloud keeps its shape. */
        double w = 2.0 * 3.14159265358979 / 600.0, ph = 6.2831853 * sl->life_phase, v = cs->boil;
        sl->boil = v3(v / w * (sin(w * t + ph) - sin(ph)), 0.3 * v * t, -v / w * (cos(w * t + ph) - cos(ph)));
        double g = (double)cycle, fq = sl->cloud.noise_freq;
        vec3 o = v3_add(v3_add(sl->noise_rest, v3(0.6180339887 * g, 0.4142135624 * g, 0.7320508076 * g)),
                        v3_scale(sl->boil, fq));
        sl->cloud.noise_offset = v3(o.x - floor(o.x), o.y - floor(o.y), o.z - floor(o.z));
    }
}
