#version 300 es
// shaders_gles/tonemap.frag: final pass from the linear HDR target: exposure, white balance, ACES filmic curve (Narkowicz fit) and
// the sRGB transfer function; or a plain copy of linear radiance when LINEAR_OUTPUT is set (PFM, tests).
precision highp float;
uniform highp sampler2D u_hdr;
uniform float u_exposure;
uniform vec3 u_white;        // white balance: divides by the colour of typical daylight
uniform bool u_composite;    // clouds only (cu_frame.clouds_only): blended premultiplied over the host's colour
out vec4 o_color;
#include "tonecurve.glsl"
void main()
{
    vec4 c = texelFetch(u_hdr, ivec2(gl_FragCoord.xy), 0);
    // Where no cloud is, the host's pixel stays exactly as it was.
    if (u_composite && c.a <= 0.0)
        discard;
#if LINEAR_OUTPUT
    o_color = c;
#else
    // Composited, the clouds' own radiance (premultiplied / coverage) is tone-mapped like the sky would be, then
    // weighted by its coverage: the host's picture shows through where the cloud is thin.
    float a = c.a;
    if (u_composite)
        c.rgb /= a;
    o_color = vec4(tone_curve(c.rgb * u_exposure / u_white), 1.0);
    if (u_composite)
        o_color *= a;
#endif
}
