// shaders_gles/ms_diffusion.glsl: multiple scattering from the cloud's own diffusion solution (MS_MODE 4, ms.mode =
// diffusion), included by cloud.frag after ext_diffuse(), segment_source() and DM_SCALE. src/core/ms_diffusion.c
// solves flux-limited diffusion on a grid over the cloud in a delta-M medium: the phase function's forward lobe
// (f_d = g^2 of what the chop left, g its mean cosine) counts as unscattered, the rest has asymmetry g' = g / (1 + g)
// and the extinction (1 - f) k_e, (1 - f) = (1 - f_chop)(1 - f_d) (pass_msd.c). Diffusion of a medium as forward-
// peaked as a cloud's is only accurate so (Joseph, Wiscombe & Weinman 1976): in plain P1 the radiance leaving the
// cloud near its surface is too smooth in angle, and every view came out 10-35 % dark.
// The radiance then follows Nakajima & Tanaka's (1988) split: the exact single scattering of the unscaled beam stays
// in source_from() (phase ph0 - msd_ph, attenuated by the true optical depths), and everything else is the scaled
// medium's: its own single scattering (msd_ph, the beam e^-(1-f) tau_s) and the diffuse light (phi + 3 g' F.w) / 4pi
// read from the grid (per unit sun irradiance, trilinear), both attenuated toward the eye by the scaled optical
// depth (msd_interval). msd_ph = min((1 - f) HG(g', mu), ph0): away from the forward lobe the scaled medium's single
// scattering uses the exact phase function (Nakajima & Tanaka's TMS); inside it, the lobe's excess stays exact, so
// it is counted once. Without MS_MODE 4, nothing.

// The march ends where the transmittance to the eye falls below e^-TAU_CUT (6e-6) for the light that reaches
// farthest (the delta-M medium's, or diffusion's scaled one: msd_reach): nothing behind can add more than that
// fraction of its source, and a ray through a thick cloud spends most of its samples behind it (Kol's segments grow
// away from the entry; the exit ramp and the intervals behind come last). Not in the energy pass, which wants the
// whole column.
#define TAU_CUT 12.0

#if MS_MODE == 4
uniform highp sampler3D u_msd; // RGBA16F: phi, F (pass_msd.c)
uniform vec3 u_msd_lo;         // cloud-local corner of the grid
uniform vec3 u_msd_size;       // its extent (m)
uniform vec3 u_msd_dm;         // 1 - f_d (the scaled over the chopped extinction), g', 1 - f
vec3 msd_dir;                  // the ray's direction
vec3 msd_ph;                   // the scaled medium's phase per unit extinction toward the eye, this ray
vec3 msd_S;                    // the scaled medium's source at the last sample (msd_source)
#if MSD_LOBE
// ms.lobe (src/core/ms_lobe.c): light the forward lobe alone carries to the eye, n >= 1 lobe scatterings on the way
// in and one toward it, which the scaled medium counts as still on the sun's line. Rows 2 .. 2 + LOBE_ROWS - 1 of
// the phase texture over the scattering angle and the chopped optical depth toward the sun ts (rows at
// ts = LOBE_TS_MAX (r / (LOBE_ROWS - 1))^2). It is attenuated toward the eye as the exact single scattering is, by
// the chopped optical depth: one more lobe scattering on the way out is a longer lobe-only path, counted where it
// happens. LOBE_ROWS and LOBE_TS_MAX come from the renderer's defines (CU_LOBE_ROWS, CU_LOBE_TS_MAX of ms_lobe.h).
int msd_lobe_col;              // the ray's scattering angle's column of the table
vec3 msd_lobe;                 // the lobe's light at the last sample (msd_source)
#else
const vec3 msd_lobe = vec3(0.0);
#endif

// Per ray: its direction and the source phase split; returns what stays with the exact single scattering.
vec3 msd_begin(vec3 dir, float mu, vec3 ph0)
{
    msd_dir = dir;
#if MSD_LOBE
    msd_lobe_col = int(acos(clamp(mu, -1.0, 1.0)) / PI * float(u_phase_n - 1) + 0.5);
#endif
    msd_ph = min(vec3(u_msd_dm.z * hg(u_msd_dm.y, mu)), ph0);
    return ph0 - msd_ph;
}

// The scaled medium's source at p per unit extinction, ts the chopped optical depth toward the sun (other clouds'
// included): its single scattering plus the grid's diffuse light.
void msd_source(vec3 p, float ts)
{
    vec4 v = texture(u_msd, (p - u_msd_lo) / u_msd_size);
    msd_S = msd_ph * exp(-u_msd_dm.x * ts) +
            vec3(u_msd_dm.z / (4.0 * PI) * max(v.x - 3.0 * u_msd_dm.y * dot(v.yzw, msd_dir), 0.0) * ext_diffuse(p));
#if MSD_LOBE
    float r = sqrt(min(ts / LOBE_TS_MAX, 1.0)) * float(LOBE_ROWS - 1);
    int i = min(int(r), LOBE_ROWS - 2);
    msd_lobe = mix(texelFetch(u_phase, ivec2(msd_lobe_col, 2 + i), 0).rgb,
                   texelFetch(u_phase, ivec2(msd_lobe_col, 3 + i), 0).rgb, r - float(i));
#endif
}

// What a segment of chopped optical depth dt at chopped depth taup from the eye sends to the eye, from the scaled
// sources S0 and S1 at its ends: attenuated by the scaled optical depth, per unit of the true extinction.
vec3 msd_interval(float taup, float dt, vec3 S0, vec3 S1)
{
    float x = u_msd_dm.x;
    return exp(-x * taup) * segment_source(x * dt, S0, S1) / (x * DM_SCALE);
}

// The optical depth the farthest-reaching light toward the eye has crossed at chopped depth taup: the scaled
// medium's, which attenuates the diffuse light less than the chopped one does (x = 1 - f_d < 1). The march's end
// (TAU_CUT) is judged on it.
float msd_reach(float taup)
{
    return u_msd_dm.x * taup;
}
#else
const vec3 msd_lobe = vec3(0.0);
vec3 msd_begin(vec3 dir, float mu, vec3 ph0)
{
    return ph0;
}

void msd_source(vec3 p, float ts)
{
}

float msd_reach(float taup)
{
    return taup;
}
#endif
