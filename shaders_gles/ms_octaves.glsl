// shaders_gles/ms_octaves.glsl: multiple scattering as octaves (Wrenninge 2015, MS_MODE 1), included by cloud.frag
// after hg() and DM_SCALE. Octave o (1 .. MS_OCTAVES - 1) is a copy of the single-scattering source with the optical
// depth toward the sun times a^o, the scattering times b^o and the anisotropy times c^o; a, b, c and the octave count
// are fitted to the path tracer (docs/ms_octaves_fit.md, tools/sweep/fit.c), not the textbook factors.
//
// The octaves attenuate by a^o of the optical depth itself, not the delta-M one: diffused light depends on the
// medium's transport, (1 - g) k_e (van de Hulst's similarity), not on how much of the phase function's peak the table
// chopped off, so one fit serves the Mie table and Henyey-Greenstein alike.
uniform vec3 u_ms_abc;         // octave factors a (extinction), b (scattering), c (anisotropy)
uniform float u_ms_g;          // anisotropy of the octave phase functions

float ph_oct[MS_OCTAVES];      // b^o hg(g c^o, mu) for this pixel's scattering angle (octaves_phase)

// 1 - e^-tau_c for the optical size tau_c (delta-M) of the cloud the ray is in: the chance that scattered light
// scatters once more before it leaves. Octave o is light scattered about o + 1 times, so it is weighted by oct_keep^o:
// the thin limit of order o + 1 goes as tau_c^o, and a thick cloud keeps every octave (1).
float oct_keep = 1.0;

// The octaves' phase functions for the cosine mu of the scattering angle (the same along the ray: parallel sunlight).
void octaves_phase(float mu)
{
    float bo = 1.0, go = u_ms_g;
    for (int o = 1; o < MS_OCTAVES; o++) {
        bo *= u_ms_abc.y; go *= u_ms_abc.z;
        ph_oct[o] = bo * hg(go, mu);
    }
}

// The interval the ray is in has delta-M optical size tau_c: the thin-cloud weight of its octaves.
void octaves_interval(float tau_c)
{
    oct_keep = 1.0 - exp(-tau_c);
}

// The octaves' source per unit of sun irradiance at a sample whose optical depth toward the sun (not delta-M) is t.
vec3 octaves_source(float t)
{
    vec3 S = vec3(0.0);
    float ao = 1.0, keep = 1.0;
    for (int o = 1; o < MS_OCTAVES; o++) {
        ao *= u_ms_abc.x;
        keep *= oct_keep;
        S += vec3(keep * ph_oct[o] * exp(-ao * t));
    }
    return S;
}
