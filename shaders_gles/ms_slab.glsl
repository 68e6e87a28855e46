// shaders_gles/ms_slab.glsl: multiple scattering from Bouthors' slab model (Kol 3.1.4, 3.4.5, eqs. 3.32, 3.55-3.58,
// 3.70). A plane-parallel slab is fitted to the cloud around a point from the mipmapped slab maps (slab_map.frag),
// and the fitted per-group functions of eq. 3.32 (data/slab_fit_bouthors.txt, made by tools/slab) give the radiance
// of scattering orders 2..16+. The CPU twin is src/core/slabmodel.c (cu_slab_model_eval): same interpolation, clamps and
// extrapolation, so tests can compare the two. Needs density.glsl (PI), SLAB_NT/NV/NL/NP.
uniform sampler2D u_slab_tab;   // RGBA32F, one row per (group 2..16+, thickness): (A1,B1,C,D)@thV, (A2,B2)@thL, P@Theta
uniform float u_slab_t[SLAB_NT];
uniform float u_slab_thv[SLAB_NV];
uniform float u_slab_thl[SLAB_NL];
uniform float u_slab_th[SLAB_NP];
const float SLAB_KE_REF = 0.0905; // m^-1, the extinction the tables' metres refer to

// Bracketing node i and weight w of x on an ascending node list, clamped at both ends (bracket() in slabmodel.c).
// One function per list: GLSL ES has no unsized array parameters (and no line continuation for a macro).
int bracket_th(float x, out float w)
{
    w = 0.0;
    if (SLAB_NP < 2 || x <= u_slab_th[0]) return 0;
    if (x >= u_slab_th[SLAB_NP - 1]) { w = 1.0; return SLAB_NP - 2; }
    int i = 0;
    for (int j = 1; j < SLAB_NP - 1; j++) if (x > u_slab_th[j]) i = j;
    w = (x - u_slab_th[i]) / (u_slab_th[i + 1] - u_slab_th[i]);
    return i;
}
int bracket_thv(float x, out float w)
{
    w = 0.0;
    if (SLAB_NV < 2 || x <= u_slab_thv[0]) return 0;
    if (x >= u_slab_thv[SLAB_NV - 1]) { w = 1.0; return SLAB_NV - 2; }
    int i = 0;
    for (int j = 1; j < SLAB_NV - 1; j++) if (x > u_slab_thv[j]) i = j;
    w = (x - u_slab_thv[i]) / (u_slab_thv[i + 1] - u_slab_thv[i]);
    return i;
}
int bracket_thl(float x, out float w)
{
    w = 0.0;
    if (SLAB_NL < 2 || x <= u_slab_thl[0]) return 0;
    if (x >= u_slab_thl[SLAB_NL - 1]) { w = 1.0; return SLAB_NL - 2; }
    int i = 0;
    for (int j = 1; j < SLAB_NL - 1; j++) if (x > u_slab_thl[j]) i = j;
    w = (x - u_slab_thl[i]) / (u_slab_thl[i + 1] - u_slab_thl[i]);
    return i;
}
int bracket_t(float x, out float w)
{
    w = 0.0;
    if (SLAB_NT < 2 || x <= u_slab_t[0]) return 0;
    if (x >= u_slab_t[SLAB_NT - 1]) { w = 1.0; return SLAB_NT - 2; }
    int i = 0;
    for (int j = 1; j < SLAB_NT - 1; j++) if (x > u_slab_t[j]) i = j;
    w = (x - u_slab_t[i]) / (u_slab_t[i + 1] - u_slab_t[i]);
    return i;
}

// Eq. 3.32 at one node pair without cos thL, in log space (slabmodel.c: node_value), capped by the fit's bound.
float slab_node(int row, int iv, int il, float d, float log_p, float log_bound)
{
    vec4 v = texelFetch(u_slab_tab, ivec2(iv, row), 0);            // log A1, B1, C, D
    vec3 l = texelFetch(u_slab_tab, ivec2(SLAB_NV + il, row), 0).xyz; // log A2, B2, energy scaling kappa
    float B = v.y - l.y;
    float num = log(d + v.w), den = log(max(B + v.w, 1e-9));
    den = max(den * den, 1e-8);   // eq. 3.32 is singular where B* + D* = 1 (the fitter's guard)
    float lc = log_p + v.x + l.x + log(max(num * num, 1e-30)) - log(den) - (d - B) * (d - B) / max(2.0 * v.z * v.z, 1e-12);
    return exp(min(lc, log_bound)) * l.z;
}

