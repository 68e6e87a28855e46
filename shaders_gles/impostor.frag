#version 300 es
// shaders_gles/impostor.frag: a cloud drawn from its impostor: the premultiplied image the cloud pass made of it,
// filtered; with the temporal grid, the distance and motion its reprojection needs (as cloud.frag writes them).
precision highp float;
precision highp sampler2D;
uniform sampler2D u_image;
in vec2 v_uv;
in float v_dist;
layout(location = 0) out vec4 o_color;
#if TEMPORAL
layout(location = 1) out vec4 o_depth;
uniform vec2 u_motion;
#endif
void main()
{
    o_color = texture(u_image, v_uv);
#if TEMPORAL
    o_depth = o_color.a * vec4(v_dist, u_motion, 1.0);
#endif
}
