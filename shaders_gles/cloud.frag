#version 300 es
// shaders_gles/cloud.frag: opacity and single scattering of a cloud of noisy ellipsoids in one march (Kol 3.3.2,
// eqs. 3.20-3.22), over the ray's in-cloud intervals in front-to-back order, output premultiplied over the sky.
//
// Compile-time switches (only what the scene uses is compiled): NUM_ELL, SEGMENTS, MAX_INTERVALS, NOISE,
// NOISE_OCTAVES, PROFILE_KOL, INTEGRATION_KOL, MS_MODE (0 none, 1 octaves, 2 slab, 3 collector, 4 diffusion), MS_OCTAVES,
// PHASE_PEAK (chopped Mie), SKY_SPLIT (sky and ground light told apart by the slab model), FULLSCREEN (camera
// inside), BOUNDARY_KNOTS (quality.boundary_step), RAMP_KNOTS (quality.ramp_step), SHADOW_PEEL, SUN_INTERVALS, SUN_FILTER (sunmap.glsl), SLAB_*
// (ms_slab.glsl), ENERGY_PASS (the slab model's energy closure, src/gpu/pass_energy.c: sunlight terms apart instead of a colour), EXT_SHADOW (other
// clouds shade this one: their optical depth along the sun, pass_shadow.c), METHOD_UNIFORM (the mainstream uniform
// ray march instead of Kol's segments: UNIFORM_STEPS along the view, UNIFORM_SUN_STEPS toward the sun at each).
//
// Precision: everything is highp. Positions and distances are cloud-local metres (hundreds to thousands), optical
// depths reach hundreds: fp16 (mediump on Mali/V3D) has 11 bits and would lose both. Colours would survive mediump,
// but they are a few multiplies per sample; the cost is not worth a second precision domain.
#ifndef ENERGY_PASS
#define ENERGY_PASS 0
#endif
#ifndef EXT_SHADOW
#define EXT_SHADOW 0
#endif
#ifndef METHOD_UNIFORM
#define METHOD_UNIFORM 0
#endif
#include "density.glsl"
#include "sunmap.glsl"
#if MS_MODE == 2 || MS_MODE == 3
uniform vec2 u_ms_gain;                 // energy closure (pass_energy.c): <= 1, on reflected and transmitted light
#if ENERGY_PASS
uniform bool u_budget_view;             // the closure's view from the sun: columns' optical depth and slab angle
#endif
#include "ms_slab.glsl"
uniform sampler2D u_slab_a, u_slab_n;   // the slab map from the sun (slab_map.frag), mipmapped
uniform float u_slab_lod;               // its level for the fixed blur ms.blur (metres -> texels -> log2)
#if MS_MODE == 3
#include "ms_collector.glsl"
#endif
#if SKY_SPLIT
uniform sampler2D u_sky_a, u_sky_n;     // the same from the zenith, for sky and ground light
uniform vec3 u_sky_right, u_sky_up;
#endif
#endif

#if FULLSCREEN
in vec2 v_ndc;
#else
in vec3 v_pos;
#endif
uniform mat4 u_inv_viewproj;   // clip -> cloud-local
uniform vec3 u_cam;            // camera, cloud-local (perspective)
uniform bool u_ortho;          // parallel rays along u_view_dir, each from its pixel on the near plane
uniform vec3 u_view_dir;
uniform vec2 u_inv_viewport;   // 1 / the frame's size in pixels
#if !ENERGY_PASS
// The host's depth (cu_frame.depth_texture): the march ends at its surface. Window depth unprojected through the
// host's own projection; u_host_clear is the value that means no geometry.
uniform bool u_host_depth_on;
uniform highp sampler2D u_host_depth;
uniform mat4 u_host_inv_vp;
uniform float u_host_clear;
uniform float u_host_scale;       // full-resolution pixels per pixel of this pass (quality.cloud_downsample)
#endif
uniform float u_bound_R;       // radius of a sphere about the local origin containing every ellipsoid
uniform float u_seg_ratio;     // geometric ratio of consecutive segment lengths
uniform float u_boundary_step; // quality.boundary_step: the longest step along a chord that never reaches the core
uniform float u_ramp_step;     // quality.ramp_step: the longest step through a chord's entry ramp (RAMP_KNOTS)
uniform sampler2D u_phase;     // row 0: phase function p(theta) per RGB, sr^-1, theta = i * pi / (N-1);
                               // row 1: the removed forward peak P_p of a chopped Mie function (eq. 3.65)
