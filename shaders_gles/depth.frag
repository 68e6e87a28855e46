#version 300 es
// shaders_gles/depth.frag: depth pre-pass; writes nothing but depth so the cloud pass shades each pixel once.
precision mediump float;
out vec4 o_color;
void main()
{
    o_color = vec4(0.0);
}
