#version 460
// Sky pass: every pixel gets the radiance of its view ray (common/sky.glsl).
// Inputs: frame uniforms (inverse view-projection, sun). Output: HDR colour.
#include "common/frame.glsl"
#include "common/sky.glsl"

layout(location = 0) in vec2 in_uv;
layout(location = 1) in vec2 in_ndc;
layout(location = 0) out vec4 out_colour;

void main() {
    vec3 dir = view_ray(in_ndc);
    out_colour = vec4(sky_radiance(dir, frame.sun_dir.xyz, frame.sun_dir.w), 1.0);
}
