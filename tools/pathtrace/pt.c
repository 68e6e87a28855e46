/* tools/pathtrace/pt.c: the reference path tracer's integrator, phase sampler, renderer driver and density dump
 * (see pt.h and README.md for the estimators and why each choice is unbiased). */
#include "pt.h"
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

static int fail(cu_error *err, const char *fmt, const char *a)
{
    snprintf(err->msg, sizeof err->msg, fmt, a);
    return 1;
}

/* ---------------------------------------------------------------- random numbers */

uint64_t pt_splitmix64(uint64_t *x)
{
    uint64_t z = (*x += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

void pt_rng_seed(pt_rng *r, uint64_t seed, uint64_t stream)
{
    /* Two splitmix rounds decorrelate neighbouring (seed, stream) pairs before they fill the state. */
    uint64_t x = seed;
    uint64_t a = pt_splitmix64(&x);
    x = a ^ (stream * 0xd1342543de82ef95ull + 0x632be59bd9b4e019ull);
    for (int i = 0; i < 4; i++)
        r->s[i] = pt_splitmix64(&x);
    if (!(r->s[0] | r->s[1] | r->s[2] | r->s[3]))
        r->s[0] = 1; /* the all-zero state is xoshiro's only fixed point */
}

static inline uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

uint64_t pt_rng_next(pt_rng *r)
{
    uint64_t *s = r->s;
    uint64_t out = rotl(s[1] * 5, 7) * 9, t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl(s[3], 45);
    return out;
}

double pt_rng_uniform(pt_rng *r) { return (double)(pt_rng_next(r) >> 11) * 0x1.0p-53; }

/* Exponential free path with rate m; 1 - u is in (0, 1] so the log is finite. */
static inline double free_path(pt_rng *r, double m) { return -log(1.0 - pt_rng_uniform(r)) / m; }

/* ---------------------------------------------------------------- phase function */

int pt_phase_init(pt_phase *ph, const cu_phase_table *t, cu_error *err)
{
    memset(ph, 0, sizeof *ph);
    if (t->n < 2 || !t->rgb)
        return fail(err, "%s", "path tracer: empty phase table");
    ph->n = t->n;
    ph->h = CU_PI / (t->n - 1);
    ph->mono = t->peak == NULL;
    for (int c = 0; c < 3; c++) {
        ph->f[c] = malloc(sizeof(double) * (size_t)ph->n);
        ph->cdf[c] = malloc(sizeof(double) * (size_t)ph->n);
        if (!ph->f[c] || !ph->cdf[c]) {
            pt_phase_free(ph);
            return fail(err, "%s", "path tracer: out of memory");
        }
    }
    for (int c = 0; c < 3; c++) {
        /* The full phase function P = P~ + P_p: the truth the renderer's split approximates. */
        for (int i = 0; i < ph->n; i++) {
            double p = t->rgb[3 * i + c] + (t->peak ? t->peak[3 * i + c] : 0.0);
            double st = (i == 0 || i == ph->n - 1) ? 0.0 : sin(ph->h * i);
            ph->f[c][i] = 2.0 * CU_PI * st * p;
            if (ph->mono && t->rgb[3 * i + c] != t->rgb[3 * i])
                ph->mono = 0;
        }
        /* Normalise the piecewise-linear density exactly: with albedo 1 a table integrating to 1.001 would add 0.1%
         * per scattering event, i.e. tens of percent over the hundreds of events inside a cumulus. */
        double sum = 0;
        ph->cdf[c][0] = 0;
        for (int i = 0; i + 1 < ph->n; i++) {
            sum += 0.5 * ph->h * (ph->f[c][i] + ph->f[c][i + 1]);
            ph->cdf[c][i + 1] = sum;
        }
        if (!(sum > 0) || !isfinite(sum)) {
            pt_phase_free(ph);
            return fail(err, "%s", "path tracer: phase table integrates to zero");
        }
        ph->norm[c] = sum;
        for (int i = 0; i < ph->n; i++) {
            ph->f[c][i] /= sum;
            ph->cdf[c][i] /= sum;
        }
        ph->cdf[c][ph->n - 1] = 1.0;
    }
    /* The green channel's removed peak P_p as a sampling lobe for guiding toward the sun (Mie only). */
    if (t->peak) {
        ph->gf = malloc(sizeof(double) * (size_t)ph->n);
        ph->gcdf = malloc(sizeof(double) * (size_t)ph->n);
        if (!ph->gf || !ph->gcdf) {
            pt_phase_free(ph);
            return fail(err, "%s", "path tracer: out of memory");
        }
        double sum = 0;
        for (int i = 0; i < ph->n; i++)
            ph->gf[i] = (i == 0 || i == ph->n - 1) ? 0.0 : 2.0 * CU_PI * sin(ph->h * i) * t->peak[3 * i + 1];
        ph->gcdf[0] = 0;
        for (int i = 0; i + 1 < ph->n; i++) {
            sum += 0.5 * ph->h * (ph->gf[i] + ph->gf[i + 1]);
            ph->gcdf[i + 1] = sum;
        }
        if (sum > 0) {
            for (int i = 0; i < ph->n; i++) {
                ph->gf[i] /= sum;
                ph->gcdf[i] /= sum;
            }
            ph->gcdf[ph->n - 1] = 1.0;
        } else { /* no peak to guide with */
            free(ph->gf);
            free(ph->gcdf);
            ph->gf = ph->gcdf = NULL;
        }
    }
    return 0;
}

void pt_phase_free(pt_phase *ph)
{
    for (int c = 0; c < 3; c++) {
        free(ph->f[c]);
        free(ph->cdf[c]);
        ph->f[c] = ph->cdf[c] = NULL;
    }
    free(ph->gf);
    free(ph->gcdf);
    ph->gf = ph->gcdf = NULL;
}

/* The normalised density over theta (f = 2 pi sin p), linear between nodes. */
static inline double f_at(const pt_phase *ph, int c, double theta)
{
    double u = theta / ph->h;
    int i = (int)u;
    if (i < 0) i = 0;
    if (i > ph->n - 2) i = ph->n - 2;
    double a = u - i;
    a = a < 0 ? 0 : a > 1 ? 1 : a;
    return ph->f[c][i] + a * (ph->f[c][i + 1] - ph->f[c][i]);
}

double pt_phase_eval(const pt_phase *ph, int c, double theta, double sin_theta)
{
    if (sin_theta < 1e-300) {
        /* Exactly forward or backward: the limit of f / (2 pi sin) in the first or last bin (f is linear there and
         * vanishes at the end node, so the ratio tends to the next node's slope). */
        int i = theta < 0.5 * CU_PI ? 1 : ph->n - 2;
        return ph->f[c][i] / (2.0 * CU_PI * ph->h);
    }
    return f_at(ph, c, theta) / (2.0 * CU_PI * sin_theta);
}

void pt_phase_eval_dirs(const pt_phase *ph, vec3 a, vec3 b, double out[3])
{
    double st = v3_len(v3_cross(a, b)), ct = v3_dot(a, b);
    double th = atan2(st, ct); /* accurate at both ends, unlike acos */
    out[0] = pt_phase_eval(ph, 0, th, st);
    if (ph->mono) {
        out[1] = out[2] = out[0];
        return;
    }
    out[1] = pt_phase_eval(ph, 1, th, st);
    out[2] = pt_phase_eval(ph, 2, th, st);
}

/* Inverts the piecewise-linear CDF (cdf, f over n nodes of spacing h) at r in [0, 1). */
static double sample_theta(const double *cdf, const double *f, int n, double h, double r)
{
    int lo = 0, hi = n - 1; /* cdf[lo] <= r < cdf[hi] */
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (cdf[mid] <= r) lo = mid;
        else hi = mid;
    }
    /* Inside the bin f(x) = a + b x; solve a x + b x^2 / 2 = m in the cancellation-free form. */
    double m = r - cdf[lo], a = f[lo], b = (f[lo + 1] - f[lo]) / h;
    double disc = a * a + 2.0 * b * m;
    double den = a + sqrt(disc > 0 ? disc : 0);
    double x = den > 0 ? 2.0 * m / den : 0.0;
    if (x > h) x = h;
    if (x < 0) x = 0;
    return lo * h + x;
}

/* Unit vector at polar angle th and azimuth phi about the unit axis a (basis of Duff et al. 2017). */
static vec3 around(vec3 a, double th, double phi)
{
    double sign = copysign(1.0, a.z), p = -1.0 / (sign + a.z), q = a.x * a.y * p;
    vec3 t1 = v3(1.0 + sign * a.x * a.x * p, sign * q, -sign * a.x);
    vec3 t2 = v3(q, sign + a.y * a.y * p, -a.y);
    double st = sin(th), ct = cos(th);
    vec3 o = v3_add(v3_add(v3_scale(t1, st * cos(phi)), v3_scale(t2, st * sin(phi))), v3_scale(a, ct));
    return v3_norm(o); /* renormalise so rounding cannot accumulate over thousands of events */
}

/* Density (sr^-1) of the guide lobe: the green channel's diffraction peak P_p / f, centred on the sun. */
double pt_phase_peak_pdf(const pt_phase *ph, vec3 guide, vec3 dir)
{
    double st = v3_len(v3_cross(guide, dir)), th = atan2(st, v3_dot(guide, dir));
    if (th >= (ph->n - 1) * ph->h)
        return 0.0;
    double u = th / ph->h;
    int i = (int)u;
    if (i > ph->n - 2) i = ph->n - 2;
    double a = u - i, fl = ph->gf[i] + a * (ph->gf[i + 1] - ph->gf[i]);
    if (st < 1e-300)
        return th < 0.5 * CU_PI ? ph->gf[1] / (2.0 * CU_PI * ph->h) : 0.0;
    return fl / (2.0 * CU_PI * st);
}

vec3 pt_phase_sample_channel(const pt_phase *ph, vec3 d, int k, pt_rng *rng, double p[3])
{
    double th = sample_theta(ph->cdf[k], ph->f[k], ph->n, ph->h, pt_rng_uniform(rng));
    vec3 o = around(d, th, 2.0 * CU_PI * pt_rng_uniform(rng));
    double st = sin(th);
    p[0] = pt_phase_eval(ph, 0, th, st);
    if (ph->mono) {
        p[1] = p[2] = p[0];
    } else {
        p[1] = pt_phase_eval(ph, 1, th, st);
        p[2] = pt_phase_eval(ph, 2, th, st);
    }
    return o;
}

vec3 pt_phase_sample(const pt_phase *ph, vec3 d, pt_rng *rng, double w[3], double *pdf)
{
    int k = 0;
    if (!ph->mono) {
        k = (int)(3.0 * pt_rng_uniform(rng));
        if (k > 2) k = 2;
    }
    double p[3];
    vec3 o = pt_phase_sample_channel(ph, d, k, rng, p);
    double mix = (p[0] + p[1] + p[2]) / 3.0;
    for (int c = 0; c < 3; c++)
        w[c] = ph->mono ? 1.0 : mix > 0 ? p[c] / mix : 1.0;
    if (pdf)
        *pdf = ph->mono ? p[0] : mix;
    return o;
}

vec3 pt_phase_sample_peak(const pt_phase *ph, vec3 axis, pt_rng *rng)
{
    double th = sample_theta(ph->gcdf, ph->gf, ph->n, ph->h, pt_rng_uniform(rng));
    return around(axis, th, 2.0 * CU_PI * pt_rng_uniform(rng));
}

/* ---------------------------------------------------------------- context */

int pt_ctx_init(pt_ctx *c, const cu_scene *s, const char *data_dir, cu_error *err)
{
    memset(c, 0, sizeof *c);
    c->scene = *s;
    if (cu_noise_create(&c->noise, PT_NOISE_SEED))
        return fail(err, "%s", "path tracer: cannot create the noise texture (out of memory)");
    if (cu_phase_table_build(&c->table, &c->scene, data_dir, err)) {
        cu_noise_destroy(&c->noise);
        return 1;
    }
    if (pt_phase_init(&c->phase, &c->table, err)) {
        cu_phase_table_free(&c->table);
        cu_noise_destroy(&c->noise);
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

/* Delta (Woodcock) tracking: returns 1 and the position of the first real collision, 0 if the ray escapes. */
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
            if (t >= iv[i][1])
                break;
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

double pt_transmittance(const pt_ctx *c, vec3 o, vec3 d, pt_rng *rng, pt_counters *k)
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
            if (t >= iv[i][1])
                break;
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
    if (!(qb > 0) || !track(c, p, d2, rng, &p2, k))
        return;
    double T = pt_transmittance(c, p2, c->sun_dir, rng, k);
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
    for (int depth = 0;; depth++) {
        vec3 p;
        if (!track(c, o, d, rng, &p, k)) {
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
            double T = pt_transmittance(c, p, c->sun_dir, rng, k);
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

/* ---------------------------------------------------------------- rendering */

typedef struct job {
    const pt_ctx *c;
    const pt_render_opts *o;
    float *mean, *se;
    pthread_mutex_t lock;
    int next_row, rows_done;
    double t0, last_print;
    pt_counters total;
} job;

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static void progress(job *j, int final)
{
    double t = now_s(), el = t - j->t0;
    if (!final && t - j->last_print < 0.5)
        return;
    j->last_print = t;
    int H = j->o->height, done = j->rows_done, bar = 30, fill = (int)((double)bar * done / H);
    char b[64];
    for (int i = 0; i < bar; i++)
        b[i] = i < fill ? '#' : '.';
    b[bar] = 0;
    double eta = done > 0 ? el * (H - done) / done : 0;
    fprintf(stderr, "\rcumulo-pt [%s] %3d%% %d/%d rows, %.0f s elapsed, ETA %.0f s   %s", b, 100 * done / H, done, H,
            el, eta, final ? "\n" : "");
    fflush(stderr);
}

static void render_row(job *j, int y, pt_counters *k)
{
    const pt_ctx *c = j->c;
    const pt_render_opts *o = j->o;
    for (int x = 0; x < o->width; x++) {
        pt_rng rng;
        pt_rng_seed(&rng, o->seed, (uint64_t)y * (uint64_t)o->width + (uint64_t)x);
        double mean[3] = {0, 0, 0}, m2[3] = {0, 0, 0};
        for (int s = 0; s < o->spp; s++) {
            double jx = 0.5, jy = 0.5;
            if (o->aa) {
                jx = pt_rng_uniform(&rng);
                jy = pt_rng_uniform(&rng);
            }
            vec3 ro, rd;
            pt_camera_ray(c, x + jx, y + jy, &ro, &rd);
            double L[3];
            if (o->mode == PT_MODE_TRANSMITTANCE) {
                L[0] = L[1] = L[2] = pt_transmittance(c, ro, rd, &rng, k);
                k->paths++;
            } else {
                pt_radiance(c, ro, rd, &rng, L, k);
            }
            for (int i = 0; i < 3; i++) { /* Welford: stable even with the sun disk's 1e6 radiance */
                double dl = L[i] - mean[i];
                mean[i] += dl / (s + 1);
                m2[i] += dl * (L[i] - mean[i]);
            }
        }
        size_t idx = 3 * ((size_t)y * o->width + x);
        for (int i = 0; i < 3; i++) {
            j->mean[idx + i] = (float)mean[i];
            if (j->se)
                j->se[idx + i] = o->spp > 1 ? (float)sqrt(m2[i] / (o->spp - 1) / o->spp) : 0.0f;
        }
    }
}

static void *worker(void *arg)
{
    job *j = arg;
    pt_counters k = {0, 0, 0, 0};
    for (;;) {
        pthread_mutex_lock(&j->lock);
        int y = j->next_row < j->o->height ? j->next_row++ : -1;
        pthread_mutex_unlock(&j->lock);
        if (y < 0)
            break;
        render_row(j, y, &k);
        pthread_mutex_lock(&j->lock);
        j->rows_done++;
        if (j->o->progress)
            progress(j, 0);
        pthread_mutex_unlock(&j->lock);
    }
    pthread_mutex_lock(&j->lock);
    j->total.paths += k.paths;
    j->total.scatters += k.scatters;
    j->total.truncated += k.truncated;
    j->total.density_evals += k.density_evals;
    pthread_mutex_unlock(&j->lock);
    return NULL;
}

int pt_render(const pt_ctx *c, const pt_render_opts *o, float *mean, float *se, pt_counters *k, cu_error *err)
{
    if (o->width != c->width || o->height != c->height)
        return fail(err, "%s", "path tracer: render size differs from the context's camera (set it before init)");
    job j;
    memset(&j, 0, sizeof j);
    j.c = c;
    j.o = o;
    j.mean = mean;
    j.se = se;
    j.t0 = now_s();
    pthread_mutex_init(&j.lock, NULL);
    int nt = o->threads < 1 ? 1 : o->threads > 256 ? 256 : o->threads;
    pthread_t th[256];
    int started = 0;
    for (int i = 1; i < nt; i++) {
        if (pthread_create(&th[i], NULL, worker, &j) != 0)
            break;
        started = i;
    }
    worker(&j); /* the calling thread works too */
    for (int i = 1; i <= started; i++)
        pthread_join(th[i], NULL);
    if (o->progress)
        progress(&j, 1);
    pthread_mutex_destroy(&j.lock);
    if (k)
        *k = j.total;
    return 0;
}

int pt_render_scene(const cu_scene *s, const char *data_dir, const pt_render_opts *o, float *mean, float *se,
                    pt_counters *k, cu_error *err)
{
    cu_scene *sc = malloc(sizeof *sc);
    pt_ctx *c = malloc(sizeof *c);
    int rc = 1;
    if (!sc || !c) {
        fail(err, "%s", "path tracer: out of memory");
    } else {
        *sc = *s;
        sc->width = o->width;
        sc->height = o->height;
        if (pt_ctx_init(c, sc, data_dir, err) == 0) {
            rc = pt_render(c, o, mean, se, k, err);
            pt_ctx_free(c);
        }
    }
    free(c);
    free(sc);
    return rc;
}

/* ---------------------------------------------------------------- density dump */

int pt_dump_density(const pt_ctx *c, const char *path, int nx, int ny, int nz, uint32_t noise_seed, cu_error *err)
{
    const cu_cloud *cl = &c->cloud;
    if (cl->n < 1)
        return fail(err, "%s", "--dump-density: the scene has no ellipsoids");
    vec3 lo = cl->bounds_min, hi = cl->bounds_max;
    double vx = (hi.x - lo.x) / nx, vy = (hi.y - lo.y) / ny, vz = (hi.z - lo.z) / nz;
    FILE *fp = fopen(path, "wb");
    if (!fp) {
        snprintf(err->msg, sizeof err->msg, "%s: cannot write density grid: %s", path, strerror(errno));
        return 1;
    }
    unsigned char *row = malloc(4 * (size_t)nx);
    if (!row) {
        fclose(fp);
        return fail(err, "%s", "--dump-density: out of memory");
    }
    int ok = 1;
    for (int z = 0; z < nz && ok; z++)
        for (int y = 0; y < ny && ok; y++) {
            for (int x = 0; x < nx; x++) {
                vec3 p = v3(lo.x + (x + 0.5) * vx, lo.y + (y + 0.5) * vy, lo.z + (z + 0.5) * vz);
                float v = (float)cu_cloud_extinction(cl, p);
                uint32_t u;
                memcpy(&u, &v, 4);
                for (int b = 0; b < 4; b++) /* little-endian on any host */
                    row[4 * x + b] = (unsigned char)(u >> (8 * b));
            }
            ok = fwrite(row, 4, (size_t)nx, fp) == (size_t)nx;
        }
    free(row);
    if (fclose(fp) != 0 || !ok) {
        snprintf(err->msg, sizeof err->msg, "%s: write failed", path);
        return 1;
    }
    char hp[1200];
    snprintf(hp, sizeof hp, "%s.txt", path);
    fp = fopen(hp, "w");
    if (!fp) {
        snprintf(err->msg, sizeof err->msg, "%.400s: cannot write density header: %s", hp, strerror(errno));
        return 1;
    }
    const cu_scene *s = &c->scene;
    const char *base = strrchr(path, '/');
    fprintf(fp, "# cumulo-pt density grid: extinction k_e the path tracer used, sampled at voxel centres\n");
    fprintf(fp, "# voxel (i,j,k) centre, world metres = origin + ((i+0.5)*voxel_x, (j+0.5)*voxel_y, (k+0.5)*voxel_z)\n");
    fprintf(fp, "file %s\n", base ? base + 1 : path);
    fprintf(fp, "format float32 little-endian raw, x fastest, then y, then z\n");
    fprintf(fp, "dims %d %d %d\n", nx, ny, nz);
    fprintf(fp, "origin_m %.9g %.9g %.9g\n", lo.x + cl->origin.x, lo.y + cl->origin.y, lo.z + cl->origin.z);
    fprintf(fp, "voxel_m %.9g %.9g %.9g\n", vx, vy, vz);
    fprintf(fp, "units k_e m^-1\n");
    fprintf(fp, "scene %s\n", s->name);
    fprintf(fp, "noise_seed %u\n", (unsigned)noise_seed);
    fprintf(fp, "core_extinction_m-1 %.9g\n", cl->ke);
    fprintf(fp, "cloud_origin_m %.9g %.9g %.9g\n", cl->origin.x, cl->origin.y, cl->origin.z);
    fprintf(fp, "boundary_m %.9g\nnoise %s\nnoise_scale %.9g\nnoise_octaves %d\nprofile %s\n", cl->h,
            cl->noise_on ? "on" : "off", s->noise_scale, cl->octaves, cl->profile == CU_PROFILE_KOL ? "kol" : "tapered");
    fclose(fp);
    return 0;
}
