// shaders_gles/ms_diffusion.glsl: multiple scattering from the cloud's own diffusion solution (MS_MODE 4, ms.mode =
// diffusion), included by cloud.frag after ext_diffuse() and DM_SCALE. src/core/ms_diffusion.c solves flux-limited
// diffusion of the sunbeam's first scattering on a grid over the cloud; the cloud pass reads the fluence phi and flux
// F here (per unit sun irradiance, trilinear): the diffuse radiance is L(w) = (phi + 3 F.w) / 4pi (P1), and what it
// scatters toward the eye per unit extinction, through the chopped phase function of asymmetry g (the peak stays on
// its way), is (1 - f) (phi + 3 g F.w) / 4pi with w the direction toward the eye. Single scattering stays with the
// exact phase function (source_from): this is light scattered twice and more. Without MS_MODE 4, zero.
#if MS_MODE == 4
uniform highp sampler3D u_msd; // RGBA16F: phi, F (pass_msd.c)
uniform vec3 u_msd_lo;         // cloud-local corner of the grid
uniform vec3 u_msd_size;       // its extent (m)
uniform vec2 u_msd_k;          // (1 - f) / 4pi and 3 g
vec3 msd_dir;                  // the ray's direction

void msd_begin(vec3 dir)
{
    msd_dir = dir;
}

vec3 grid_source(vec3 p)
{
    vec4 v = texture(u_msd, (p - u_msd_lo) / u_msd_size);
    return vec3(u_msd_k.x * max(v.x - u_msd_k.y * dot(v.yzw, msd_dir), 0.0) * ext_diffuse(p));
}
#else
void msd_begin(vec3 dir)
{
}

vec3 grid_source(vec3 p)
{
    return vec3(0.0);
}
#endif
