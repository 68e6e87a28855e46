/* tools/pathtrace/pt.c: the reference path tracer's context and integrator: delta and ratio tracking through the
 * clouds, next-event estimation, the environment (see pt.h and README.md for why each estimator is unbiased). */
#include "pt.h"
#include "error.h"
#include <errno.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* Sun disk as the sky shader draws it: cos(0.2666 deg) and 6.8e-5 sr. */
#define PT_SUN_COS 0.99998917
#define PT_SUN_SR 6.8e-5
/* Ratio tracking plays Russian roulette below this transmittance (survive with p = T / RR_T, then T = RR_T): the
 * expectation is unchanged, and deep inside the cloud a shadow ray stops after a few steps instead of hundreds. */
#ifndef PT_RR_T
#define PT_RR_T 0.1
#endif



/* Exponential free path with rate m; 1 - u is in (0, 1] so the log is finite. */
static inline double free_path(pt_rng *r, double m) { return -log(1.0 - pt_rng_uniform(r)) / m; }


int pt_ctx_init(pt_ctx *c, const cu_scene *s, const char *data_dir, cu_error *err)
{
    memset(c, 0, sizeof *c);
    if (cu_noise_create(&c->noise, PT_NOISE_SEED))
        return cu_fail(err, "%s", "path tracer: cannot create the noise texture (out of memory)");
    if (pt_ctx_set_scene(c, s, data_dir, err)) {
        cu_noise_destroy(&c->noise);
        return 1;
    }
    return 0;
}

int pt_ctx_set_scene(pt_ctx *c, const cu_scene *s, const char *data_dir, cu_error *err)
{
    /* One written cloud or a clear sky: a field of clouds needs a union of media this tracer does not have yet. */
    if (cu_scene_cloud_count(s) > 1 || s->n_layers > 0)
        return cu_fail(err, "%s: the path tracer renders one cloud; this scene has %d written clouds and %d [layer]s",
                       s->name, cu_scene_cloud_count(s), s->n_layers);
    pt_phase_free(&c->phase);
    cu_phase_table_free(&c->table);
    c->scene = *s;
    if (cu_phase_table_build(&c->table, &c->scene, data_dir, err))
        return 1;
    if (pt_phase_init(&c->phase, &c->table, err)) {
        cu_phase_table_free(&c->table);
        return 1;
    }
    cu_cloud_build(&c->cloud, &c->scene, &c->noise);
    c->cloud.ke = cu_phase_table_extinction(&c->table, &c->scene); /* exactly as the renderer */
    c->medium = PT_MEDIUM_CLOUD;
    c->majorant = c->cloud.ke; /* the sigmoid is clamped to [0,1], so k_e(p) <= ke everywhere */
    cu_sky_compute(&c->sky, &c->scene);
    c->sun_dir = c->sky.sun_dir;
    for (int i = 0; i < 3; i++)
        c->sun_irr[i] = c->sky.sun_irradiance[i];
    c->env = PT_ENV_SCENE;
    c->max_depth = 1000000;
    c->max_steps = PT_MAX_STEPS;
    c->guide = PT_GUIDE_DEFAULT;
    c->cam = v3_sub(v3_from(s->cam_pos), c->cloud.origin);
    vec3 dir = v3_norm(v3_sub(v3_from(s->cam_look), v3_from(s->cam_pos)));
    c->width = s->width;
    c->height = s->height;
    mat4 proj = m4_perspective(s->cam_fov * CU_PI / 180.0, (double)s->width / s->height, 1.0, 2.0);
    c->inv_rot = m4_inverse(m4_mul(proj, m4_look_dir(v3(0, 0, 0), dir, v3(0, 1, 0))));
    return 0;
}

void pt_ctx_free(pt_ctx *c)
{
    pt_phase_free(&c->phase);
    cu_phase_table_free(&c->table);
    cu_noise_destroy(&c->noise);
}

void pt_ctx_use_slab(pt_ctx *c, double tau)
{
    c->medium = PT_MEDIUM_SLAB;
    c->slab_thickness = 1000.0;
    c->slab_ke = tau / c->slab_thickness;
    c->majorant = c->slab_ke;
}

/* ---------------------------------------------------------------- medium */

