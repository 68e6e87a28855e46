#version 300 es
// shaders_gles/refine_mark.frag: which pixels quality.edge_refine marches again at full resolution (pass_refine.c).
// A pixel is kept (written transparent black, its stencil set to 0 by the pass) where the four low-resolution cloud
// texels its bilinear upsampling reads differ by more than u_threshold in coverage, or in luminance contrast
// (max - min) / (max + min): there the upsampled picture is a blend of unlike neighbours (a rim, a thin bright edge,
// a cloud's outline). Elsewhere it is discarded and keeps the clear value, whose alpha of 2 tells the composite
// (sky.frag, upsample.frag) to use the upsampled image.
precision highp float;
uniform highp sampler2D u_low;  // premultiplied radiance, alpha = 1 - transmittance, at 1/u_factor resolution
uniform float u_factor;         // output pixels per low-resolution texel
uniform float u_threshold;      // quality.edge_refine
out vec4 o_color;

void main()
{
    // the four texels of the composite's bilinear read (sky.frag clouds_at, upsample.frag), clamped the same way
    vec2 q = gl_FragCoord.xy / u_factor - 0.5;
    ivec2 t0 = ivec2(floor(q)), size = textureSize(u_low, 0);
    float amin = 2.0, amax = -1.0, lmin = 3.0e38, lmax = 0.0;
    for (int k = 0; k < 4; k++) {
        vec4 c = texelFetch(u_low, clamp(t0 + ivec2(k & 1, k >> 1), ivec2(0), size - 1), 0);
        float l = max(dot(c.rgb, vec3(0.2126, 0.7152, 0.0722)), 0.0);
        amin = min(amin, c.a);
        amax = max(amax, c.a);
        lmin = min(lmin, l);
        lmax = max(lmax, l);
    }
    // a pixel no cloud reaches (all four transparent and black) is never marked: 0 > threshold is false
    bool edge = amax - amin > u_threshold || lmax - lmin > u_threshold * (lmax + lmin);
    if (!edge)
        discard;
    o_color = vec4(0.0);
}
