// shaders_gles/tonecurve.glsl: the display curve shared by the tone map (tonemap.frag) and the sky drawn straight to
// the output (sky.frag with SKY_TONEMAP): ACES filmic (Narkowicz's fit) of exposed, white-balanced radiance, then the
// sRGB transfer function. No #version: the loader inserts it.
// sRGB's 1.055 c^(1/2.4) - 0.055 from c^(1/2), c^(1/4) and c^(1/8) (Taylor 2012, chilliant.blogspot.com): within
// 0.25/255 of the power, at the cost of three square roots where llvmpipe's pow is a log2 and an exp2 a channel.
vec3 srgb(vec3 c)
{
    vec3 s1 = sqrt(c), s2 = sqrt(s1), s3 = sqrt(s2);
    return mix(12.92 * c, 0.662002687 * s1 + 0.68412206 * s2 - 0.323583601 * s3 - 0.022541147 * c,
               step(vec3(0.0031308), c));
}

vec3 tone_curve(vec3 x)
{
    x = max(x, vec3(0.0));
    return srgb(clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0));
}
