#version 300 es
// shaders_gles/fullscreen.vert: one triangle covering the viewport (sky, tone map, camera-inside cloud pass).
precision highp float;
out vec2 v_ndc;
void main()
{
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)) * 2.0 - 1.0;
    v_ndc = p;
    gl_Position = vec4(p, 0.0, 1.0);
}
