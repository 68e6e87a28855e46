// shaders_gles/sky.glsl: the analytic sky above the horizon, shared by sky.frag (a pixel at a time) and sky.vert with
// SKY_VERTEX (at the corners of a grid of cells, interpolated between: quality.sky_grid). Preetham et al. 1999: the
// Perez distribution of Y, x, y as the product of its zenith and sun factors, read from the tables of sky.c
// (cu_sky_tables). No #version: the loader inserts it. Declares the uniforms both stages share.
// The variants (pass_sky.c): SKY_TONEMAP, the display's colours; SKY_COMPOSITE, a cloud image over the sky on the way;
// SKY_PART 0 draws rows that hold the horizon, 1 rows of sky alone, 2 rows of ground alone (a software rasteriser,
// llvmpipe in Mesa 22, runs both sides of a branch on every pixel, so rows without the horizon take a program
// without it); SKY_VERTEX, the sky from the grid's corners; SKY_CORNER_TONE (with SKY_TONEMAP and SKY_VERTEX 1), the
// display's curve at the corners too (a frame of sky alone, where pass_sky.c's plan allows it: sky_grid.c).
#ifndef SKY_TONEMAP
#define SKY_TONEMAP 0
#endif
#ifndef SKY_COMPOSITE
#define SKY_COMPOSITE 0
#endif
#ifndef SKY_PART
#define SKY_PART 0
#endif
#ifndef SKY_VERTEX
#define SKY_VERTEX 0
#endif
#ifndef SKY_CORNER_TONE
#define SKY_CORNER_TONE 0
#endif
precision highp float;
precision highp sampler2D; // lowp by default: the tables need their full precision (and both stages must agree)
uniform vec3 u_sun_dir;
uniform vec3 u_sun_irr;        // irradiance perpendicular to the rays
uniform float u_out_max;       // what the target may hold (fp16 overflows at 65504; gpu_scene.c: cu_out_max)
uniform vec3 u_ground;         // ground radiance
uniform vec3 u_out_scale;      // exposure / white, or 1 for linear output (gpu_scene.c: cu_out_scale)
#if SKY_CONSTANT
uniform vec3 u_sky_color;
#else
uniform sampler2D u_sky_tables;// row 0: (Y, x, y)'s zenith factor at sqrt(cos theta); row 1: the sun's at sin(gamma/2)

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

// The Perez sky toward dir (unit, at or above the horizon), without the sun's disk.
vec3 perez_sky(vec3 dir)
{
    float t_zenith = sqrt(max(dir.y, 0.0)), t_sun = sqrt(clamp(0.5 - 0.5 * dot(dir, u_sun_dir), 0.0, 1.0));
    vec3 Yxy = table(t_zenith, 0) * table(t_sun, 1);
    return max(xyY_to_rgb(Yxy.y, Yxy.z, Yxy.x), vec3(0.0));
}
#endif

// The radiance toward dir, scaled for the target and capped below what it holds.
vec3 exposed(vec3 L)
{
    return min(L * u_out_scale, vec3(u_out_max));
}