double pt_extinction(const pt_ctx *c, vec3 p)
{
    if (c->medium == PT_MEDIUM_SLAB)
        return (p.y <= 0 && p.y >= -c->slab_thickness) ? c->slab_ke : 0.0;
    return cu_cloud_extinction(&c->cloud, p);
}

/* Sorted, merged parameter intervals [t0, t1] with t >= 0 outside which the extinction is zero. Returns the count. */
static int intervals(const pt_ctx *c, vec3 o, vec3 d, double iv[][2])
{
    if (c->medium == PT_MEDIUM_SLAB) {
        double top = 0.0, bot = -c->slab_thickness;
        if (d.y == 0) {
            if (o.y > top || o.y < bot)
                return 0;
            iv[0][0] = 0;
            iv[0][1] = INFINITY;
            return 1;
        }
        double ta = (top - o.y) / d.y, tb = (bot - o.y) / d.y;
        double t0 = fmax(fmin(ta, tb), 0.0), t1 = fmax(ta, tb);
        if (!(t1 > t0))
            return 0;
        iv[0][0] = t0;
        iv[0][1] = t1;
        return 1;
    }
    int n = 0;
    for (int i = 0; i < c->cloud.n; i++) {
        double t0, t1;
        if (!cu_ray_ellipsoid(o, d, c->cloud.c[i], c->cloud.r[i], &t0, &t1) || t1 <= 0)
            continue;
        if (t0 < 0) t0 = 0;
        /* insertion sort by entry: n <= 64 */
        int j = n++;
        while (j > 0 && iv[j - 1][0] > t0) {
            iv[j][0] = iv[j - 1][0];
            iv[j][1] = iv[j - 1][1];
            j--;
        }
        iv[j][0] = t0;
        iv[j][1] = t1;
    }
    int m = 0;
    for (int i = 0; i < n; i++) {
        if (m > 0 && iv[i][0] <= iv[m - 1][1]) {
            if (iv[i][1] > iv[m - 1][1]) iv[m - 1][1] = iv[i][1];
        } else {
            iv[m][0] = iv[i][0];
            iv[m][1] = iv[i][1];
            m++;
        }
    }
    return m;
}

/* One more tracking step of the current path; 0 once the path has used up max_steps (it is then cut). */
static int step(const pt_ctx *c, pt_counters *k)
{
    return ++k->path_steps <= c->max_steps;
}

/* Delta (Woodcock) tracking: returns 1 and the position of the first real collision, 0 if the ray escapes, -1 if
 * the path ran out of steps. */
static int track(const pt_ctx *c, vec3 o, vec3 d, pt_rng *rng, vec3 *hit, pt_counters *k)
{
    if (!(c->majorant > 0))
        return 0;
    double iv[CU_MAX_ELLIPSOIDS][2];
    int n = intervals(c, o, d, iv);
    for (int i = 0; i < n; i++) {
        /* Free paths are memoryless, so restarting at each interval's entry is exact. */
        double t = iv[i][0];
        for (;;) {
            t += free_path(rng, c->majorant);
            if (!(t < iv[i][1])) /* also ends a NaN interval, which cu_ray_ellipsoid no longer makes */
                break;
            if (!step(c, k))
                return -1;
            vec3 p = v3_add(o, v3_scale(d, t));
            double ke = pt_extinction(c, p);
            k->density_evals++;
            if (pt_rng_uniform(rng) * c->majorant < ke) {
                *hit = p;
                return 1;
            }
        }
    }
    return 0;
}

/* Ratio tracking to infinity; -1 if the path ran out of steps. */
static double transmittance(const pt_ctx *c, vec3 o, vec3 d, pt_rng *rng, pt_counters *k)
{
    if (!(c->majorant > 0))
        return 1.0;
    double iv[CU_MAX_ELLIPSOIDS][2];
    int n = intervals(c, o, d, iv);
    double T = 1.0;
    for (int i = 0; i < n; i++) {
        double t = iv[i][0];
        for (;;) {
            t += free_path(rng, c->majorant);
            if (!(t < iv[i][1]))
                break;
            if (!step(c, k))
                return -1.0;
            double ke = pt_extinction(c, v3_add(o, v3_scale(d, t)));
            k->density_evals++;
            T *= 1.0 - ke / c->majorant; /* ratio tracking (Novak et al. 2014) */
            if (T <= 0)
                return 0.0;
            if (T < PT_RR_T) {
                if (pt_rng_uniform(rng) * PT_RR_T >= T)
                    return 0.0;
                T = PT_RR_T;
            }
        }
    }
    return T;
}

