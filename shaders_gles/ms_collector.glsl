// shaders_gles/ms_collector.glsl: Bouthors' iterative collector search (Kol 3.1.4, eqs. 3.59-3.63), the accurate
// alternative to Kol's fixed blur (ms.mode = collector). Start from the viewpoint with a collector as large as the
// cloud; fit a slab from the sun's slab maps averaged over the collector (mip level from its width); look up where
// the light reaching the viewpoint entered that slab and how widely (data/slab_collector.txt, tabulated from the slab
// simulations by scripts/collector_table.sh); move the collector there with Bouthors' step limits (centre by at
// most sigma/2, width by at most half its size), until the centre moves less than sigma/10 (eq. 3.63) and the width
// has settled too, or COLL_ITER steps.
// Needs ms_slab.glsl (fit_slab) and sunmap.glsl's sun frame; COLL_NT/NL/NV/NP, COLL_ITER.
uniform sampler2D u_coll;          // RGBA32F (cx, cz, sigma) in table metres; x = phi * 11 + depth, y = (t, thL, thV)
uniform float u_coll_t[COLL_NT];
uniform float u_coll_thl[COLL_NL];
uniform float u_coll_thv[COLL_NV];
uniform float u_coll_phi[COLL_NP];

int coll_nearest_thl(float x)
{
    int best = 0;
    for (int i = 1; i < COLL_NL; i++)
        if (abs(u_coll_thl[i] - x) < abs(u_coll_thl[best] - x)) best = i;
    return best;
}

int coll_nearest_phi(float x)
{
    int best = 0;
    for (int i = 1; i < COLL_NP; i++)
        if (abs(u_coll_phi[i] - x) < abs(u_coll_phi[best] - x)) best = i;
    return best;
}

vec3 coll_fetch(int it, int il, int j, int iv, int ip)
{
    return texelFetch(u_coll, ivec2(ip * 11 + j, (it * COLL_NL + il) * COLL_NV + iv), 0).xyz;
}

// Collector (cx, cz, sigma) in table metres for a slab of thickness t (table metres): linear in log t, relative
// depth and theta_V, nearest in theta_L and phi_V (phi in [0, 180]). Outside the thickness nodes the geometry is
// scaled with t.
vec3 coll_lookup(float t, float d, float thv, float thl, float phi)
{
    float tc = clamp(t, u_coll_t[0], u_coll_t[COLL_NT - 1]);
    float k = 1.0;
    int it = 0;
    for (int i = 1; i < COLL_NT - 1; i++) if (tc > u_coll_t[i]) it = i;
    int it1 = min(it + 1, COLL_NT - 1);
    float wt = it1 > it ? clamp(log(tc / u_coll_t[it]) / log(u_coll_t[it1] / u_coll_t[it]), 0.0, 1.0) : 0.0;
    float jd = clamp(d / max(t, 1e-6), 0.0, 1.0) * 10.0;
    int j = min(int(jd), 9);
    float wj = jd - float(j);
    int iv = 0;
    for (int i = 1; i < COLL_NV - 1; i++) if (thv > u_coll_thv[i]) iv = i;
    float wv = clamp((thv - u_coll_thv[iv]) / (u_coll_thv[iv + 1] - u_coll_thv[iv]), 0.0, 1.0);
    int il = coll_nearest_thl(thl), ip = coll_nearest_phi(phi);
    vec3 r = vec3(0.0);
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++)
            for (int c = 0; c < 2; c++) {
                float w = (a == 0 ? 1.0 - wt : wt) * (b == 0 ? 1.0 - wj : wj) * (c == 0 ? 1.0 - wv : wv);
                r += w * coll_fetch(a == 0 ? it : it1, il, j + b, iv + c, ip);
            }
    return r * (t / tc);
}

bool collector_search(vec3 p, vec3 dir, out float t, out float d, out vec3 n)
{
    float texel = 2.0 * u_sun_R / float(u_sun_size);
    vec3 c = p;
    float sigma = u_sun_R;   // Bouthors' start: the collector as large as the cloud
    float scale;
    for (int i = 0; i < COLL_ITER; i++) {
        float lod = log2(max(2.0 * sigma / texel, 1.0));
        if (!fit_slab(u_slab_a, u_slab_n, u_sun_dir, u_sun_right, u_sun_up, u_sun_R, lod, c, p, t, d, n, scale))
            return false;
        // Bouthors' frame (Kol Fig. 3.6): y = n, the sun's horizontal propagation along -z, x = y cross z
        vec3 z = u_sun_dir - dot(u_sun_dir, n) * n;
        z = dot(z, z) > 1e-8 ? normalize(z) : normalize(cross(n, abs(n.x) < 0.9 ? vec3(1, 0, 0) : vec3(0, 0, 1)));
        vec3 x = cross(n, z);
        vec3 sv = -dir;
        float thv = 180.0 - degrees(acos(clamp(dot(sv, n), -1.0, 1.0)));
        float thl = degrees(acos(clamp(dot(u_sun_dir, n), -1.0, 1.0)));
        float phi = degrees(atan(dot(sv, x), -dot(sv, z)));  // eq. 3.58's phi_V, signed
        vec3 col = coll_lookup(t, d, thv, thl, abs(phi)) / scale;  // to metres
        if (phi < 0.0)
            col.x = -col.x;                                  // c_x is odd in phi_V
        vec3 cn = p + n * (d / scale) + x * col.x + z * col.y;  // on the fitted slab's lit face
        float target = max(col.z, 0.5 * texel);
        float sn = clamp(target, 0.5 * sigma, 1.5 * sigma);   // eq. 3.62
        vec3 step = cn - c;
        float len = length(step);
        if (len > 0.5 * sigma)
            cn = c + step * (0.5 * sigma / len);             // eq. 3.61
        // eq. 3.63, and the width too: from Bouthors' start (sigma as large as the cloud) the centre of a uniform
        // slab never moves, and stopping on the centre alone would keep a collector kilometres wide
        bool converged = len < 0.1 * sigma && abs(target - sigma) < 0.1 * sigma;
        c = cn;
        sigma = sn;
        if (converged)
            break;
    }
    float lod = log2(max(2.0 * sigma / texel, 1.0));
    return fit_slab(u_slab_a, u_slab_n, u_sun_dir, u_sun_right, u_sun_up, u_sun_R, lod, c, p, t, d, n, scale);
}
