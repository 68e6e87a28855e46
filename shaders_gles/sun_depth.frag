#version 300 es
// shaders_gles/sun_depth.frag: front depth of the ellipsoid union seen from the sun (Kol 3.1.2). Depth is the exact
// analytic entry of this fragment's sun ray into its ellipsoid (not the polygonal hull), as a fraction of 4R.
precision highp float;
in vec3 v_pos;
flat in int v_inst;
uniform vec4 u_ell_c[NUM_ELL];
uniform vec4 u_ell_ir[NUM_ELL];
uniform vec3 u_sun_dir;  // toward the sun
uniform float u_sun_R;   // bounding radius: the sun plane is at 2R along u_sun_dir, depth range 4R
out vec4 o_color;
void main()
{
    vec3 o = v_pos + u_sun_dir * (2.0 * u_sun_R - dot(v_pos, u_sun_dir));
    vec3 d = -u_sun_dir;
    vec3 ir = u_ell_ir[v_inst].xyz;
    vec3 q = (o - u_ell_c[v_inst].xyz) * ir, ds = d * ir;
    // closest-approach form, as cast_ray in density.glsl (no cancellation for thin ellipsoids far from the plane)
    float A = dot(ds, ds);
    float tc = -dot(q, ds) / A;
    vec3 qc = q + tc * ds;
    float h2 = 1.0 - dot(qc, qc);
    if (h2 < 0.0)
        discard; // the hull is larger than the ellipsoid: its rim misses
    float t0 = tc - sqrt(h2 / A);
    gl_FragDepth = clamp(t0 / (4.0 * u_sun_R), 0.0, 1.0);
    o_color = vec4(0.0);
}
