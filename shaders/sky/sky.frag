#version 460
// Sky pass: every pixel gets the sky cubemap's radiance along its view ray (in the reflection
// view the ray is mirrored, so the reflection shows the sky the water reflects). With the test
// background on (modes.w), the main view paints a solid colour found nowhere else instead.
#include "common/frame.glsl"
#include "common/display.glsl"

layout(location = 0) in vec2 in_uv;
layout(location = 1) in vec2 in_ndc;
layout(location = 0) out vec4 out_colour;

void main() {
    if (frame.modes.w == 1u && pass.view == 0u) {
        out_colour = target_colour(frame.background.rgb);
        return;
    }
    out_colour = target_colour(sky_lookup(view_ray(in_ndc)));
}
