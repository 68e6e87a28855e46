#version 300 es
// shaders_gles/sky.vert: one triangle covering the viewport, carrying each corner's points on the near and far planes
// (homogeneous, through u_inv_viewproj): they are linear in the screen, so the sky's fragments get them interpolated
// exactly and divide, instead of two matrix products a pixel. With SKY_VERTEX (quality.sky_grid): a grid of cells
// over rows of the Perez sky instead (1, 2 or 4 times that size a band of rows, where the sky bends little:
// sky_grid.c), the sky worked out at their corners and interpolated between them: it varies slowly across the
// screen, and the fragments only tone-map it (pass_sky.c draws the sun's disk and the aureole about it, the horizon
// and the ground a pixel at a time). With SKY_VERTEX 2: a colour the same at every pixel (the
// ground where no shadow map can reach, a constant sky) worked out once a corner and passed on flat, the display's
// curve included: the curve alone is most of what a pixel of it cost on llvmpipe (pass_sky.c draws the sun's disk
// over a constant sky a pixel at a time).
#ifndef SKY_VERTEX
#define SKY_VERTEX 0
#endif
#if SKY_VERTEX == 1
#include "sky.glsl"
#if SKY_CORNER_TONE
#include "tonecurve.glsl"
#endif
uniform mat4 u_inv_viewproj;   // clip -> direction (camera at the origin)
uniform vec4 u_grid_box;       // the grid's first corner and its last (pixels)
uniform vec2 u_grid_cell;      // a cell's width and height in pixels
uniform vec2 u_grid_size;      // the viewport's
uniform int u_grid_cols;       // cells across the box
out vec3 v_sky;
void main()
{
    // a strip a row of cells, corners alternately on its lower and upper edge, the rows joined by two repeated
    // corners (the degenerate triangles between them cover nothing); the last row and column clamped to the box
    int per = 2 * u_grid_cols + 4, row = gl_VertexID / per, j = gl_VertexID - row * per;
    ivec2 at = j < per - 2 ? ivec2(j >> 1, row + (j & 1)) : ivec2(j == per - 2 ? u_grid_cols : 0, row + 1);
    vec2 px = min(u_grid_box.xy + vec2(at) * u_grid_cell, u_grid_box.zw);
    vec2 p = px / u_grid_size * 2.0 - 1.0;
    vec4 n = u_inv_viewproj * vec4(p, -1.0, 1.0), f = u_inv_viewproj * vec4(p, 1.0, 1.0);
    // rows of the Perez sky alone (pass_sky.c): linear, the display's curve at every pixel, as the sky drawn under
    // the clouds gets it later
    v_sky = exposed(perez_sky(normalize(f.xyz / f.w - n.xyz / n.w)));
#if SKY_CORNER_TONE
    v_sky = tone_curve(v_sky); // the display's values interpolated: within sky_grid.c's bound where the plan allows
#endif
    gl_Position = vec4(p, 0.0, 1.0);
}
#elif SKY_VERTEX == 2
#include "sky.glsl"
#if SKY_TONEMAP
#include "tonecurve.glsl"
#endif
flat out vec3 v_flat;
void main()
{
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)) * 2.0 - 1.0;
#if SKY_CONSTANT
    v_flat = exposed(u_sky_color);
#else
    v_flat = exposed(u_ground); // sky.frag's ground() where no map is read
#endif
#if SKY_TONEMAP
    v_flat = tone_curve(v_flat);
#endif
    gl_Position = vec4(p, 0.0, 1.0);
}
#else
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
#endif