#if PHASE_PEAK
uniform vec3 u_peak_f;         // weight f of the removed peak per channel (eq. 3.68)
#endif
uniform int u_phase_n;
uniform vec3 u_sun_irr;        // irradiance on a plane perpendicular to the sun's rays
uniform vec3 u_sky_rad;        // mean radiance of the sky (upper hemisphere)
uniform vec3 u_ground_rad;     // radiance of the ground (lower hemisphere; the sky colour for a constant sky)
uniform vec3 u_out_scale;      // exposure / white, or 1 for linear output (gpu_scene.c: cu_out_scale)
uniform float u_out_max;       // what the target may hold (fp16 overflows at 65504; gpu_scene.c: cu_out_max)
uniform vec4 u_px_map;         // this pass's pixel -> the cloud image's: xy * u_px_map.xy + u_px_map.zw (temporal_grid)
layout(location = 0) out vec4 o_color;
#if TEMPORAL && !ENERGY_PASS
// For the reprojection of the next frames (pass_temporal.c), premultiplied like the colour so clouds composite:
// alpha times the distance to where the ray enters the cloud (m) and times how far the cloud moved since the last
// frame (x, z, m), and alpha.
layout(location = 1) out vec4 o_depth;
uniform vec2 u_motion;
#define DEPTH_OUT(a, d) o_depth = (a) * vec4(d, u_motion, 1.0)
#else
#define DEPTH_OUT(a, d)
#endif

// A fragment with no cloud on its ray. Full screen it is discarded; a hull fragment instead writes transparent black
// (a no-op under the premultiplied blend): a shader that can discard makes llvmpipe and tilers run it before the
// depth and stencil tests, for every hull layer of the pixel, instead of once.
#if FULLSCREEN
#define NO_CLOUD discard
#else
#define NO_CLOUD { o_color = vec4(0.0); DEPTH_OUT(0.0, 0.0); return; }
#endif

vec3 phase_table(float cos_theta, int row)
{
    float x = acos(clamp(cos_theta, -1.0, 1.0)) / PI * float(u_phase_n - 1);
    int i = min(int(x), u_phase_n - 2);
    float f = x - float(i);
    return mix(texelFetch(u_phase, ivec2(i, row), 0).rgb, texelFetch(u_phase, ivec2(i + 1, row), 0).rgb, f);
}

float hg(float g, float mu)
{
    float d = 1.0 + g * g - 2.0 * g * mu;
    return (1.0 - g * g) / (4.0 * PI * d * sqrt(d));
}

#if PHASE_PEAK
// Chopped peak (delta-M): light scattered into the removed forward peak keeps travelling in its direction, so light
// on its way (the sunbeam to a sample, scattered light to the eye) is attenuated by the scaled extinction (1 - f) k_e,
// and P~ / (1 - f) is the phase function of the remaining scattering. This is also how the slab tables were made
// (tools/slab: delta-M transport with the chopped table), so single and multiple scattering agree.
#define DM_SCALE (1.0 - u_peak_f.g)
#else
#define DM_SCALE 1.0
#endif

#if MS_MODE == 1
#include "ms_octaves.glsl"
#endif

