#version 300 es
// shaders_gles/temporal.frag: quality.temporal_grid's resolve (pass_temporal.c). This frame marched one cloud pixel
// of every G x G block (u_fresh: the block's pixel u_offset; u_fresh_depth: alpha x (distance, motion x, motion z),
// alpha); every other pixel of the cloud image takes last frame's image (u_hist) where its cloud was then: the
// pixel's ray, at the distance of the block's fresh sample, moved back by the camera's and the cloud's motion and
// projected with last frame's camera. Where that falls outside last frame's view, the fresh samples around stand in
// (bilinear); when the view moved, history is clamped to the fresh samples' range about the pixel (Karis 2014), so a
// cloud uncovering the sky leaves no trail. A still view takes every pixel's own ray back unchanged: after G^2
// frames the image is the full one.
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
uniform bool u_hw_filter;                 // the targets are RGBA16F, set to LINEAR
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_depth;

// Bilinear at texel position q (texel centres at integers): the hardware's where the targets are RGBA16F (GLES 3.0
// filters them), else from texels fetched one by one (RGBA32F is not filterable without an extension).
void bilinear(sampler2D c, sampler2D d, vec2 q, out vec4 col, out vec4 dep)
{
    if (u_hw_filter) {
        vec2 uv = (q + 0.5) / vec2(textureSize(c, 0));
        col = texture(c, uv);
        dep = texture(d, uv);
        return;
    }
    ivec2 size = textureSize(c, 0);
    ivec2 t0 = ivec2(floor(q));
    vec2 f = q - floor(q);
    col = vec4(0.0);
    dep = vec4(0.0);
    for (int k = 0; k < 4; k++) {
        ivec2 o = ivec2(k & 1, k >> 1);
        ivec2 t = clamp(t0 + o, ivec2(0), size - 1);
        float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        col += w * texelFetch(c, t, 0);
        dep += w * texelFetch(d, t, 0);
    }
}

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    ivec2 cell = px / u_grid;
    vec4 fc = texelFetch(u_fresh, cell, 0), fd = texelFetch(u_fresh_depth, cell, 0);
    if (px - cell * u_grid == u_offset) {
        o_color = fc;
        o_depth = fd;
        return;
    }
    // the fresh samples about this pixel: sample (i, j) sits at pixel G (i, j) + u_offset
    vec2 q = (gl_FragCoord.xy - 0.5 - vec2(u_offset)) / float(u_grid);
    // the range of the fresh samples about the pixel, which history is held to when the view moved: where none of
    // them sees a cloud, that is nothing, whatever the history (the sky: most of a frame, and cheap this way)
    vec4 lo = vec4(3.0e38), hi = vec4(-3.0e38);
    if (u_moved) {
        ivec2 size = textureSize(u_fresh, 0), t0 = ivec2(floor(q));
        for (int k = 0; k < 4; k++) {
            vec4 c = texelFetch(u_fresh, clamp(t0 + ivec2(k & 1, k >> 1), ivec2(0), size - 1), 0);
            lo = min(lo, c);
            hi = max(hi, c);
        }
        if (hi == vec4(0.0)) {
            o_color = vec4(0.0);
            o_depth = vec4(0.0);
            return;
        }
    }
    vec3 dir = normalize(v_far.xyz / v_far.w - v_near.xyz / v_near.w);
    // where this pixel's cloud was last frame: at the fresh sample's distance and motion (alpha-weighted over the
    // clouds along the ray); no cloud there: a direction, which the camera's translation does not move
    vec4 clip;
    if (fd.a > 1.0e-3)
        clip = u_prev_rot * vec4(dir * (fd.x / fd.a) + u_eye_delta - vec3(fd.y, 0.0, fd.z) / fd.a, 1.0);
    else
        clip = u_prev_rot * vec4(dir, 0.0);
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    if (clip.w <= 0.0 || any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) {
        bilinear(u_fresh, u_fresh_depth, q, o_color, o_depth); // not in last frame's view
        return;
    }
    vec4 hc, hd;
    vec2 h = uv * u_size - 0.5;
    if (all(lessThan(abs(h - floor(h + 0.5)), vec2(1.0e-3)))) { // on a texel (a still view): that texel
        hc = texelFetch(u_hist, ivec2(floor(h + 0.5)), 0);
        hd = texelFetch(u_hist_depth, ivec2(floor(h + 0.5)), 0);
    } else {
        bilinear(u_hist, u_hist_depth, h, hc, hd);
    }
    if (u_moved) {
        vec4 clamped = clamp(hc, lo, hi);
        // what the clamp takes away from the history's coverage, its depth loses in proportion
        hd *= hc.a > 1.0e-6 ? clamped.a / hc.a : 0.0;
        hc = clamped;
    }
    o_color = hc;
    o_depth = hd;
}
