#version 460
// A spray puff (shaders/spray/spray.vert): a soft disc, Gaussian across its radius, blended over
// the scene with premultiplied alpha (the pass tests depth, writes none).
#include "common/frame.glsl"
#include "common/display.glsl"

layout(location = 0) in vec2 in_corner;
layout(location = 1) in vec4 in_colour;
layout(location = 0) out vec4 out_colour;

void main() {
    float alpha = in_colour.a * exp(-3.0 * dot(in_corner, in_corner));
    if (alpha < 1.0 / 255.0) {
        discard;
    }
    out_colour = vec4(target_colour(in_colour.rgb).rgb * alpha, alpha);
}
