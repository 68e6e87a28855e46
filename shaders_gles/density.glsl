// shaders_gles/density.glsl: the cloud's extinction field (Kol eqs. 3.1-3.2, 3.74) and the ray's chords through the
// ellipsoids, shared by the cloud pass and the sun opacity pass so both integrate the same density. No #version:
// the loader inserts it (see gl.c). Needs NUM_ELL, NOISE, NOISE_OCTAVES, PROFILE_KOL.
precision highp float;
precision highp int;
precision highp sampler3D;
precision highp sampler2D;

uniform vec4 u_ell_c[NUM_ELL]; // centres, cloud-local
uniform vec4 u_ell_ir[NUM_ELL];// 1 / radii
uniform float u_ke;            // core extinction, m^-1
uniform float u_h;             // boundary thickness, m
uniform float u_noise_freq;    // texture tiles per metre
uniform vec3 u_noise_offset;
uniform float u_noise_mean[5]; // mean of each mip level, stands in for octaves that are switched off
uniform sampler3D u_noise;

const float PI = 3.14159265358979;

float sample_level(vec3 t, int level)
{
    return textureLod(u_noise, t, float(level)).r;
}

// Kol eq. 3.74: five LODs at p and at 8p, each sum minus 0.75, clamped to [0,1], mapped to [-1,1]. NOISE_BAKED
// (quality.noise_baked): u_noise holds the octaves' weighted sum in one level (src/core/noise.c: cu_noise_bake), read
// at p and 8p.
#ifndef NOISE_BAKED
#define NOISE_BAKED 0
#endif
float fractal_noise(vec3 p)
{
    vec3 t = p * u_noise_freq + u_noise_offset;
#if NOISE_BAKED
    float a = textureLod(u_noise, t, 0.0).r + textureLod(u_noise, 8.0 * t, 0.0).r - 1.5;
#else
    float a = -1.5;
    const float w[5] = float[5](0.015, 0.035, 0.1, 0.35, 1.5);
    for (int L = 0; L < 5; L++) {
        if (L < 5 - NOISE_OCTAVES) {
            a += 2.0 * w[L] * u_noise_mean[L];
        } else {
            a += w[L] * (sample_level(t, L) + sample_level(8.0 * t, L));
        }
    }
#endif
    return clamp(a, 0.0, 1.0) * 2.0 - 1.0;
}

// Kol's radial signed distance (positive inside): d = |q| (1/s - 1) with s = |q / r|. Finite at the centre.
float radial_distance(vec3 p, int i)
{
    vec3 q = p - u_ell_c[i].xyz;
    float len = length(q);
    float s = length(q * u_ell_ir[i].xyz);
    if (s < 1e-6) {
        vec3 r = 1.0 / u_ell_ir[i].xyz;
        return min(r.x, min(r.y, r.z));
    }
    return len / s - len;
}

float sigmoid(float x)
{
    x = clamp(x, 0.0, 1.0);
    return x * x * x * (x * (x * 6.0 - 15.0) + 10.0);
}

// Chords of the ray through each ellipsoid it hits, sorted by entry.
int n_hits;
int hit_idx[NUM_ELL];
float hit_t0[NUM_ELL], hit_t1[NUM_ELL];

// Extinction at signed distance d from the union's surface (positive inside): the core, the noisy boundary, air.
float extinction_at_distance(vec3 p, float d)
{
    if (d <= 0.0)
        return 0.0;
    if (d >= u_h)
        return u_ke;
    float u = d / u_h;
#if NOISE
    float n = fractal_noise(p);
#else
    float n = 0.0;
#endif
#if PROFILE_KOL
    return u_ke * sigmoid(u + n);                       // eq. 3.1 as printed
#else
    return u_ke * sigmoid(u + 4.0 * u * (1.0 - u) * n);  // noise tapered to 0 at both borders: continuous density
#endif
}

// Extinction at p = ray(t): the distance to the union is the max over ellipsoids, and only ellipsoids whose chord
// contains t can be non-negative there, so the loop runs over the hit list, skipping chords that end before t.
float extinction(vec3 p, float t)
{
    float d = -1e30;
    for (int k = 0; k < n_hits; k++) {
        if (t >= hit_t0[k] - 1e-3 && t <= hit_t1[k] + 1e-3) {
            d = max(d, radial_distance(p, hit_idx[k]));
            if (d >= u_h)
                break; // the core: the union's distance can only grow, and the core's extinction is u_ke whatever it is
        }
    }
    return extinction_at_distance(p, d);
}