// Light a segment of optical depth dt scatters toward its entry, per unit of source: int_0^dt e^-u S(u) du with S
// log-linear from S0 to S1, S(u) = S0 e^(-b u / dt), b = ln(S0 / S1): S0 dt (1 - e^-(dt + b)) / (dt + b). The
// sunlit source falls like e^(-tau_sun) across a segment, steeply in a thick one, which the mean of the two ends
// misses (docs/gpu_notes.md). Falls back to the mean of the ends where a channel is zero.
vec3 segment_source(float dt, vec3 S0, vec3 S1)
{
    vec3 r = vec3(0.0);
    float e = 1.0 - exp(-dt);
    for (int c = 0; c < 3; c++) {
        float a = S0[c], b1 = S1[c];
        if (a > 1e-30 && b1 > 1e-30) {
            // S0 dt (1 - e^-x) / x with S0 e^-x = S1 e^-dt, written so that nothing overflows: a steeply rising
            // source (x << 0) would make e^-x overflow, and log(a / b1) underflow; near x = 0 its series
            float x = dt + (log(a) - log(b1));
            r[c] = abs(x) > 1e-3 ? dt * (a - b1 * exp(-dt)) / x : a * dt * (1.0 - 0.5 * x + x * x / 6.0);
        } else {
            r[c] = 0.5 * (a + b1) * e;
        }
    }
    return r;
}

// Light scattered toward the eye per unit extinction at p, relative to the sun's irradiance: single scattering of
// the attenuated sunbeam (eq. 3.21 without k_e and without the view transmittance) plus the multiple-scattering term.
#if EXT_SHADOW
uniform sampler2D u_sun_ext;   // other clouds' optical depth toward the sun, over this cloud's sun-map square
uniform float u_shadow_g;      // asymmetry for the diffuse light that gets through them (two-stream)
float ext_tau(vec3 p)
{
    vec2 uv = vec2(dot(p, u_sun_right), dot(p, u_sun_up)) / u_sun_R * 0.5 + 0.5;
    return texture(u_sun_ext, uv).r;
}
// Sunlight through other clouds, direct and diffuse: a conservative two-stream slab transmits 1 / (1 + 3/4 (1 - g)
// tau) (Bohren 1987, Am. J. Phys. 55, 524): what drives this cloud's multiple scattering in their shadow.
float ext_diffuse(vec3 p)
{
    return 1.0 / (1.0 + 0.75 * (1.0 - u_shadow_g) * ext_tau(p));
}
#else
float ext_tau(vec3 p)
{
    return 0.0;
}
float ext_diffuse(vec3 p)
{
    return 1.0;
}
#endif

#include "ms_diffusion.glsl"
// The same for a sample whose (delta-M scaled) optical depth toward the sun is ts.
vec3 source_from(float ts, vec3 ph0)
{
    vec3 S = ph0 * exp(-ts);
#if MS_MODE == 1
    S += octaves_source(ts / DM_SCALE);
#endif
    return S;
}

// ms.mode = diffusion also leaves the scaled medium's source in msd_S (ms_diffusion.glsl).
vec3 source(vec3 p, float ke, vec3 ph0)
{
    float ts = (sun_optical_depth(p, ke) + ext_tau(p)) * DM_SCALE;
    msd_source(p, ts);
    return source_from(ts, ph0) + msd_lobe; // ms.lobe's light: the exact single scattering's attenuation
}

#if BOUNDARY_KNOTS
// Whether the chords k0 .. k1 - 1 of the cast ray reach the core (d >= h) anywhere: each chord at its deepest point,
// its closest approach to its ellipsoid's centre in the ellipsoid's unit-sphere space (the union's distance is the
// largest of its ellipsoids', so one chord reaching its core is enough).
bool reaches_core(vec3 ro, vec3 dir, int k0, int k1)
{
    for (int j = k0; j < k1; j++) {
        int i = hit_idx[j];
        vec3 ir = u_ell_ir[i].xyz;
        vec3 q = (ro - u_ell_c[i].xyz) * ir, ds = dir * ir;
        float tc = clamp(-dot(q, ds) / dot(ds, ds), hit_t0[j], hit_t1[j]);
        if (radial_distance(ro + dir * tc, i) >= u_h)
            return true;
    }
    return false;
}
#endif

