#version 300 es
// shaders_gles/slab_map.frag: the slab map for the multiple-scattering model (Kol 3.1.4 "Fitting a plane-parallel
// slab to an arbitrary cloud", 3.4.5). One texel per parallel ray from the light (the sun, or the zenith for sky
// light): target 0 = (coverage, height of the first entry along the light direction / R, in-cloud length / R, optical
// depth through every interval),
// target 1 = the hull normal where the ray first enters. Coverage-weighted, so the mip chain (glGenerateMipmap)
// holds Gaussian-ish averages over the collector area: depth = x / coverage, and the mean normal's direction is the
// normal (coverage cancels). The thickness is the length inside the union's intervals, not back minus front depth,
// and the optical depth integrates the real density (noise included) with SLAB_SAMPLES trapezoids per interval
// (integrate_interval in density.glsl).
// RGBA16F: lengths are fractions of R (no fp16 overflow for 50 km clouds), and the entry is stored as its height
// above the cloud's centre along the light, not as a depth from the map plane at 2R: fp16 keeps 11 bits, which on a
// depth near 2R is 1/2000 of the map (29 m for a 60 km slab), while heights keep that precision relative to the
// cloud's own extent. tau is capped at 1e4, where the slab model saturates anyway.
#include "density.glsl"
uniform vec3 u_map_dir, u_map_right, u_map_up; // toward the light, and the map's axes
uniform float u_map_R;                          // the map covers [-R, R]^2, its plane is 2R along u_map_dir
uniform int u_map_size;
layout(location = 0) out vec4 o_slab;
layout(location = 1) out vec4 o_normal;

void main()
{
    vec2 uv = (gl_FragCoord.xy) / float(u_map_size);
    vec2 xy = (uv * 2.0 - 1.0) * u_map_R;
    vec3 ro = u_map_right * xy.x + u_map_up * xy.y + u_map_dir * (2.0 * u_map_R);
    vec3 dir = -u_map_dir;
    cast_ray(ro, dir);
    if (n_hits == 0) {
        o_slab = vec4(0.0);
        o_normal = vec4(0.0);
        return;
    }
    int first = hit_idx[0];
    vec3 q = (ro + dir * hit_t0[0] - u_ell_c[first].xyz) * u_ell_ir[first].xyz;
    vec3 n = normalize(q * u_ell_ir[first].xyz);   // gradient of |(p - c) / r|^2
    float len = 0.0, tau = 0.0, a, b;
    int merged, k = 0;
    while (k < n_hits) {
        k = next_interval(k, a, b, merged);
        len += b - a;
        vec4 q;
        vec2 qn;
        tau += integrate_interval(ro, dir, a, b, SLAB_SAMPLES, true, false, q, qn); // 8 segments: ramps matter
    }
    float s = 1.0 / u_map_R;
    o_slab = vec4(1.0, dot(ro + dir * hit_t0[0], u_map_dir) * s, len * s, min(tau, 1e4));
    o_normal = vec4(n, 0.0);
}