#if defined(METHOD_UNIFORM) && METHOD_UNIFORM
// Extinction anywhere, not only on the cast ray's chords: the uniform march's steps toward the sun leave the ray.
float extinction_anywhere(vec3 p)
{
    float d = -1e30;
    for (int i = 0; i < NUM_ELL; i++)
        d = max(d, radial_distance(p, i));
    return extinction_at_distance(p, d);
}
#endif

// Knots of the quadrature over an in-cloud interval [a, a + len] with n segments. The boundary ramps (density rising
// over h at each end) get segments of their own, in proportion to their length but at least one: the ramp/core
// border is then a knot, and with a thin boundary its one trapezoid is exact for the symmetric sigmoid, where a long
// segment from the surface into the core would take the rise for a linear one over the whole segment. With a thick
// noisy boundary the ramps keep their share of the samples (the noise lives there).
// Exact along the normal of a lone ellipsoid; along oblique rays the ramp is longer and the core's first segments
// see the rest of it (cloud.frag's core_entry measures the entry ramp along the ray instead). The core's segments
// grow geometrically by r (1: uniform). The entry ramp (length rl_in, nr_in segments) and the exit ramp (rl_out,
// nr_out) are apart: a view ray sees its entry ramp, the exit one only through the core.
struct knots {
    float a, len, rl_in, rl_out, r;
    int nr_in, nr_out, nc;
};

knots make_knots(float a, float len, float nudge, int n, float r, bool allow_ramps)
{
    knots k;
    k.a = a; k.len = len; k.r = r;
    bool ramps = allow_ramps && u_h > 2.0 * nudge && 2.0 * u_h < 0.5 * len;
    k.rl_in = k.rl_out = ramps ? u_h : 0.0;
    k.nr_in = k.nr_out = ramps ? max(1, int(floor(float(n) * u_h / len + 0.5))) : 0;
    k.nc = max(1, n - 2 * k.nr_in);
    return k;
}

// A chord that never reaches the core (a silhouette, a grazing rim): all of it is noisy boundary, where Kol's few
// geometric segments alias the noise (their long last segments step over its 30 m features: the blocky rims). Even
// knots at most `step` apart, at least n, at most BOUNDARY_KNOTS_MAX.
#define BOUNDARY_KNOTS_MAX 32
#define RAMP_KNOTS_MAX 16 // quality.ramp_step's most knots in an entry ramp (cloud.frag)
knots boundary_knots(float a, float len, int n, float step)
{
    knots k;
    k.a = a; k.len = len; k.r = 1.0; k.rl_in = k.rl_out = 0.0; k.nr_in = k.nr_out = 0;
    k.nc = clamp(int(ceil(len / step)), n, BOUNDARY_KNOTS_MAX);
    return k;
}

int knot_count(knots k)
{
    return k.nc + k.nr_in + k.nr_out;
}

// Knot i, the core's at fraction f of its length (the boundary ramps' knots need none).
float knot_at(knots k, int i, float f)
{
    int n = knot_count(k);
    if (k.nr_in > 0 && i <= k.nr_in)
        return k.a + k.rl_in * float(i) / float(k.nr_in);
    if (k.nr_out > 0 && i >= n - k.nr_out)
        return k.a + k.len - k.rl_out * float(n - i) / float(k.nr_out);
    float core = k.len - k.rl_in - k.rl_out;
    return k.a + k.rl_in + core * f;
}

float knot_t(knots k, int i)
{
    // (r^j - 1) / (r^nc - 1), written as r^(j - nc) (1 - r^-j) / (1 - r^-nc): r^nc overflows fp32 for 48 segments
    // per chord over several merged chords (1.6^192), which made NaN
    float j = float(i - k.nr_in), lr = log(max(k.r, 1.0)), nc = float(k.nc);
    return knot_at(k, i, k.r > 1.0001 ? exp((j - nc) * lr) * (1.0 - exp(-j * lr)) / (1.0 - exp(-nc * lr)) : j / nc);
}

// The same for a uniform core (r = 1): without the geometric progression's three exp and a log, which llvmpipe
// works out whatever r is (it runs both sides of a choice).
float knot_t_uniform(knots k, int i)
{
    return knot_at(k, i, float(i - k.nr_in) / float(k.nc));
}

