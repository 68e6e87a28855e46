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

// Kol eq. 3.74: five LODs at p and at 8p, each sum minus 0.75, clamped to [0,1], mapped to [-1,1].
float fractal_noise(vec3 p)
{
    vec3 t = p * u_noise_freq + u_noise_offset;
    float a = -1.5, b;
    const float w[5] = float[5](0.015, 0.035, 0.1, 0.35, 1.5);
    for (int L = 0; L < 5; L++) {
        if (L < 5 - NOISE_OCTAVES) {
            a += 2.0 * w[L] * u_noise_mean[L];
        } else {
            a += w[L] * (sample_level(t, L) + sample_level(8.0 * t, L));
        }
    }
    b = clamp(a, 0.0, 1.0);
    return b * 2.0 - 1.0;
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

// Extinction at p = ray(t): the distance to the union is the max over ellipsoids, and only ellipsoids whose chord
// contains t can be non-negative there, so the loop runs over the hit list, skipping chords that end before t.
float extinction(vec3 p, float t)
{
    float d = -1e30;
    for (int k = 0; k < n_hits; k++) {
        if (t >= hit_t0[k] - 1e-3 && t <= hit_t1[k] + 1e-3)
            d = max(d, radial_distance(p, hit_idx[k]));
    }
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

// Length of the boundary ramp at each end of an in-cloud interval of length len for the integrators: h, when the
// boundary is thicker than the end nudge and the interval has a core between its ramps; else 0 (no ramp segments).
// Exact along the normal of a lone ellipsoid; along oblique rays the ramp is longer and the first core segment
// sees the rest of it.
float ramp_length(float len, float nudge)
{
    return (u_h > 2.0 * nudge && 2.0 * u_h < 0.5 * len) ? u_h : 0.0;
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

// Optical depth through the in-cloud interval [a, b] of the ray ro + t dir: the boundary ramps as one trapezoid each
// (ramp_length), the core in n uniform trapezoids, the end samples a hair inside (as in cloud.frag). Also returns
// the cumulative optical depth at 1/4, 1/2, 3/4 and 1 of the interval (linear within the segment that holds each).
float integrate_interval(vec3 ro, vec3 dir, float a, float b, int n, out vec4 quarters)
{
    float len = b - a;
    float nudge = min(1e-3 * len, 0.05);
    float rl = ramp_length(len, nudge);
    float x = (len - 2.0 * rl) / float(n);
    float t_prev = a, ke_prev = extinction(ro + dir * (a + nudge), a + nudge), tau = 0.0;
    quarters = vec4(0.0);
    for (int i = rl > 0.0 ? -1 : 0; i < n + (rl > 0.0 ? 1 : 0); i++) {
        bool last = i == n - (rl > 0.0 ? 0 : 1);
        float t = i < 0 ? a + rl : last ? b : (i == n - 1 ? b - rl : a + rl + x * float(i + 1));
        float ts = last ? b - nudge : t;
        float ke = extinction(ro + dir * ts, ts);
        float tau_new = tau + (t - t_prev) * 0.5 * (ke_prev + ke);
        for (int j = 0; j < 3; j++) {
            float q = a + 0.25 * float(j + 1) * len;
            if (q > t_prev && q <= t)
                quarters[j] = mix(tau, tau_new, (q - t_prev) / max(t - t_prev, 1e-9));
        }
        tau = tau_new;
        t_prev = t;
        ke_prev = ke;
    }
    quarters.w = tau;
    return tau;
}