double pt_transmittance(const pt_ctx *c, vec3 o, vec3 d, pt_rng *rng, pt_counters *k)
{
    k->path_steps = 0;
    double T = transmittance(c, o, d, rng, k);
    if (T < 0)
        k->step_capped++;
    return T < 0 ? 0.0 : T;
}

/* Radiance of the environment seen along d; the sun disk only for rays from the camera (scattered paths see the
 * sun through next-event estimation, so counting the disk again would count it twice). */
static void environment(const pt_ctx *c, vec3 d, int camera_ray, double out[3])
{
    if (c->env == PT_ENV_HEMISPHERES) {
        for (int i = 0; i < 3; i++)
            out[i] = d.y > 0 ? c->env_up[i] : c->env_down[i];
        return;
    }
    const cu_scene *s = &c->scene;
    int above = 1;
    if (s->sky_model == CU_SKY_CONSTANT) {
        for (int i = 0; i < 3; i++)
            out[i] = s->sky_color[i];
    } else if (d.y < 0) {
        above = 0; /* no ground geometry: the sky shader's Lambertian ground radiance */
        for (int i = 0; i < 3; i++)
            out[i] = c->sky.ground[i];
    } else {
        cu_sky_radiance(&c->sky, s, d, out);
    }
    if (camera_ray && above && v3_dot(d, c->sun_dir) > PT_SUN_COS)
        for (int i = 0; i < 3; i++)
            out[i] += c->sun_irr[i] / PT_SUN_SR;
}

/* Colour: hero-channel spectral MIS (Wilkie et al. 2014) at the level of whole paths. A path samples every direction
 * from the phase function of one channel k (its hero, uniform among R, G, B); channel c's contribution is
 * f_c / ((1/3) sum_j pdf_j), pdf_j being the path's density had channel j been the hero. R[j] holds prod p_j / prod
 * p_k over the events so far (rescaled now and then: only ratios matter), so the weight of channel c is
 * R[c] / mean(R): at most 3 for a whole path. Per-event MIS would multiply weights up to 3 per event and turn the
 * Mie peak's channel differences (p(0) = 186, 226, 320 sr^-1) into coloured fireflies after a few forward events. */
static void spectral_weights(const double R[3], int mono, double beta[3])
{
    if (mono) { /* identical channels: exactly 1, as the furnace test requires */
        beta[0] = beta[1] = beta[2] = 1.0;
        return;
    }
    double m = (R[0] + R[1] + R[2]) / 3.0;
    for (int i = 0; i < 3; i++)
        beta[i] = m > 0 ? R[i] / m : 0.0;
}

/* Strategy B of the sun's forward-peak MIS (README "Variance: the forward peak"): from vertex p with incoming
 * direction d, pick a direction in the sun's diffraction lobe, track to the next collision and take the sun there.
 * The balance heuristic runs over all strategies (hero j x {continuation A, lobe B}), so the denominator is
 * (1/3) sum_j R[j] (p_j(d.d2) + guide * G(d2)); B runs with probability guide, which its density includes. */
static void peak_nee(const pt_ctx *c, vec3 p, vec3 d, const double R[3], pt_rng *rng, double L[3], pt_counters *k)
{
    const pt_phase *ph = &c->phase;
    vec3 d2 = pt_phase_sample_peak(ph, c->sun_dir, rng);
    double qb = c->guide * pt_phase_peak_pdf(ph, c->sun_dir, d2);
    double pa[3];
    pt_phase_eval_dirs(ph, d, d2, pa);
    vec3 p2;
    if (!(qb > 0) || track(c, p, d2, rng, &p2, k) != 1)
        return; /* a miss, or out of steps (pt_radiance sees that and cuts the path) */
    double T = transmittance(c, p2, c->sun_dir, rng, k);
    if (!(T > 0))
        return;
    double ps[3];
    pt_phase_eval_dirs(ph, c->sun_dir, d2, ps);
    double den = (R[0] * (pa[0] + qb) + R[1] * (pa[1] + qb) + R[2] * (pa[2] + qb)) / 3.0;
    if (!(den > 0))
        return;
    for (int i = 0; i < 3; i++)
        L[i] += R[i] * pa[i] / den * ps[i] * c->sun_irr[i] * T;
}

