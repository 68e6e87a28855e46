// shaders_gles/march_uniform.glsl: the uniform ray march (quality.method = uniform), included by cloud.frag after
// source_from() and the sky terms when METHOD_UNIFORM (and not the energy pass).
// The mainstream method (Schneider's Nubis, Hillaire's Frostbite, Unreal): the trade study's baseline. No sun maps:
// the optical depth toward the sun is marched at every sample to the edge of the cloud's bounding sphere, in
// UNIFORM_SUN_STEPS steps growing geometrically (short near the sample, where the light's attenuation is resolved
// first), midpoint rule. The ratio 1 + 4 / M (3 for two steps, 2 for four, 1.125 for 32) lets the longest step shrink
// as M grows, so the march converges; a fixed ratio of 2 would leave half the path to one sample.
const float SUN_RATIO = 1.0 + 4.0 / float(UNIFORM_SUN_STEPS);
float sun_march(vec3 p)
{
    float b = dot(p, u_sun_dir), c = dot(p, p) - u_bound_R * u_bound_R;
    float len = sqrt(max(b * b - c, 0.0)) - b;
    if (len <= 0.0)
        return 0.0;
    float x = len * (SUN_RATIO - 1.0) / (pow(SUN_RATIO, float(UNIFORM_SUN_STEPS)) - 1.0), s = 0.0, tau = 0.0;
    for (int j = 0; j < UNIFORM_SUN_STEPS; j++) {
        tau += x * extinction_anywhere(p + u_sun_dir * (s + 0.5 * x));
        s += x;
        x *= SUN_RATIO;
    }
    return tau;
}

// UNIFORM_STEPS steps of equal length from the ray's first entry into the cloud to its last exit (or the host's
// surface), jittered per pixel, each step's source held constant and its attenuation integrated exactly (Hillaire
// 2016): single scattering through the scene's phase function, octaves for multiple scattering (MS_MODE 1), the same
// isotropic sky and ground light as Kol's intervals. Ends when the delta-M transmittance is below e^-TAU_CUT, as
// Kol's march does.
void march_uniform(vec3 ro, vec3 dir, float t_end, vec3 ph0, inout float tau, inout vec3 L, inout vec3 amb)
{
    float a = hit_t0[0], b = hit_t1[0];
    for (int k = 1; k < n_hits; k++)
        b = max(b, hit_t1[k]);
    b = min(b, t_end);
    if (b <= a)
        return;
    float dt = (b - a) / float(UNIFORM_STEPS);
    // interleaved gradient noise (Jimenez 2014): a fixed offset per pixel, so a still picture is stable
    float jit = fract(52.9829189 * fract(dot(gl_FragCoord.xy * u_px_map.xy + u_px_map.zw,
                                             vec2(0.06711056, 0.00583715))));
    vec3 J = mix(u_ground_rad, u_sky_rad, 0.5);
    float taup = 0.0;
#if MS_MODE == 1
    octaves_interval(DM_SCALE * u_ke * (b - a));
#endif
    for (int i = 0; i < UNIFORM_STEPS; i++) {
        float t = a + (float(i) + jit) * dt;
        vec3 p = ro + dir * t;
        float ke = extinction(p, t);
        if (ke <= 0.0)
            continue;
        float dtau = ke * dt;
        vec3 S = source_from((sun_march(p) + ext_tau(p)) * DM_SCALE, ph0);
        L += exp(-taup) * S * (1.0 - exp(-DM_SCALE * dtau)) / DM_SCALE;
        amb += exp(-tau) * (1.0 - exp(-dtau)) * J;
        tau += dtau;
        taup += DM_SCALE * dtau;
        if (taup > TAU_CUT)
            break;
    }
}
