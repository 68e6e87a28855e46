#version 300 es
// shaders_gles/sun_opacity.frag: the sun's opacity map (DESIGN "Sun transmittance"). For each sun-map texel, the ray
// from the sun is cast through every ellipsoid, its chords are merged into the union's intervals (the surfaces a
// depth peel would find, but exact: the ellipsoids are analytic, so no hull rasterisation, no polygonal depths and no
// peel passes are needed), and the real density, noise included, is integrated through interval j = the tile this
// fragment lies in. Output: target 0 (z_entry, z_exit) in metres from the sun plane and tau at 1/32 and 1/8 of the
// interval; target 1: tau at 1/4, 1/2, 3/4 and 1 of it. SUN_SAMPLES trapezoid segments, boundary ramps on their
// own, those points sampled (integrate_interval and TAU_AT in density.glsl).
#include "density.glsl"
uniform vec3 u_sun_dir, u_sun_right, u_sun_up;
uniform float u_sun_R;
uniform int u_sun_size;
layout(location = 0) out vec4 o_layers;
layout(location = 1) out vec4 o_tau;

void main()
{
    ivec2 fc = ivec2(gl_FragCoord.xy);
    int j = fc.x / u_sun_size;
    vec2 uv = (vec2(float(fc.x - j * u_sun_size), float(fc.y)) + 0.5) / float(u_sun_size);
    vec2 xy = (uv * 2.0 - 1.0) * u_sun_R;
    vec3 ro = u_sun_right * xy.x + u_sun_up * xy.y + u_sun_dir * (2.0 * u_sun_R);
    vec3 dir = -u_sun_dir;
    cast_ray(ro, dir);
    float a = 0.0, b = 0.0;
    int merged, k = 0;
    for (int i = 0; i <= j; i++) {
        if (k >= n_hits) {
            o_layers = vec4(1e30, 1e30, 0.0, 0.0);
            o_tau = vec4(0.0);
            return;
        }
        k = next_interval(k, a, b, merged);
    }
    vec4 q;
    vec2 qn;
    integrate_interval(ro, dir, a, b, SUN_SAMPLES, true, true, q, qn);
    o_layers = vec4(a, b, qn);
    o_tau = q;
}