// Intersects the ray ro + t dir (dir unit) with every ellipsoid and keeps the chords with t1 > 0, clipped to t >= 0
// (origin inside: start at the origin), sorted by entry. The roots come from the point of closest approach in the
// ellipsoid's unit-sphere space (t_c, |q_c|): the textbook discriminant B^2 - 4AC cancels catastrophically in fp32
// when the ray starts far away relative to the radius (a sun-map ray from 60 km through an 11 m thick slab lost the
// whole chord); 1 - |q_c|^2 does not (Haines et al., Ray Tracing Gems ch. 7).
void cast_ray(vec3 ro, vec3 dir)
{
    n_hits = 0;
    for (int i = 0; i < NUM_ELL; i++) {
        vec3 ir = u_ell_ir[i].xyz;
        vec3 q = (ro - u_ell_c[i].xyz) * ir, ds = dir * ir;
        float A = dot(ds, ds);
        float tc = -dot(q, ds) / A;
        vec3 qc = q + tc * ds;
        float h2 = 1.0 - dot(qc, qc);
        if (h2 <= 0.0)
            continue;
        float hw = sqrt(h2 / A);
        float t0 = max(tc - hw, 0.0), t1 = tc + hw;
        if (t1 <= t0)
            continue;
        int k = n_hits;
        while (k > 0 && hit_t0[k - 1] > t0) {
            hit_t0[k] = hit_t0[k - 1]; hit_t1[k] = hit_t1[k - 1]; hit_idx[k] = hit_idx[k - 1];
            k--;
        }
        hit_t0[k] = t0; hit_t1[k] = t1; hit_idx[k] = i;
        n_hits++;
    }
}

// The next interval of the union along the cast ray, starting at hit k: merges overlapping chords so overlap
// regions are integrated once. Returns the index after the interval; a, b are its ends, merged counts the chords.
int next_interval(int k, out float a, out float b, out int merged)
{
    a = hit_t0[k];
    b = hit_t1[k];
    merged = 1;
    k++;
    while (k < n_hits && hit_t0[k] <= b) {
        b = max(b, hit_t1[k]);
        merged++;
        k++;
    }
    return k;
}

// The points of an interval where the sun map keeps the optical depth from its entry (sun_opacity.frag, sunmap.glsl),
// as fractions of its length: 1/32 and 1/8 near the entry, where the noisy boundary ramp makes tau strongly convex (a
// line from the entry to 1/4 put a front-lit cloud's lit skin in shadow: about 1/3 too dark against the path
// tracer), then 1/4, 1/2 and 3/4, and the exit.
const int TAU_POINTS = 5;
const float TAU_AT[TAU_POINTS] = float[TAU_POINTS](0.03125, 0.125, 0.25, 0.5, 0.75);

// Optical depth through the in-cloud interval [a, b] of the ray ro + t dir: n trapezoids on the knots above (uniform
// core; boundary ramps if `ramps`), the end samples a hair inside (as in cloud.frag). Also returns the cumulative
// optical depth at the TAU_AT points (near.x, near.y: 1/32, 1/8; quarters: 1/4, 1/2, 3/4 and 1 of the interval),
// each a knot of its own (a segment holding one is split there), so the opacity map stores sampled values, not
// interpolations inside a noisy segment. One loop over the knots and the points in order, one density sample a
// trip: a loop nested in it for the points cost a sample every knot on llvmpipe, which runs a loop's first trip
// whether or not any pixel takes it.
// `points` false: the total alone, no sample spent on the points (the slab and shadow maps want only that); a constant
// at every call, so the compiler drops the points' work after inlining.
float integrate_interval(vec3 ro, vec3 dir, float a, float b, int n, bool ramps, bool points, out vec4 quarters,
                         out vec2 near)
{
    float len = b - a;
    float nudge = min(1e-3 * len, 0.05);
    knots kn = make_knots(a, len, nudge, n, 1.0, ramps);
    int m = knot_count(kn);
    float t_prev = a, ke_prev = extinction(ro + dir * (a + nudge), a + nudge), tau = 0.0;
    int i = 1, j = 0; // the next knot, the next point
    float t_knot = m == 1 ? b : knot_t_uniform(kn, 1);
    float got[TAU_POINTS];
    for (int k = 0; k < TAU_POINTS; k++)
        got[k] = 0.0;
    int np = points ? TAU_POINTS : 0;
    for (int step = 0; step < m + np && i <= m; step++) {
        float q = a + TAU_AT[min(j, TAU_POINTS - 1)] * len;
        bool inside = j < np && q < t_knot - 1e-4 * len; // a point strictly inside this segment: first
        float t = inside ? q : t_knot, ts = inside || i < m ? t : b - nudge;
        float ke = extinction(ro + dir * ts, ts);
        tau += (t - t_prev) * 0.5 * (ke_prev + ke);
        if (inside || (j < np && abs(q - t) < 1e-4 * len)) { // ... or a knot on it
            got[min(j, TAU_POINTS - 1)] = tau;
            j++;
        }
        if (!inside) {
            i++;
            t_knot = i >= m ? b : knot_t_uniform(kn, i);
        }
        t_prev = t;
        ke_prev = ke;
    }
    near = vec2(got[0], got[1]);
    quarters = vec4(got[2], got[3], got[4], tau);
    return tau;
}
