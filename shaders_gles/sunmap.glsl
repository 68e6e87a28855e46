// shaders_gles/sunmap.glsl: optical depth from the sun to a sample, by one of four methods (light.shadow):
//   SHADOW_PEEL 1: the opacity map of the union's intervals along each sun-map texel's ray (sun_opacity.frag): the
//      sample's interval is found by its depth, tau = the intervals before it + a piecewise-quadratic estimate from
//      tau at 1/32, 1/8, 1/4, 1/2, 3/4 and 1 of its own interval. Exact in gaps and concavities; noise included.
//   SHADOW_PEEL 0 (SHADOW_METHOD 1): Kol's estimate l * k_e(p) with l the distance below the front depth (wrong
//      across gaps and concavities, and banded where k_e(p) varies; kept for the trade study).
//   SHADOW_METHOD 2 (osm): regular-slice opacity shadow maps (sun_osm.frag): tau at OSM_SLICES depths spaced evenly
//      between the texel ray's first entry and last exit, linear between slices.
//   SHADOW_METHOD 3 (fom): Fourier opacity maps (sun_fom.frag): tau(z) reconstructed from FOM_COEFFS Fourier terms
//      of k_e over the same per-texel range, clamped to [0, tau of the whole ray].
// SHADOW_METHOD is the cu_shadow_method (0 peel, 1 front, 2 osm, 3 fom); without it SHADOW_PEEL picks peel or front.
// Needs density.glsl (PI) and SUN_INTERVALS, SUN_FILTER, SUN_PLANAR (light.sun_planar, below; and OSM_SLICES or
// FOM_COEFFS).
#ifndef SHADOW_METHOD
#if SHADOW_PEEL
#define SHADOW_METHOD 0
#else
#define SHADOW_METHOD 1
#endif
#endif
#ifndef SUN_PLANAR
#define SUN_PLANAR 0
#endif
#ifndef FOM_FEJER
#define FOM_FEJER 0
#endif
uniform vec3 u_sun_dir;        // toward the sun
uniform vec3 u_sun_right, u_sun_up;
uniform float u_sun_R;         // the sun plane is at 2R along u_sun_dir, maps cover [-R, R]^2
uniform int u_sun_size;        // texels per side
uniform float u_sun_tau_scale; // the cloud's density now against the map's (life cycle, border fade)
#if SHADOW_PEEL
uniform sampler2D u_sun_layers;  // per interval j (tile j of SUN_INTERVALS side by side): z_entry, z_exit (m), and
                                 // tau at 1/32 and 1/8 of it, counted from its entry
uniform sampler2D u_sun_tau;     // tau at 1/4, 1/2, 3/4, 1 of interval j, counted from its entry
uniform int u_sun_intervals;     // intervals present in this sun direction (<= SUN_INTERVALS)
#elif SHADOW_METHOD == 2 || SHADOW_METHOD == 3
uniform sampler2D u_sun_map;     // osm / fom: RGBA32F tiles side by side, tile 0 starting with (z0, z1)
#else
uniform sampler2D u_sun_depth;   // front depth / 4R
#endif

#if SHADOW_PEEL
// Optical depth at u (fraction of the interval) from the seven points kept: the entry (0), TAU_AT (density.glsl) and
// the exit. Between two points, the quadratic through them and the point before (the first piece's: the one after),
// clamped to the piece's ends so it stays monotone. Near the entry the noisy ramp makes tau convex, and a chord
// between points overestimates it: the lit skin of a front-lit cloud came out too dark (its brightest fifth 0.86 of
// the path tracer's single scattering; 0.96 with the quadratic). test_sunmap measures both against a CPU march.
float tau_between(float u, vec4 ab, vec4 q)
{
    const float X[7] = float[7](0.0, 0.03125, 0.125, 0.25, 0.5, 0.75, 1.0);
    float T[7] = float[7](0.0, ab.z, ab.w, q.x, q.y, q.z, q.w);
    int k = u < 0.25 ? (u < 0.03125 ? 0 : u < 0.125 ? 1 : 2) : u < 0.5 ? 3 : u < 0.75 ? 4 : 5; // the piece
    int i = max(k - 1, 0);
    float x0 = X[i], x1 = X[i + 1], x2 = X[i + 2];
    float e = T[i] * (u - x1) * (u - x2) / ((x0 - x1) * (x0 - x2)) +
              T[i + 1] * (u - x0) * (u - x2) / ((x1 - x0) * (x1 - x2)) +
              T[i + 2] * (u - x0) * (u - x1) / ((x2 - x0) * (x2 - x1));
    return clamp(e, min(T[k], T[k + 1]), max(T[k], T[k + 1]));
}

