#version 460
// For tests/shared.rs only: `tone_map` of shaders/common/display.glsl at `count` exposed
// radiances, to check its inverse in the tests (`untone` in tests/common/mod.rs). Radiance i
// is `top` times three fractions of i's golden-ratio sequences, the first of them pushed up
// toward 1: dark, bright, grey and saturated colours, peaks from 0 to `top`.
layout(local_size_x = 64) in;

// Named as display.glsl's `target_colour` expects (frame.sky_light.w: the exposure).
layout(push_constant) uniform Push {
    vec4 sky_light;
    float top;
    uint count;
} frame;
// Per radiance: (the radiance, -), (its display colour, -).
layout(std430, set = 0, binding = 0) writeonly buffer Colours { vec4 c[]; } colours;

#include "common/display.glsl"

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i < frame.count) {
        float f = float(i);
        vec3 x = frame.top * vec3(sqrt(fract(f * 0.618034)), fract(f * 0.7548777 + 0.1),
                                  fract(f * 0.5698403 + 0.3));
        colours.c[2u * i] = vec4(x, 0.0);
        colours.c[2u * i + 1u] = vec4(tone_map(x), 0.0);
    }
}
