// shaders_gles/tonecurve.glsl: the display curve shared by the tone map (tonemap.frag) and the sky drawn straight to
// the output (sky.frag with SKY_TONEMAP): ACES filmic (Narkowicz's fit) of exposed, white-balanced radiance, then the
// sRGB transfer function. No #version: the loader inserts it.
vec3 srgb(vec3 c)
{
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

vec3 tone_curve(vec3 x)
{
    x = max(x, vec3(0.0));
    return srgb(clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0));
}
