#version 300 es
// shaders_gles/hull.vert: instanced ellipsoid hulls (unit mesh scaled per instance) for the sun, depth and cloud passes.
// The same source is used by every pass and gl_Position is invariant, so GL_EQUAL in the cloud pass matches the
// depth pre-pass bit for bit (Kol 3.4.2).
precision highp float;
layout(location = 0) in vec3 a_pos;      // unit hull vertex (already scaled to circumscribe the sphere)
layout(location = 1) in vec4 a_center;   // per instance: centre, cloud-local metres
layout(location = 2) in vec4 a_radii;    // per instance: radii, metres
uniform mat4 u_viewproj; // cloud-local -> clip
out vec3 v_pos;
flat out int v_inst;
invariant gl_Position;
void main()
{
    v_pos = a_center.xyz + a_pos * a_radii.xyz;
    v_inst = gl_InstanceID;
    gl_Position = u_viewproj * vec4(v_pos, 1.0);
}
