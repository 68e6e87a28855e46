#version 300 es
// shaders_gles/sky.frag: background radiance: Preetham et al. 1999 analytic sky (Perez distribution of Y, x, y, read
// as the product of its zenith and sun factors from the tables of sky.c: cu_sky_tables) or a constant sky, the sun disk, and a Lambertian ground below the horizon. Output: linear RGB radiance (kcd/m^2 units);
// with SKY_TONEMAP (a frame with no cloud in view) the display's colour straight away, as the tone map would make it.
precision highp float;
precision highp sampler2D; // lowp by default in GLES fragment shaders: the tables need their full precision
in vec4 v_near, v_far;         // the pixel's points on the near and far planes, homogeneous (sky.vert)
uniform vec3 u_sun_dir;
uniform vec3 u_sun_irr;        // irradiance perpendicular to the rays
uniform float u_out_max;       // what the target may hold (fp16 overflows at 65504; gpu_scene.c: cu_out_max)
uniform vec3 u_ground;         // ground radiance
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
uniform vec3 u_out_scale;      // exposure / white, or 1 for linear output (gpu_scene.c: cu_out_scale)
#if SKY_CONSTANT
uniform vec3 u_sky_color;
#else
uniform sampler2D u_sky_tables;// row 0: (Y, x, y)'s zenith factor at sqrt(cos theta); row 1: the sun's at sin(gamma/2)
#endif
out vec4 o_color;
#ifndef SKY_TONEMAP
#define SKY_TONEMAP 0
#endif
// SKY_PART (pass_sky.c): 0 draws rows that hold the horizon, 1 rows of sky alone, 2 rows of ground alone. A software
// rasteriser (llvmpipe, Mesa 22) runs both sides of a branch on every pixel, so rows without the horizon take a
// program without it.
#ifndef SKY_PART
#define SKY_PART 0
#endif
#ifndef SKY_COMPOSITE
#define SKY_COMPOSITE 0
#endif
#if SKY_TONEMAP
#include "tonecurve.glsl"
#endif
#if SKY_COMPOSITE
// The cloud image (quality.cloud_downsample, temporal_grid) composited over the sky here, on its way to the output:
// one pass instead of the sky's, the upsampling's and the tone map's. Premultiplied, in the sky's exposed units;
// bilinear from the four nearest of its texels, as upsample.frag does without a host depth.
uniform highp sampler2D u_clouds;
uniform float u_cloud_factor;  // output pixels per texel of the cloud image
vec4 clouds_at(vec2 frag)
{
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
// Table row `row` at t in 0..1, interpolated here: RGBA32F, exact (fp16's rounding, amplified by the conversion from
// xyY, would move the sky's colour by 0.3 %), and GLES 3.0 filters 32-bit float textures only with an extension.
vec3 table(float t, int row)
{
    float f = t * float(SKY_TABLE - 1);
    int i = min(int(f), SKY_TABLE - 2);
    return mix(texelFetch(u_sky_tables, ivec2(i, row), 0).rgb, texelFetch(u_sky_tables, ivec2(i + 1, row), 0).rgb,
               f - float(i));
}
vec3 xyY_to_rgb(float x, float y, float Y)
{
    float X = Y * x / max(y, 1e-4), Z = Y * (1.0 - x - y) / max(y, 1e-4);
    return vec3(3.2406 * X - 1.5372 * Y - 0.4986 * Z, -0.9689 * X + 1.8758 * Y + 0.0415 * Z,
                0.0557 * X - 0.2040 * Y + 1.0570 * Z);
}
#endif

#if !SKY_CONSTANT
// Above the horizon: the Perez sky and the sun's disk.
vec3 sky_above(vec3 dir)
{
    float t_zenith = sqrt(dir.y), t_sun = sqrt(clamp(0.5 - 0.5 * dot(dir, u_sun_dir), 0.0, 1.0));
    vec3 Yxy = table(t_zenith, 0) * table(t_sun, 1);
    vec3 L = max(xyY_to_rgb(Yxy.y, Yxy.z, Yxy.x), vec3(0.0));
    // Sun disk: angular radius 0.2666 deg, solid angle 6.8e-5 sr; radiance = irradiance / solid angle.
    if (dot(dir, u_sun_dir) > 0.99998917)
        L += u_sun_irr / 6.8e-5;
    return L;
}
#endif

void main()
{
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
    o_color = vec4(min(L * u_out_scale, vec3(u_out_max)), 1.0);
#if SKY_COMPOSITE
    vec4 c = clouds_at(gl_FragCoord.xy); // at a factor of 1 the weights are exactly 1 and 0: the pixel's texel
    o_color.rgb = c.rgb + (1.0 - c.a) * o_color.rgb;
#endif
#if SKY_TONEMAP
    o_color = vec4(tone_curve(o_color.rgb), 1.0);
#endif
}
