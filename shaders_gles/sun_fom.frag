#version 300 es
// shaders_gles/sun_fom.frag: Fourier opacity maps (Jansen & Bavoil 2010; Giulietti 3.3.3.5), for light.shadow = fom.
// Per sun-map texel the sun ray is cast through the ellipsoids (cast_ray) and the extinction along it, noise
// included, is projected on a Fourier basis over the ray's own depth range [z0, z1] (first cloud entry, last exit;
// D = z1 - z0, x = z - z0): a_k = (2/D) int k_e cos(2 pi k x / D) dz, b_k = (2/D) int k_e sin(2 pi k x / D) dz,
// k = 0 .. FOM_COEFFS - 1 (b_0 = 0 is not stored). The quadrature is the opacity pass's (SUN_SAMPLES segments over
// each interval's core, one per boundary ramp) with k_e linear over each segment and the product integrated in
// closed form, so a_0 D / 2 is exactly the trapezoid tau of the whole ray however coarse a segment is against a
// period. Layout (RGBA32F, 1 + FOM_COEFFS / 2 tiles of u_sun_size side by side): tile 0 = (z0, z1, a_0, 0) with
// z0, z1 in metres from the sun plane (1e30 on rays that miss); tile t >= 1 = (a_k, b_k, a_k+1, b_k+1) with
// k = 2t - 1 (0 beyond k = FOM_COEFFS - 1), so the lookup reads each tile once, in order, with no dynamic indexing.
// Read by sunmap.glsl (SHADOW_METHOD 3).
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
    float D = max(z1 - z0, 1e-6);
    // the four slots of this tile: angular frequency, cosine (0) or sine (1) term, and whether the slot is used
    vec4 om = vec4(0.0), sine = vec4(0.0), used = vec4(0.0);
    if (j == 0) {
        used.z = 1.0; // a_0
    } else {
        int k = 2 * j - 1;
        om = 2.0 * PI * vec4(float(k), float(k), float(k + 1), float(k + 1)) / D;
        sine = vec4(0.0, 1.0, 0.0, 1.0);
        used = vec4(float(k < FOM_COEFFS), float(k < FOM_COEFFS), float(k + 1 < FOM_COEFFS), float(k + 1 < FOM_COEFFS));
    }
    vec4 acc = vec4(0.0);
    if (any(greaterThan(used, vec4(0.0)))) {
        float a, b;
        int merged, k = 0;
        while (k < n_hits) {
            k = next_interval(k, a, b, merged);
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
                // int over [t_prev, t] of (k_e linear) * cos or sin(om x), x = z - z0, about the segment's middle:
                //   cos: km L g cos(phi) + dk sin(phi) E,  sin: km L g sin(phi) - dk cos(phi) E, with h = om L / 2,
                //   g = sin(h) / h, E = (cos(h) - g) / om (series for small h: no cancellation)
                float L = t - t_prev, km = 0.5 * (ke + ke_prev), dk = ke - ke_prev;
                vec4 h = 0.5 * om * L;
                vec4 phi = om * (0.5 * (t + t_prev) - z0);
                bvec4 small = lessThan(h, vec4(0.1));
                vec4 h2 = h * h;
                vec4 g = mix(sin(h) / max(h, vec4(1e-30)), 1.0 - h2 / 6.0, vec4(small));
                vec4 E = mix((cos(h) - g) / max(om, vec4(1e-30)), -om * L * L / 12.0 * (1.0 - h2 / 10.0),
                             vec4(small));
                vec4 cs = cos(phi), sn = sin(phi);
                vec4 ic = km * L * g * cs + dk * sn * E;
                vec4 is = km * L * g * sn - dk * cs * E;
                acc += mix(ic, is, sine);
                t_prev = t;
                ke_prev = ke;
            }
        }
        acc *= 2.0 / D * used;
    }
    if (j == 0) {
        acc.x = z0;
        acc.y = z1;
    }
    o_map = acc;
}
