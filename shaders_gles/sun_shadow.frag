#version 300 es
// shaders_gles/sun_shadow.frag: the optical depth of one cloud along the sun's rays, for shadows cast on others: each
// texel's ray starts at u_origin + u_ax (2u - 1) + u_ay (2v - 1) (the cloud's frame, before the cloud) and runs
// along u_dir; the real density without noise (a shadow a few hundred metres off blurs the boundary's noise away) is
// integrated over every interval of the union. Drawn once per casting cloud with additive blending (pass_shadow.c),
// into another cloud's shadow map or the ground's. Needs density.glsl's NUM_ELL, NOISE 0, PROFILE_KOL.
#include "density.glsl"
uniform vec3 u_origin, u_ax, u_ay, u_dir;
uniform vec2 u_size;          // the target's texels
out vec4 o_tau;

void main()
{
    vec2 uv = gl_FragCoord.xy / u_size;
    vec3 ro = u_origin + u_ax * (2.0 * uv.x - 1.0) + u_ay * (2.0 * uv.y - 1.0);
    cast_ray(ro, u_dir);
    float tau = 0.0;
    int k = 0;
    while (k < n_hits) {
        float a, b;
        int merged;
        k = next_interval(k, a, b, merged);
        vec4 q;
        vec2 qn;
        tau += integrate_interval(ro, u_dir, a, b, 8 * merged, true, false, q, qn);
    }
    o_tau = vec4(tau, 0.0, 0.0, 1.0);
}