#if RAMP_KNOTS
// Where the chords k0 .. k1 - 1 of the cast ray first reach the core (d >= h): the entry into each ellipsoid shrunk
// by h (Kol's radial distance d = R(u) - |q| reaches h on the surface R(u) - h; the ellipsoid with radii r - h is it
// for a sphere and close to it otherwise: the knots it places need not be exact). 1e30 where none does.
float core_entry(vec3 ro, vec3 dir, int k0, int k1)
{
    float t_core = 1e30;
    for (int j = k0; j < k1; j++) {
        int i = hit_idx[j];
        vec3 r = 1.0 / u_ell_ir[i].xyz - u_h;
        if (min(r.x, min(r.y, r.z)) <= 0.0)
            continue; // no core: all boundary
        vec3 ir = 1.0 / r;
        vec3 q = (ro - u_ell_c[i].xyz) * ir, ds = dir * ir;
        float A = dot(ds, ds);
        float tc = -dot(q, ds) / A;
        vec3 qc = q + tc * ds;
        float h2 = 1.0 - dot(qc, qc);
        if (h2 > 0.0)
            t_core = min(t_core, tc - sqrt(h2 / A));
    }
    return t_core;
}
#endif

#if METHOD_UNIFORM && !ENERGY_PASS
#include "march_uniform.glsl"
#endif

#if MS_MODE == 2 || MS_MODE == 3
// Multiple scattering (orders 2..16+) leaving the cloud at p toward the eye, per unit sun irradiance: Bouthors' slab
// model with Kol's simplification (a fixed blur instead of the collector search). Angles per eqs. 3.56-3.57; the
// scattering angle is the true one (eq. 3.58's phi_V only enters eq. 3.32 through it). Also returns the opacity
// the fitted slab has along the view (delta-M), for weighting the interval.
float ms_slab(vec3 p, vec3 dir, float mu, out float slab_alpha, out bool lit_side)
{
    slab_alpha = 1.0;
    lit_side = true;
    float t, d, scale;
    vec3 n;
#if MS_MODE == 3
    if (!collector_search(p, dir, t, d, n))
        return 0.0;
#else
    if (!fit_slab(u_slab_a, u_slab_n, u_sun_dir, u_sun_right, u_sun_up, u_sun_R, u_slab_lod, p, p, t, d, n, scale))
        return 0.0;
#endif
    float thv = 180.0 - degrees(acos(clamp(dot(-dir, n), -1.0, 1.0)));
    float thl = degrees(acos(clamp(dot(u_sun_dir, n), -1.0, 1.0)));
    lit_side = thv > 90.0; // the eye on the side of the fitted slab the sun lights: reflected, else transmitted
    // Kol 3.4.5: seen from below the fitted slab's normal a point at d = 0 would get no light at all (a protruding
    // part lit from the side); its depth is raised to at least t / 10 there. Seen from above, d = 0 is the true exit.
    d = max(d, smoothstep(100.0, 80.0, thv) * 0.1 * t);
    slab_alpha = 1.0 - exp(-DM_SCALE * t * SLAB_KE_REF / max(abs(dot(dir, n)), 0.05));
    return slab_radiance(1, t, d, thv, thl, degrees(acos(clamp(mu, -1.0, 1.0))));
}
#endif

