#version 300 es
// shaders_gles/impostor.vert: a cloud's impostor (pass_impostor.c): a square through the cloud's centre, facing the
// eye the image was made from, whose corners are that image's frustum there; seen from that eye it covers exactly
// the pixels the cloud did. Points are given about this frame's eye, so fp32 keeps them at any distance.
precision highp float;
uniform mat4 u_rot_vp;   // points about the eye -> clip (the cloud camera's rot_vp)
uniform vec3 u_corner0;  // the square's corner at image (0, 0), about the eye (m)
uniform vec3 u_du, u_dv; // its edges toward image (1, 0) and (0, 1) (m)
out vec2 v_uv;
out float v_dist;        // m from the eye
void main()
{
    vec2 c = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
    vec3 p = u_corner0 + c.x * u_du + c.y * u_dv;
    v_uv = c;
    v_dist = length(p);
    vec4 clip = u_rot_vp * vec4(p, 1.0);
    gl_Position = vec4(clip.xy, 0.0, clip.w); // no depth test here; depth 0 keeps any distance inside the clip volume
}
