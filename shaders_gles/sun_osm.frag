#version 300 es
// shaders_gles/sun_osm.frag: regular-slice opacity shadow maps (Kim & Neumann 2001; Giulietti 3.3.3.2), for
// light.shadow = osm. Built the analytic way the opacity map is (sun_opacity.frag): per sun-map texel the sun ray is
// cast through the ellipsoids (cast_ray) and the real density, noise included, is integrated along it with the
// opacity pass's quadrature (SUN_SAMPLES trapezoids over each interval's core, one per boundary ramp). Instead of
// the peeled surfaces, the depths kept are OSM_SLICES regular slices between the ray's first cloud entry z0 and its
// last exit z1 (per texel, so no slice is spent on air outside the cloud along this ray): slice i (0-based) at
// z0 + (i + 1) / OSM_SLICES * (z1 - z0) stores the optical depth from the sun plane to that depth.
// Layout (RGBA32F, tiles of u_sun_size side by side): tile 0 = (z0, z1, 0, 0) in metres from the sun plane
// (1e30 on rays that miss), tile 1 + j = slices 4j .. 4j + 3. Read by sunmap.glsl (SHADOW_METHOD 2).
#include "density.glsl"
uniform vec3 u_sun_dir, u_sun_right, u_sun_up;
uniform float u_sun_R;
uniform int u_sun_size;
out vec4 o_map;

void main()
{
    ivec2 fc = ivec2(gl_FragCoord.xy);
    int j = fc.x / u_sun_size;
    vec2 uv = (vec2(float(fc.x - j * u_sun_size), float(fc.y)) + 0.5) / float(u_sun_size);
    vec2 xy = (uv * 2.0 - 1.0) * u_sun_R;
    vec3 ro = u_sun_right * xy.x + u_sun_up * xy.y + u_sun_dir * (2.0 * u_sun_R);
    vec3 dir = -u_sun_dir;
    cast_ray(ro, dir);
    if (n_hits == 0) {
        o_map = j == 0 ? vec4(1e30, 1e30, 0.0, 0.0) : vec4(0.0);
        return;
    }
    float z0 = hit_t0[0], z1 = hit_t1[0];
    for (int i = 1; i < NUM_ELL; i++) {
        if (i >= n_hits)
            break;
        z1 = max(z1, hit_t1[i]);
    }
    if (j == 0) {
        o_map = vec4(z0, z1, 0.0, 0.0);
        return;
    }
    // the four slice depths of this tile
    vec4 q = z0 + (z1 - z0) * (vec4(1.0, 2.0, 3.0, 4.0) + float(4 * (j - 1))) / float(OSM_SLICES);
    vec4 s = vec4(-1.0); // -1: not reached yet
    float tau = 0.0, a, b;
    int merged, k = 0;
    while (k < n_hits && s.w < 0.0) {
        k = next_interval(k, a, b, merged);
        for (int c = 0; c < 4; c++)
            if (s[c] < 0.0 && q[c] <= a)
                s[c] = tau; // in the air before this interval
        if (s.w >= 0.0)
            break;
        // integrate_interval's quadrature, recording tau where a slice depth falls inside a segment
        float len = b - a;
        float nudge = min(1e-3 * len, 0.05);
        knots kn = make_knots(a, len, nudge, SUN_SAMPLES, 1.0, false);
        int m = knot_count(kn);
        float t_prev = a, ke_prev = extinction(ro + dir * (a + nudge), a + nudge);
        for (int i = 1; i <= m; i++) {
            bool last = i == m;
            float t = last ? b : knot_t_uniform(kn, i);
            float ts = last ? b - nudge : t;
            float ke = extinction(ro + dir * ts, ts);
            float tau_new = tau + (t - t_prev) * 0.5 * (ke_prev + ke);
            for (int c = 0; c < 4; c++)
                if (s[c] < 0.0 && q[c] <= t)
                    s[c] = mix(tau, tau_new, clamp((q[c] - t_prev) / max(t - t_prev, 1e-9), 0.0, 1.0));
            tau = tau_new;
            t_prev = t;
            ke_prev = ke;
            if (s.w >= 0.0)
                break; // this tile's slices are all behind: the rest of the ray is not needed
        }
    }
    for (int c = 0; c < 4; c++)
        if (s[c] < 0.0)
            s[c] = tau; // at or beyond the last exit (rounding of the last slice's depth)
    o_map = s;
}
