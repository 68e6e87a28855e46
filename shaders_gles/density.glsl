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

// Intersects the ray ro + t dir (dir unit) with every ellipsoid (cancellation-free quadratic) and keeps the chords
// with t1 > 0, clipped to t >= 0 (origin inside: start at the origin), sorted by entry.
void cast_ray(vec3 ro, vec3 dir)
{
    n_hits = 0;
    for (int i = 0; i < NUM_ELL; i++) {
        vec3 ir = u_ell_ir[i].xyz;
        vec3 q = (ro - u_ell_c[i].xyz) * ir, ds = dir * ir;
        float A = dot(ds, ds), B = 2.0 * dot(q, ds), C = dot(q, q) - 1.0;
        float disc = B * B - 4.0 * A * C;
        if (disc <= 0.0)
            continue;
        float s = sqrt(disc);
        float qq = -0.5 * (B + (B >= 0.0 ? s : -s));
        float ta = qq / A, tb = C / qq;
        float t0 = max(min(ta, tb), 0.0), t1 = max(ta, tb);
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
