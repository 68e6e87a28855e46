#version 300 es
// shaders_gles/upsample.frag: the clouds drawn at 1/N of the resolution (quality.cloud_downsample) brought up to the
// frame, premultiplied (the blend puts them over the sky, or over nothing for clouds_only). Bilinear from the four
// nearest low-resolution texels; with the host's depth, only those whose surface is the one this pixel sees
// (linear depth within 10 %; the sky counts as one surface) take part, so a cloud behind a building does not bleed
// over its edge and the building's veil does not bleed onto the sky (joint bilateral with a depth step: Kopf et al.
// 2007; nearest-depth when no neighbour matches, after Bavoil's "nearest-depth upsampling").
precision highp float;
uniform highp sampler2D u_low;     // premultiplied radiance, alpha = 1 - transmittance
uniform int u_factor;              // the downsample factor N
uniform bool u_depth_on;
uniform highp sampler2D u_depth;   // the host's window depth at full resolution
uniform float u_depth_clear;       // its clear value: no surface (the sky)
uniform vec3 u_lin;                // z_ndc -> eye distance: perspective -B / (z_ndc + A) (u_lin.z = 0) or ortho
uniform bool u_refined_on;          // quality.edge_refine: u_refined holds the marked pixels at full resolution
uniform highp sampler2D u_refined; // premultiplied; alpha 2 where not marked (pass_refine.h)
out vec4 o_color;

float dist_at(ivec2 p)
{
    float d = texelFetch(u_depth, p, 0).r;
    if (d == u_depth_clear)
        return 3.0e38;
    float z = 2.0 * d - 1.0;
    return u_lin.z == 0.0 ? abs(u_lin.y / (z + u_lin.x)) : abs((z - u_lin.y) / u_lin.x);
}

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    if (u_factor == 1) { // the temporal grid's image at the frame's size: a copy
        o_color = texelFetch(u_low, p, 0);
        if (o_color.a <= 0.0 && all(equal(o_color.rgb, vec3(0.0))))
            discard;
        return;
    }
    if (u_refined_on) {
        vec4 r = texelFetch(u_refined, p, 0);
        if (r.a <= 1.5) {
            o_color = r;
            if (o_color.a <= 0.0 && all(equal(o_color.rgb, vec3(0.0))))
                discard;
            return;
        }
    }
    ivec2 lsize = textureSize(u_low, 0);
    float n = float(u_factor);
    // this pixel's centre in low-resolution texel units, the four texels about it and the bilinear weights
    vec2 q = gl_FragCoord.xy / n - 0.5;
    ivec2 t0 = ivec2(floor(q));
    vec2 f = q - floor(q);
    vec4 sum = vec4(0.0);
    float wsum = 0.0, d0 = u_depth_on ? dist_at(p) : 0.0, best = 3.4e38;
    vec4 nearest = vec4(0.0);
    for (int k = 0; k < 4; k++) {
        ivec2 o = ivec2(k & 1, k >> 1);
        ivec2 t = clamp(t0 + o, ivec2(0), lsize - 1);
        vec4 c = texelFetch(u_low, t, 0);
        float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        if (u_depth_on) {
            // the host texel the cloud pass read for this low-resolution texel (cloud.frag, u_host_scale)
            ivec2 hp = clamp(ivec2((vec2(t) + 0.5) * n), ivec2(0), textureSize(u_depth, 0) - 1);
            float di = dist_at(hp), gap = abs(di - d0);
            bool same = (d0 > 1.0e38 && di > 1.0e38) || gap <= 0.1 * min(d0, di);
            if (gap < best) {
                best = gap;
                nearest = c;
            }
            if (!same)
                w = 0.0;
        }
        sum += w * c;
        wsum += w;
    }
    o_color = wsum > 1.0e-6 ? sum / wsum : nearest;
    if (o_color.a <= 0.0 && all(equal(o_color.rgb, vec3(0.0))))
        discard; // no cloud: the sky below stays exactly as it was
}
