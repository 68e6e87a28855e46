/* tools/pathtrace/pt_sample.c: the path tracer's random numbers (xoshiro256**) and its phase function: evaluation
 * of the tabulated channels and importance sampling of the chopped peak and the rest (see pt.h). */
#include "pt.h"
#include "error.h"
#include <stdlib.h>
#include <string.h>

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
/* ---------------------------------------------------------------- phase function */

int pt_phase_init(pt_phase *ph, const cu_phase_table *t, cu_error *err)
{
    memset(ph, 0, sizeof *ph);
    if (t->n < 2 || !t->rgb)
        return cu_fail(err, "%s", "path tracer: empty phase table");
    ph->n = t->n;
    ph->h = CU_PI / (t->n - 1);
    ph->mono = t->peak == NULL;
    for (int c = 0; c < 3; c++) {
        ph->f[c] = malloc(sizeof(double) * (size_t)ph->n);
        ph->cdf[c] = malloc(sizeof(double) * (size_t)ph->n);
        if (!ph->f[c] || !ph->cdf[c]) {
            pt_phase_free(ph);
            return cu_fail(err, "%s", "path tracer: out of memory");
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
            return cu_fail(err, "%s", "path tracer: phase table integrates to zero");
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
            return cu_fail(err, "%s", "path tracer: out of memory");
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
