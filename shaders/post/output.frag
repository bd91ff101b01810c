#version 460
// Output pass, drawn (src/render/passes/output.rs): where the output image takes no copies
// (a swapchain without TRANSFER_DST usage), the picture is drawn into it as a colour
// attachment instead of copied or blitted. Input: the main or anti-aliased colour (binding 0),
// sampled nearest at the same size, bilinearly when scaling, like the blit it replaces.
// Output: the output image; an sRGB pair decodes on sampling and encodes on writing, a UNORM
// pair passes the bytes through. Vertex shader: common/fullscreen.vert.

layout(set = 0, binding = 0) uniform sampler2D picture;

layout(location = 0) in vec2 in_uv;
layout(location = 0) out vec4 out_colour;

void main() {
    out_colour = textureLod(picture, in_uv, 0.0);
}