float tau_in_texel(ivec2 tc, float z)
{
    float tau = 0.0;
    for (int j = 0; j < SUN_INTERVALS; j++) {
        if (j >= u_sun_intervals)
            break;
        ivec2 at = ivec2(tc.x + j * u_sun_size, tc.y);
        vec4 ab = texelFetch(u_sun_layers, at, 0);
        if (ab.x > 1e29)
            break; // no more intervals on this ray
        vec4 q = texelFetch(u_sun_tau, at, 0);
        if (z >= ab.y) {
            tau += q.w;
        } else {
            if (z > ab.x)
                tau += tau_between(clamp((z - ab.x) / max(ab.y - ab.x, 1e-6), 0.0, 1.0), ab, q);
            break;
        }
    }
    return tau;
}
#elif SHADOW_METHOD == 2
float osm_slice(ivec2 tc, int i)
{
    return texelFetch(u_sun_map, ivec2(tc.x + (1 + i / 4) * u_sun_size, tc.y), 0)[i - 4 * (i / 4)];
}

// Slice i holds tau at z0 + (i + 1) / OSM_SLICES (z1 - z0); tau = 0 at z0 and the total beyond z1.
float tau_in_texel(ivec2 tc, float z)
{
    vec2 r = texelFetch(u_sun_map, tc, 0).xy;
    if (z <= r.x)
        return 0.0; // before the first entry, or a ray that misses (z0 = 1e30)
    float f = min((z - r.x) / max(r.y - r.x, 1e-6), 1.0) * float(OSM_SLICES);
    int m = min(int(f), OSM_SLICES - 1);
    float hi = osm_slice(tc, m);
    float lo = m > 0 ? osm_slice(tc, m - 1) : 0.0;
    return mix(lo, hi, f - float(m));
}
#elif SHADOW_METHOD == 3
const int FOM_TILES = 1 + FOM_COEFFS / 2;

// tau(x) = a0/2 x + sum_k>=1 [a_k sin(w_k x) + b_k (1 - cos(w_k x))] / w_k, x = z - z0, w_k = 2 pi k / D; cos and
// sin of k theta by rotation. Clamped to [0, a0 D / 2] (the exact total at z1): ringing of the truncated series
// cannot make tau negative or exceed the whole ray's; before z0 it is 0, beyond z1 the total. Tile t >= 1 holds
// (a_k, b_k, a_k+1, b_k+1), k = 2t - 1 (sun_fom.frag).
float tau_in_texel(ivec2 tc, float z)
{
    vec4 c0 = texelFetch(u_sun_map, tc, 0);
    if (z <= c0.x)
        return 0.0;
    float D = max(c0.y - c0.x, 1e-6);
    float total = 0.5 * c0.z * D;
    if (z >= c0.y)
        return total;
    float x = z - c0.x;
    float th = 2.0 * PI * x / D;
    vec2 r1 = vec2(cos(th), sin(th)), rk = vec2(1.0, 0.0);
    float sum = 0.0; // sum_k [a_k sin(k th) + b_k (1 - cos(k th))] / k
    for (int t = 1; t < FOM_TILES; t++) {
        vec4 c = texelFetch(u_sun_map, ivec2(tc.x + t * u_sun_size, tc.y), 0);
        float k = float(2 * t - 1);
        rk = vec2(rk.x * r1.x - rk.y * r1.y, rk.x * r1.y + rk.y * r1.x); // (cos k th, sin k th)
#if FOM_FEJER
        vec2 w = max(1.0 - vec2(k, k + 1.0) / float(FOM_COEFFS), 0.0); // Fejer means: k_e >= 0, so tau is monotone
#else
        vec2 w = vec2(1.0);
#endif
        sum += w.x * (c.x * rk.y + c.y * (1.0 - rk.x)) / k;
        rk = vec2(rk.x * r1.x - rk.y * r1.y, rk.x * r1.y + rk.y * r1.x);
        sum += w.y * (c.z * rk.y + c.w * (1.0 - rk.x)) / (k + 1.0);
    }
    float tau = 0.5 * c0.z * x + sum * D / (2.0 * PI);
    return clamp(tau, 0.0, total);
}
#endif

#if SHADOW_METHOD != 1 && SUN_PLANAR
// Where texel t's ray first enters the ellipsoids (m from the sun plane; above 1e29 where it misses): tile 0's x in
// every method's layout.
float texel_entry(ivec2 t)
{
#if SHADOW_METHOD == 0
    return texelFetch(u_sun_layers, t, 0).x;
#else
    return texelFetch(u_sun_map, t, 0).x;
#endif
}

