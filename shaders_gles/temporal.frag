#version 300 es
// shaders_gles/temporal.frag: quality.temporal_grid's resolve (pass_temporal.c). This frame marched one cloud pixel
// of every G x G block (u_fresh: the block's pixel u_offset; u_fresh_depth: alpha x (distance, motion x, motion z),
// alpha); every other pixel of the cloud image takes last frame's image (u_hist) where its cloud was then: the
// pixel's ray, at the distance of the block's fresh sample, moved back by the camera's and the cloud's motion and
// projected with last frame's camera. Where that falls outside last frame's view, the fresh samples around stand in
// (bilinear); when the view moved, history is clamped to the fresh samples' range about the pixel (Karis 2014), so a
// cloud uncovering the sky leaves no trail. A still view takes every pixel's own ray back unchanged: after G^2
// frames the image is the full one.
// Written without branches around texture reads: a software rasteriser (llvmpipe, Mesa 22) runs both sides of every
// `if`, whatever the condition, so each read here is made once and the cases are selected after. HW_FILTER (the
// targets are RGBA16F, set LINEAR: GLES 3.0 filters them) reads the history through the texture unit; without it
// (RGBA32F, for linear output, is not filterable without an extension) from its four texels.
precision highp float;
precision highp sampler2D;
uniform sampler2D u_fresh, u_fresh_depth; // this frame's marched pixels, one per block (premultiplied)
uniform sampler2D u_hist, u_hist_depth;   // last frame's cloud image, the same layout at full size
uniform int u_grid;                       // G
uniform ivec2 u_offset;                   // the block's pixel marched this frame
uniform vec2 u_size;                      // the cloud image's size in pixels
in vec4 v_near, v_far;                    // the pixel's points on the near and far planes (sky.vert)
uniform mat4 u_prev_rot;                  // last frame's direction -> clip (camera at the origin)
uniform vec3 u_eye_delta;                 // this frame's eye - last frame's (m)
uniform bool u_moved;                     // the view changed since the last frame
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_depth;

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    ivec2 cell = px / u_grid;
    // the fresh samples about this pixel: sample (i, j) sits at pixel G (i, j) + u_offset; the four about q hold
    // this pixel's own block's sample too (floor(q) is its cell or the one before)
    vec2 q = (gl_FragCoord.xy - 0.5 - vec2(u_offset)) / float(u_grid);
    ivec2 size = textureSize(u_fresh, 0), t0 = ivec2(floor(q));
    vec2 f = q - floor(q);
    vec4 fc = vec4(0.0), fd = vec4(0.0);        // the block's own sample
    vec4 bc = vec4(0.0), bd = vec4(0.0);        // bilinear between the four
    vec4 lo = vec4(3.0e38), hi = vec4(-3.0e38); // their range
    for (int k = 0; k < 4; k++) {
        ivec2 o = ivec2(k & 1, k >> 1), t = t0 + o;
        vec4 c = texelFetch(u_fresh, clamp(t, ivec2(0), size - 1), 0);
        vec4 d = texelFetch(u_fresh_depth, clamp(t, ivec2(0), size - 1), 0);
        float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        bc += w * c;
        bd += w * d;
        lo = min(lo, c);
        hi = max(hi, c);
        bool own = t == cell;
        fc = own ? c : fc;
        fd = own ? d : fd;
    }
    vec3 dir = normalize(v_far.xyz / v_far.w - v_near.xyz / v_near.w);
    // where this pixel's cloud was last frame: at the fresh sample's distance and motion (alpha-weighted over the
    // clouds along the ray); no cloud there: a direction, which the camera's translation does not move
    vec4 clip = fd.a > 1.0e-3 ? u_prev_rot * vec4(dir * (fd.x / fd.a) + u_eye_delta - vec3(fd.y, 0.0, fd.z) / fd.a, 1.0)
                              : u_prev_rot * vec4(dir, 0.0);
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    bool outside = clip.w <= 0.0 || any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)));
    // last frame's image there; on a texel (a still view), that texel exactly
    vec2 h = clamp(uv, 0.0, 1.0) * u_size - 0.5;
    bool on_texel = all(lessThan(abs(h - floor(h + 0.5)), vec2(1.0e-3)));
    vec4 hc, hd;
#if HW_FILTER
    ivec2 ht = clamp(ivec2(floor(h + 0.5)), ivec2(0), ivec2(u_size) - 1);
    vec4 tc = texelFetch(u_hist, ht, 0), td = texelFetch(u_hist_depth, ht, 0);
    vec2 huv = (h + 0.5) / u_size;
    vec4 lc = texture(u_hist, huv), ld = texture(u_hist_depth, huv);
    hc = on_texel ? tc : lc;
    hd = on_texel ? td : ld;
#else
    vec2 hs = on_texel ? floor(h + 0.5) : h; // at a texel the weights are exactly 1 and 0: that texel
    ivec2 hsize = ivec2(u_size), h0 = ivec2(floor(hs));
    vec2 hf = hs - floor(hs);
    hc = vec4(0.0);
    hd = vec4(0.0);
    for (int k = 0; k < 4; k++) {
        ivec2 o = ivec2(k & 1, k >> 1), t = clamp(h0 + o, ivec2(0), hsize - 1);
        float w = (o.x == 1 ? hf.x : 1.0 - hf.x) * (o.y == 1 ? hf.y : 1.0 - hf.y);
        hc += w * texelFetch(u_hist, t, 0);
        hd += w * texelFetch(u_hist_depth, t, 0);
    }
#endif
    if (u_moved) {
        vec4 clamped = clamp(hc, lo, hi);
        // what the clamp takes away from the history's coverage, its depth loses in proportion
        hd *= hc.a > 1.0e-6 ? clamped.a / hc.a : 0.0;
        hc = clamped;
    }
    // this block's own sample; where the view moved and none of the fresh samples about the pixel sees a cloud,
    // nothing, whatever the history (the sky: most of a frame); outside last frame's view, the fresh samples
    bool own = px - cell * u_grid == u_offset, none = u_moved && hi == vec4(0.0);
    o_color = own ? fc : none ? vec4(0.0) : outside ? bc : hc;
    o_depth = own ? fd : none ? vec4(0.0) : outside ? bd : hd;
}