void pt_radiance(const pt_ctx *c, vec3 o, vec3 d, pt_rng *rng, double L[3], pt_counters *k)
{
    const pt_phase *ph = &c->phase;
    double R[3] = {1, 1, 1}, beta[3] = {1, 1, 1};
    L[0] = L[1] = L[2] = 0;
    int sun = c->env == PT_ENV_SCENE && (c->sun_irr[0] > 0 || c->sun_irr[1] > 0 || c->sun_irr[2] > 0);
    int peak = sun && ph->gf && c->guide > 0;
    int hero = 0;
    if (!ph->mono) {
        hero = (int)(3.0 * pt_rng_uniform(rng));
        if (hero > 2) hero = 2;
    }
    double nee_w = 1.0; /* MIS weight of this vertex's sun NEE against strategy B; 1 for the camera ray */
    k->paths++;
    k->path_steps = 0;
    for (int depth = 0;; depth++) {
        vec3 p;
        int hit = track(c, o, d, rng, &p, k);
        if (hit < 0 || k->path_steps > c->max_steps) { /* out of steps: cut, as at max_depth (biased low) */
            k->step_capped++;
            return;
        }
        if (!hit) {
            double e[3];
            environment(c, d, depth == 0, e);
            for (int i = 0; i < 3; i++)
                L[i] += beta[i] * e[i];
            return;
        }
        if (depth >= c->max_depth) {
            k->truncated++;
            return;
        }
        k->scatters++;
        if (sun) {
            /* Next-event estimation: sunlight propagating along -sun_dir is scattered into -d (back toward the
             * previous vertex), so cos(theta) = (-sun_dir).(-d) = sun_dir.d (DESIGN: cos = s_L . v). */
            double ph3[3];
            pt_phase_eval_dirs(ph, c->sun_dir, d, ph3);
            double T = transmittance(c, p, c->sun_dir, rng, k);
            if (T > 0)
                for (int i = 0; i < 3; i++)
                    L[i] += nee_w * beta[i] * ph3[i] * c->sun_irr[i] * T;
        }
        /* Strategy B adds the event after this one, so it respects max_depth like the continuation does. */
        if (peak && depth + 1 < c->max_depth && pt_rng_uniform(rng) < c->guide)
            peak_nee(c, p, d, R, rng, L, k);
        double pc[3];
        d = pt_phase_sample_channel(ph, d, hero, rng, pc);
        if (peak) { /* the share strategy A keeps of the next vertex's sun NEE (balance heuristic) */
            double qb = c->guide * pt_phase_peak_pdf(ph, c->sun_dir, d);
            double da = R[0] * pc[0] + R[1] * pc[1] + R[2] * pc[2], db = qb * (R[0] + R[1] + R[2]);
            nee_w = da > 0 ? da / (da + db) : 0.0;
        }
        if (!ph->mono) {
            double mx = 0;
            for (int i = 0; i < 3; i++) {
                R[i] *= pc[i];
                mx = fmax(mx, R[i]);
            }
            if (!(mx > 0)) /* cannot happen: the hero's own density is positive where it sampled */
                return;
            for (int i = 0; i < 3; i++)
                R[i] /= mx; /* only ratios matter; keeps them in range over any number of events */
        }
        spectral_weights(R, ph->mono, beta);
        o = p;
    }
}

void pt_camera_ray(const pt_ctx *c, double px, double py, vec3 *o, vec3 *d)
{
    double nx = px / c->width * 2.0 - 1.0, ny = 1.0 - py / c->height * 2.0;
    const double *m = c->inv_rot.m;
    double w[4];
    for (int i = 0; i < 4; i++)
        w[i] = m[i] * nx + m[4 + i] * ny + m[8 + i] + m[12 + i];
    *o = c->cam;
    *d = v3_norm(v3(w[0] / w[3], w[1] / w[3], w[2] / w[3]));
}