#if SKY_SPLIT
// Share of the ambient light at p that comes from the sky rather than the ground (Bouthors: sky and ground light
// through the isotropic group): the 16+ response of the vertical slab to light from above and from below.
float sky_share(vec3 p, vec3 dir)
{
    float t, d, scale;
    vec3 n;
    if (!fit_slab(u_sky_a, u_sky_n, vec3(0.0, 1.0, 0.0), u_sky_right, u_sky_up, u_sun_R, u_slab_lod, p, p, t, d, n,
                  scale))
        return 0.5;
    float thv = 180.0 - degrees(acos(clamp(dot(-dir, n), -1.0, 1.0)));
    float top = slab_radiance(7, t, d, thv, 0.0, 90.0);
    float bottom = slab_radiance(7, t, t - d, 180.0 - thv, 0.0, 90.0);
    return top + bottom > 1e-12 ? top / (top + bottom) : 0.5;
}
#endif

void main()
{
    vec3 eye = u_cam, dir;
    if (u_ortho) {
#if FULLSCREEN
        vec2 ndc = v_ndc;
#else
        vec2 ndc = gl_FragCoord.xy * u_inv_viewport * 2.0 - 1.0;
#endif
        vec4 w0 = u_inv_viewproj * vec4(ndc, -1.0, 1.0);
        eye = w0.xyz / w0.w;
        dir = u_view_dir;
    } else {
#if FULLSCREEN
        vec4 w = u_inv_viewproj * vec4(v_ndc, 1.0, 1.0);
        dir = normalize(w.xyz / w.w - u_cam);
#else
        dir = normalize(v_pos - u_cam);
#endif
    }
    // Start the ray near the cloud: the quadratic's terms grow like the camera distance squared, so fp32 chords
    // from far away lose digits (tests/test_precision.c). t counts from ro.
    float t_base = max(dot(-eye, dir) - u_bound_R, 0.0);
    vec3 ro = eye + dir * t_base;
    float t_end = 3.0e38;  // where the host's surface ends the ray, from ro
#if !ENERGY_PASS
    if (u_host_depth_on) {
        float d = texelFetch(u_host_depth, ivec2(gl_FragCoord.xy * u_host_scale), 0).r;
        if (d != u_host_clear) {
            vec4 q = u_host_inv_vp * vec4(gl_FragCoord.xy * u_inv_viewport * 2.0 - 1.0, 2.0 * d - 1.0, 1.0);
            if (q.w != 0.0)
                t_end = dot(q.xyz / q.w - ro, dir);
            if (t_end <= 0.0)
                NO_CLOUD;
        }
    }
#endif
    cast_ray(ro, dir);
    if (n_hits == 0)
        NO_CLOUD;

    // Per-pixel constants: the scattering angle is the same along the ray (parallel sunlight).
    float mu = dot(-u_sun_dir, -dir);   // cos Theta = s_L . v, v from the sample toward the eye
    vec3 ph0 = msd_begin(dir, mu, phase_table(mu, 0));
#if MS_MODE == 1
    octaves_phase(mu);
#endif

    float tau = 0.0;      // optical depth from the eye to the current sample
    float taup = 0.0;     // the same with the delta-M extinction, for scattered light on its way to the eye
    vec3 L = vec3(0.0);   // scattered radiance / sun irradiance, attenuated to the eye
    vec3 amb = vec3(0.0); // sky and ground light
    vec2 Lms = vec2(0.0); // the slab model's multiple scattering (grey) reflected and transmitted, to the eye
#if ENERGY_PASS
    vec3 p_first = ro;    // where the ray enters the cloud
#endif
    int k = 0, intervals = 0;
    float ext_first = 0.0; // other clouds' optical depth toward the sun where the ray enters this one
#if METHOD_UNIFORM && !ENERGY_PASS
    ext_first = ext_tau(ro + dir * hit_t0[0]);
    march_uniform(ro, dir, t_end, ph0, tau, L, amb);
#else
    while (k < n_hits && intervals < MAX_INTERVALS) {
        // Merge overlapping chords into one interval of the union so overlap regions are integrated once.
        float a, b;
        int merged, k0 = k;
        k = next_interval(k, a, b, merged);
        if (a >= t_end)
            break;
        b = min(b, t_end);
        intervals++;
        float tau0 = tau, taup0 = taup;
        // Segments in geometric progression, shortest at the entry (DESIGN: Kol's eq. 3.23 is garbled).
        // The end samples sit a hair inside the interval (Kol 3.4.4 offsets the entry point too): exactly on the
        // surface d = 0 and a thin boundary (h -> 0) would make the step from air to core invisible to the
        // trapezoids; just inside, they see the one-sided limit. Segment lengths stay those of [a, b].
        float len = b - a;
        float nudge = min(1e-3 * len, 0.05);
#if MS_MODE == 1
        octaves_interval(DM_SCALE * u_ke * len);
#endif
        // Knots: the boundary ramps get segments of their own, the core SEGMENTS per merged chord in geometric
        // progression (make_knots in density.glsl).
        knots kn = make_knots(a, len, nudge, SEGMENTS * merged, u_seg_ratio, true);
#if BOUNDARY_KNOTS
        if (!reaches_core(ro, dir, k0, k))
            kn = boundary_knots(a, len, SEGMENTS * merged, u_boundary_step);
#endif
#if RAMP_KNOTS
        // The entry ramp as the ray crosses it (longer than h where the ray enters obliquely), in even steps of at
        // most u_ramp_step: it is the noisy skin the view sees, and one trapezoid over it sees no noise at all (the
        // noise is tapered to 0 at both its ends), so silhouettes and the shadowed base came out smooth and bright:
        // 1.6x the path tracer's single scattering in a front-lit cloud's darkest fifth. The exit ramp, seen through
        // the core, keeps Kol's share.
        if (kn.nr_in > 0) {
            float rl = clamp(core_entry(ro, dir, k0, k) - a, kn.rl_in, 0.75 * len - kn.rl_out);
            kn.nr_in = clamp(int(ceil(rl / u_ramp_step)), kn.nr_in, RAMP_KNOTS_MAX);
            kn.rl_in = rl;
        }
#endif
        int nk = knot_count(kn);
        float t = a;
        vec3 p = ro + dir * (t + nudge);
        vec3 p_entry = p;     // Kol's "multiple scattering point": the interval's entry, a hair inside
        if (intervals == 1)
            ext_first = ext_tau(p_entry);
#if ENERGY_PASS
        if (intervals == 1)
            p_first = p_entry;
#endif
        float ke_prev = extinction(p, t + nudge);
        vec3 S_prev = source(p, ke_prev, ph0);
#if MS_MODE == 4
        vec3 Sd_prev = msd_S;
#endif
        for (int i = 1; i <= nk; i++) {
            bool last = i == nk;
            float t_new = last ? b : knot_t(kn, i);
            float x = t_new - t;
            t = t_new;
            float ts_at = last ? t - nudge : t;
            p = ro + dir * ts_at;
            float ke = extinction(p, ts_at);
            float dtau = x * 0.5 * (ke_prev + ke);        // eq. 3.22
            vec3 S = source(p, ke, ph0);
#if INTEGRATION_KOL
            // eq. 3.20: trapezoids of F = k_e S e^-tau. Overestimates a segment that is optically thick by the
            // factor (dtau/2) coth(dtau/2).
            L += x * 0.5 * (ke_prev * S_prev * exp(-taup) + ke * S * exp(-(taup + DM_SCALE * dtau)));
#else
            // Energy-conserving: the extinction integrated exactly, the source per unit extinction S log-linear
            // between the segment's ends (segment_source), in delta-M form (tau' = (1 - f) tau, phase
            // P~ / (1 - f)). Exact for any k_e profile when S is uniform (the furnace), and when S falls
            // exponentially along the segment, as the sunlit source does.
            L += exp(-taup) * segment_source(DM_SCALE * dtau, S_prev, S) / DM_SCALE;
#endif
#if MS_MODE == 4
            L += msd_interval(taup, DM_SCALE * dtau, Sd_prev, msd_S);
            Sd_prev = msd_S;
#endif
            tau += dtau;
            taup += DM_SCALE * dtau;
            ke_prev = ke;
            S_prev = S;
#if !ENERGY_PASS
            if (msd_reach(taup) > TAU_CUT)
                break;
#endif
        }
#if MS_MODE == 2 || MS_MODE == 3
        // The interval's multiple scattering, evaluated once at its entry (Kol 3.4.4). C is already the radiance
        // leaving the fitted slab, so it is weighted by the interval's opacity relative to the slab's own along the
        // view (1 for a ray that crosses the cloud as it crosses the slab; small where it grazes a thin edge). Kol
        // blends with the interval's opacity alone, which takes the slab's thickness into account twice.
        float slab_alpha;
        bool lit_side;
        float ms = ms_slab(p_entry, dir, mu, slab_alpha, lit_side) * ext_diffuse(p_entry);
        ms *= exp(-taup0) * min((1.0 - exp(-(taup - taup0))) / max(slab_alpha, 1e-4), 1.0);
        Lms += lit_side ? vec2(ms, 0.0) : vec2(0.0, ms);
#endif
        // Sky and ground light: an isotropic field of the environment's mean radiance J in the cloud. A uniform
        // source in a non-absorbing medium seen through optical depth tau gives J (1 - e^-tau): exact for a uniform
        // environment (cloud + transmitted background = J everywhere, the furnace test). J mixes the sky's and the
        // ground's mean radiance: half and half, or (SKY_SPLIT) as the slab model says light reaches p.
#if SKY_SPLIT
        float w_sky = sky_share(p_entry, dir);
#else
        float w_sky = 0.5;
#endif
        amb += exp(-tau0) * (1.0 - exp(-(tau - tau0))) * mix(u_ground_rad, u_sky_rad, w_sky);
#if !ENERGY_PASS
        if (msd_reach(taup) > TAU_CUT)
            break;
#endif
    }
#endif
#if PHASE_PEAK && !ENERGY_PASS
    // The removed peak (Kol eqs. 3.66-3.69): light scattered into the forward peak and still on the beam. With the
    // delta-M extinction (1 - f) k_e of the chopped medium that is e^(-(1-f) tau) - e^(-tau), spread over angles as
    // P_p / f. Its thin limit is P_p tau, single scattering of the peak, as it must be; Kol's printed form
    // P_p (e^(-f tau) - e^(-tau)) tends to (1 - f) P_p tau instead, so we do not use it.
    vec3 pp = phase_table(mu, 1);
    if (pp.g > 0.0)
        L += pp / max(u_peak_f, vec3(1e-6)) * (exp(-(1.0 - u_peak_f) * tau) - vec3(exp(-tau))) * exp(-ext_first);
#endif
    float alpha = 1.0 - exp(-tau);
#if ENERGY_PASS
    // Per unit sun irradiance, without the forward peak: single scattering, multiple scattering reflected and
    // transmitted before the closure's gains. From the sun: the column's optical depth and the cosine of the sun's
    // angle to the slab fitted where it enters (the slab's thickness is the column's times that cosine).
    if (u_budget_view) {
        float st, sd, sscale;
        vec3 sn;
        float cos_l = 1.0;
        if (fit_slab(u_slab_a, u_slab_n, u_sun_dir, u_sun_right, u_sun_up, u_sun_R, u_slab_lod, p_first, p_first, st,
                     sd, sn, sscale))
            cos_l = max(dot(sn, u_sun_dir), 0.05);
        o_color = vec4(tau, cos_l, 0.0, 0.0);
        return;
    }
    o_color = vec4(L.g, Lms, 0.0);
    return;
#endif
#if MS_MODE == 2 || MS_MODE == 3
    L += vec3(dot(u_ms_gain, Lms));
#endif
    o_color = vec4(min((u_sun_irr * L + amb) * u_out_scale, vec3(u_out_max)), alpha);
    DEPTH_OUT(alpha, t_base + max(hit_t0[0], 0.0));
}