// A texel's ray stands for every sample in its footprint, but where the lit surface is slanted to the sun, a sample
// off the texel's centre enters the cloud earlier or later than that ray: by its offset times the tangent of the
// sun's angle to the surface's normal, up to 1.4 texel widths at a sun 20 degrees above a flat top. Read at the
// sample's own depth, the texel's tau then comes from a point that much deeper or shallower in the lit skin, where
// tau grows by a few per metre: single scattering off a wide layer under a low sun came out a quarter (bilinear) to
// a half (nearest) of the path tracer's at 128 texels. So a texel is read at the sample's depth below its own ray's
// entry: the sample's entry interpolated from the texels about it (exact where the surface is a plane across them),
// minus the texel's. Where one of them misses, or two neighbours' entries part by more than PLANAR_SLOPE texel
// widths (the surface within 7 degrees of the sun's direction, or another lobe's face), the surface is no plane
// there and the sample's own depth is kept. Compiled in where a cloud's map is coarse against its lit skin and fine
// against its lobes (light.sun_planar; renderer.c): two or four more texel reads a lookup, 5 % of the cumulus's cloud
// pass, and on small round lobes a few texels wide the plane through the neighbours is worse than none.
#define PLANAR_SLOPE 8.0
// Whether neighbours' entries e_a and e_b may lie on one plane with e_k (a texel apart; above 1e29: a miss).
bool planar(float ek, float ea, float eb)
{
    float most = PLANAR_SLOPE * 2.0 * u_sun_R / float(u_sun_size);
    return max(ek, max(ea, eb)) < 1e29 && abs(ea - ek) <= most && abs(eb - ek) <= most;
}
#endif

float sun_optical_depth(vec3 p, float ke)
{
    vec2 uv = vec2(dot(p, u_sun_right), dot(p, u_sun_up)) / u_sun_R * 0.5 + 0.5;
    float z = 2.0 * u_sun_R - dot(p, u_sun_dir);
#if SHADOW_METHOD != 1
    ivec2 hi = ivec2(u_sun_size - 1);
#if SUN_FILTER
    // Bilinear over the four texels' own estimates (a deep-opacity-map lookup, not a filter of depths), each read as
    // far below its entry as the sample is below its own, the four entries' bilinear mean.
    vec2 f = uv * float(u_sun_size) - 0.5;
    ivec2 i0 = ivec2(floor(f));
    vec2 w = f - vec2(i0);
    ivec2 c00 = clamp(i0, ivec2(0), hi), c10 = clamp(i0 + ivec2(1, 0), ivec2(0), hi);
    ivec2 c01 = clamp(i0 + ivec2(0, 1), ivec2(0), hi), c11 = clamp(i0 + ivec2(1, 1), ivec2(0), hi);
    vec4 zt = vec4(z);
#if SUN_PLANAR
    {
        vec4 e = vec4(texel_entry(c00), texel_entry(c10), texel_entry(c01), texel_entry(c11));
        float ep = mix(mix(e.x, e.y, w.x), mix(e.z, e.w, w.x), w.y);
        if (planar(e.x, e.y, e.z) && planar(e.w, e.y, e.z))
            zt -= vec4(ep) - e;
    }
#endif
    float t00 = tau_in_texel(c00, zt.x);
    float t10 = tau_in_texel(c10, zt.y);
    float t01 = tau_in_texel(c01, zt.z);
    float t11 = tau_in_texel(c11, zt.w);
    return u_sun_tau_scale * mix(mix(t00, t10, w.x), mix(t01, t11, w.x), w.y);
#else
    // The texel the sample lies in, and the sample's entry from it and its neighbours toward the sample in x and y.
    vec2 f = uv * float(u_sun_size);
    ivec2 tc = clamp(ivec2(floor(f)), ivec2(0), hi);
    float shift = 0.0;
#if SUN_PLANAR
    {
        vec2 d = f - vec2(tc) - 0.5; // the sample's offset from the texel's centre, in texels
        ivec2 toward = ivec2(d.x >= 0.0 ? 1 : -1, d.y >= 0.0 ? 1 : -1);
        float ek = texel_entry(tc);
        float ex = texel_entry(clamp(tc + ivec2(toward.x, 0), ivec2(0), hi));
        float ey = texel_entry(clamp(tc + ivec2(0, toward.y), ivec2(0), hi));
        if (planar(ek, ex, ey))
            shift = abs(d.x) * (ex - ek) + abs(d.y) * (ey - ek);
    }
#endif
    return u_sun_tau_scale * tau_in_texel(tc, z - shift);
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