float slab_group_at(int row, float d, int ip, float wp, int iv, float wv, int il, int il1, float wl)
{
    vec2 p0 = texelFetch(u_slab_tab, ivec2(SLAB_NV + SLAB_NL + ip, row), 0).xy;
    float p1 = texelFetch(u_slab_tab, ivec2(SLAB_NV + SLAB_NL + ip + 1, row), 0).x;
    float log_bound = texelFetch(u_slab_tab, ivec2(SLAB_NV + SLAB_NL, row), 0).y;
    float lp = mix(p0.x, p1, wp);
    float v00 = slab_node(row, iv, il, d, lp, log_bound), v10 = slab_node(row, iv + 1, il, d, lp, log_bound);
    float v01 = slab_node(row, iv, il1, d, lp, log_bound), v11 = slab_node(row, iv + 1, il1, d, lp, log_bound);
    return mix(mix(v00, v10, wv), mix(v01, v11, wv), wl);
}

// Sum of groups g_first..7 (1 = orders 2..16+, 7 = only 16+): I / F_sun in sr^-1 for a slab of thickness t and
// depth d (metres at SLAB_KE_REF), view altitude thv, sun angle thl, scattering angle theta (degrees).
float slab_radiance(int g_first, float t, float d, float thv, float thl, float theta)
{
    if (!(t > 0.0))
        return 0.0;
    d = clamp(d, 0.0, t);
    float rel = d / t;
    int ip, iv, il, k;
    float wp, wv, wl, wt;
    ip = bracket_th(theta, wp);
    iv = bracket_thv(thv, wv);
    il = bracket_thl(thl, wl);
    int il1 = SLAB_NL > 1 ? il + 1 : il;
    float t0 = u_slab_t[0], t1 = u_slab_t[SLAB_NT - 1];
    // thickness: linear in log t between nodes at the same relative depth; outside, see slabmodel.c
    int k1;
    float extra = 1.0;
    if (t <= t0) {
        k = 0; k1 = 0; wt = 0.0;
    } else if (t >= t1) {
        k = SLAB_NT - 1; k1 = k; wt = 0.0;
        extra = (1.0 - rel) + rel * t1 / t;
    } else {
        k = bracket_t(t, wt);
        k1 = k + 1;
        wt = log(t / u_slab_t[k]) / log(u_slab_t[k1] / u_slab_t[k]);
    }
    const int min_order[8] = int[8](1, 2, 3, 4, 5, 7, 10, 16);
    float sum = 0.0;
    for (int g = g_first; g < 8; g++) {
        int row0 = (g - 1) * SLAB_NT + k, row1 = (g - 1) * SLAB_NT + k1;
        float c = slab_group_at(row0, rel * u_slab_t[k], ip, wp, iv, wv, il, il1, wl);
        if (k1 != k)
            c = mix(c, slab_group_at(row1, rel * u_slab_t[k1], ip, wp, iv, wv, il, il1, wl), wt);
        if (t <= t0)
            c *= pow(t / t0, float(min_order[g]));
        sum += c * extra;
    }
    return sum * cos(radians(clamp(thl, 0.0, 90.0)));
}

// A slab fitted for viewpoint p from a mipmapped slab map seen from direction ldir (toward the light), sampled around
// q (p itself, or the collector's centre) at level lod: thickness t and depth d in table metres, the slab normal n,
// and scale = table metres per metre. False where the map has no cloud.
bool fit_slab(sampler2D A, sampler2D N, vec3 ldir, vec3 right, vec3 up, float R, float lod, vec3 q, vec3 p,
              out float t, out float d, out vec3 n, out float scale)
{
    t = 0.0; d = 0.0; n = ldir; scale = 1.0;
    vec2 uv = vec2(dot(q, right), dot(q, up)) / R * 0.5 + 0.5;
    vec4 a = textureLod(A, uv, lod);
    if (a.x < 1e-3)
        return false;
    float hm = a.y / a.x * R, chord = a.z / a.x * R, tau = a.w / a.x; // entry height along ldir, length, tau
    vec3 nn = textureLod(N, uv, lod).xyz;
    n = dot(nn, nn) > 1e-12 ? normalize(nn) : ldir;
    // The blurred normal faces the light where the cloud is convex; never let the slab face away from it.
    float cos_l = max(dot(n, ldir), 0.05);
    // Bouthors: m = the blurred first surface, d = (m - p).n (eq. 3.55), so d = (depth below m along the light) cos
    // thL. The slab thickness is the in-cloud length cos thL, so the light crosses the slab along the mean chord. Both
    // scaled to the tables' extinction by the mean extinction along the chords (tau / chord).
    scale = tau / max(chord, 1e-6) / SLAB_KE_REF;
    t = chord * cos_l * scale;
    d = max(hm - dot(p, ldir), 0.0) * cos_l * scale;
    return true;
}
