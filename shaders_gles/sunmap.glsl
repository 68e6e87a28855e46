// shaders_gles/sunmap.glsl: optical depth from the sun to a sample, by one of two methods (light.shadow):
//   SHADOW_PEEL 1: the opacity map of the union's intervals along each sun-map texel's ray (sun_opacity.frag): the
//      sample's interval is found by its depth, tau = the intervals before it + a piecewise-linear estimate from
//      tau at 1/4, 1/2, 3/4 and 1 of its own interval. Exact in gaps and concavities; noise included.
//   SHADOW_PEEL 0: Kol's estimate l * k_e(p) with l the distance below the front depth (wrong across gaps and
//      concavities, and banded where k_e(p) varies; kept for the trade study).
// Needs density.glsl (PI) and SUN_INTERVALS, SUN_FILTER.
uniform vec3 u_sun_dir;        // toward the sun
uniform vec3 u_sun_right, u_sun_up;
uniform float u_sun_R;         // the sun plane is at 2R along u_sun_dir, maps cover [-R, R]^2
uniform int u_sun_size;        // texels per side
#if SHADOW_PEEL
uniform sampler2D u_sun_layers;  // per interval j (tile j of SUN_INTERVALS side by side): z_entry, z_exit (m)
uniform sampler2D u_sun_tau;     // tau at 1/4, 1/2, 3/4, 1 of interval j, counted from its entry
uniform int u_sun_intervals;     // intervals present in this sun direction (<= SUN_INTERVALS)
#else
uniform sampler2D u_sun_depth;   // front depth / 4R
#endif

#if SHADOW_PEEL
float tau_in_texel(ivec2 tc, float z)
{
    float tau = 0.0;
    for (int j = 0; j < SUN_INTERVALS; j++) {
        if (j >= u_sun_intervals)
            break;
        ivec2 at = ivec2(tc.x + j * u_sun_size, tc.y);
        vec2 ab = texelFetch(u_sun_layers, at, 0).xy;
        if (ab.x > 1e29)
            break; // no more intervals on this ray
        float len = ab.y - ab.x;
        vec4 q = texelFetch(u_sun_tau, at, 0);
        if (z >= ab.y) {
            tau += q.w;
        } else {
            if (z > ab.x) {
                float f = clamp((z - ab.x) / max(len, 1e-6), 0.0, 1.0) * 4.0;
                float lo = f < 1.0 ? 0.0 : f < 2.0 ? q.x : f < 3.0 ? q.y : q.z;
                float hi = f < 1.0 ? q.x : f < 2.0 ? q.y : f < 3.0 ? q.z : q.w;
                tau += mix(lo, hi, fract(min(f, 3.9999)));
            }
            break;
        }
    }
    return tau;
}
#endif

float sun_optical_depth(vec3 p, float ke)
{
    vec2 uv = vec2(dot(p, u_sun_right), dot(p, u_sun_up)) / u_sun_R * 0.5 + 0.5;
    float z = 2.0 * u_sun_R - dot(p, u_sun_dir);
#if SHADOW_PEEL
    vec2 f = uv * float(u_sun_size) - 0.5;
    ivec2 i0 = ivec2(floor(f));
    int hi = u_sun_size - 1;
#if SUN_FILTER
    // Bilinear over the four texels' own estimates (a deep-opacity-map lookup, not a filter of depths).
    vec2 w = f - vec2(i0);
    float t00 = tau_in_texel(clamp(i0, ivec2(0), ivec2(hi)), z);
    float t10 = tau_in_texel(clamp(i0 + ivec2(1, 0), ivec2(0), ivec2(hi)), z);
    float t01 = tau_in_texel(clamp(i0 + ivec2(0, 1), ivec2(0), ivec2(hi)), z);
    float t11 = tau_in_texel(clamp(i0 + ivec2(1, 1), ivec2(0), ivec2(hi)), z);
    return mix(mix(t00, t10, w.x), mix(t01, t11, w.x), w.y);
#else
    return tau_in_texel(clamp(ivec2(floor(uv * float(u_sun_size))), ivec2(0), ivec2(hi)), z);
#endif
#else
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))))
        return 0.0;
    float front = textureLod(u_sun_depth, uv, 0.0).r;
    if (front >= 1.0)
        return 0.0;
    float l = max(z - front * 4.0 * u_sun_R, 0.0);
    return l * ke;
#endif
}
