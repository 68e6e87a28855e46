#version 300 es
// shaders_gles/sky.vert: one triangle covering the viewport, carrying each corner's points on the near and far planes
// (homogeneous, through u_inv_viewproj): they are linear in the screen, so the sky's fragments get them interpolated
// exactly and divide, instead of two matrix products a pixel.
precision highp float;
uniform mat4 u_inv_viewproj;   // clip -> direction (camera at the origin)
out vec4 v_near, v_far;
void main()
{
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)) * 2.0 - 1.0;
    v_near = u_inv_viewproj * vec4(p, -1.0, 1.0);
    v_far = u_inv_viewproj * vec4(p, 1.0, 1.0);
    gl_Position = vec4(p, 0.0, 1.0);
}
