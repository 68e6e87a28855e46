#version 300 es
// shaders_gles/sky.frag: background radiance: Preetham et al. 1999 analytic sky (Perez distribution of Y, x, y, read
// as the product of its zenith and sun factors from the tables of sky.c: cu_sky_tables, in sky.glsl) or a constant sky,
// the sun disk, and a Lambertian ground below the horizon. Output: linear RGB radiance (kcd/m^2 units); with
// SKY_TONEMAP (a frame with no cloud in view) the display's colour straight away, as the tone map would make it.
#include "sky.glsl"
#if SKY_VERTEX == 1
in vec3 v_sky;                 // the sky's exposed radiance at this pixel, interpolated from the grid's corners
#elif SKY_VERTEX == 2
flat in vec3 v_flat;           // the colour of every pixel, the display's curve applied (sky.vert)
#else
in vec4 v_near, v_far;         // the pixel's points on the near and far planes, homogeneous (sky.vert)
#endif
#if GROUND_SHADOW
uniform vec3 u_ground_sun;     // the part of it the sun lights directly
uniform sampler2D u_ground_tau;// the clouds' optical depth toward the sun above each ground point (pass_shadow.c),
uniform sampler2D u_ground_tau2;// a map for each wind the clouds ride (frame_ground.c; the second may hold zeros)
uniform vec3 u_eye;            // the camera, world metres
uniform vec3 u_gmap, u_gmap2;  // each map's centre (x, z) and side (m)
uniform float u_shadow_g;
// The clouds' shadow on the ground: sunlight through optical depth tau, direct and diffuse, as a conservative
// two-stream slab transmits it: 1 / (1 + 3/4 (1 - g) tau) (Bohren 1987). The sky light is not shadowed.
float tau_in(sampler2D map, vec3 gmap, vec2 g)
{
    vec2 uv = (g - gmap.xy) / gmap.z + 0.5;
    return any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) ? 0.0 : texture(map, uv).r;
}
// GROUND_MAPS (pass_sky.c): how many of the maps hold shadows this frame; the others are not read.
vec3 ground(vec3 dir)
{
#if GROUND_MAPS == 0
    return u_ground;
#else
    float t = -u_eye.y / min(dir.y, -1e-6);
    vec2 g = u_eye.xz + dir.xz * t;
    if (u_eye.y <= 0.0)
        return u_ground;
    float tau = tau_in(u_ground_tau, u_gmap, g);
#if GROUND_MAPS > 1
    tau += tau_in(u_ground_tau2, u_gmap2, g);
#endif
    return u_ground - u_ground_sun * (1.0 - 1.0 / (1.0 + 0.75 * (1.0 - u_shadow_g) * tau));
#endif
}
#else
vec3 ground(vec3 dir)
{
    return u_ground;
}
#endif
out vec4 o_color;
#if SKY_TONEMAP
#include "tonecurve.glsl"
#endif
#if SKY_COMPOSITE
// The cloud image (quality.cloud_downsample, temporal_grid) composited over the sky here, on its way to the output:
// one pass instead of the sky's, the upsampling's and the tone map's. Premultiplied, in the sky's exposed units;
// bilinear from the four nearest of its texels, as upsample.frag does without a host depth.
uniform highp sampler2D u_clouds;
uniform float u_cloud_factor;  // output pixels per texel of the cloud image
uniform bool u_refined_on;     // quality.edge_refine: u_refined holds the marked pixels at full resolution
uniform highp sampler2D u_refined; // premultiplied; alpha 2 where not marked (pass_refine.h)
vec4 clouds_at(vec2 frag)
{
    if (u_refined_on) {
        vec4 r = texelFetch(u_refined, ivec2(frag), 0);
        if (r.a <= 1.5)
            return r;
    }
    vec2 q = frag / u_cloud_factor - 0.5;
    ivec2 t0 = ivec2(floor(q)), size = textureSize(u_clouds, 0);
    vec2 f = q - floor(q);
    vec4 sum = vec4(0.0);
    for (int k = 0; k < 4; k++) {
        ivec2 o = ivec2(k & 1, k >> 1);
        float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        sum += w * texelFetch(u_clouds, clamp(t0 + o, ivec2(0), size - 1), 0);
    }
    return sum;
}
#endif

#if !SKY_CONSTANT
// Above the horizon: the Perez sky and the sun's disk.
vec3 sky_above(vec3 dir)
{
    vec3 L = perez_sky(dir);
    // Sun disk: angular radius 0.2666 deg, solid angle 6.8e-5 sr; radiance = irradiance / solid angle.
    if (dot(dir, u_sun_dir) > 0.99998917)
        L += u_sun_irr / 6.8e-5;
    return L;
}
#endif

void main()
{
#if SKY_VERTEX == 2
    o_color = vec4(v_flat, 1.0); // tone-mapped already where SKY_TONEMAP; never with SKY_COMPOSITE (pass_sky.c)
#elif SKY_VERTEX == 1
    // The grid's cells hold no sun disk, no horizon and no ground shadow (pass_sky.c draws those a pixel at a time);
    // with SKY_CORNER_TONE their values are the display's already.
    o_color = vec4(v_sky, 1.0);
#else
    // The ray's direction from two depths (a perspective ray through the origin, or an orthographic view's one).
    vec3 dir = normalize(v_far.xyz / v_far.w - v_near.xyz / v_near.w);
#if SKY_CONSTANT
    vec3 L = u_sky_color; // uniform radiance from every direction, below the horizon too (matches other renderers)
    if (dot(dir, u_sun_dir) > 0.99998917)
        L += u_sun_irr / 6.8e-5;
#elif SKY_PART == 1
    vec3 L = sky_above(dir);
#elif SKY_PART == 2
    vec3 L = ground(dir);
#else
    vec3 L = dir.y < 0.0 ? ground(dir) : sky_above(dir);
#endif
    o_color = vec4(exposed(L), 1.0);
#endif
#if SKY_COMPOSITE && SKY_VERTEX != 2
    vec4 c = clouds_at(gl_FragCoord.xy); // at a factor of 1 the weights are exactly 1 and 0: the pixel's texel
    o_color.rgb = c.rgb + (1.0 - c.a) * o_color.rgb;
#endif
#if SKY_TONEMAP && SKY_VERTEX != 2 && !(SKY_VERTEX == 1 && SKY_CORNER_TONE)
    o_color = vec4(tone_curve(o_color.rgb), 1.0);
#endif
}
