#version 460
// For tests/shared.rs only: `terrain_height` of shaders/common/terrain.glsl at each point of
// `points`, to compare with its Rust twin (`terrain_height` in src/render/scene.rs).
layout(local_size_x = 64) in;

// The one field of the frame uniforms terrain.glsl reads: (island x, z, sea floor depth,
// island radius), as in shaders/common/frame.glsl.
layout(push_constant) uniform Frame {
    vec4 terrain;
    uint count;
} frame;
layout(std430, set = 0, binding = 0) readonly buffer Points { vec2 xz[]; } points;
layout(std430, set = 0, binding = 1) writeonly buffer Heights { float h[]; } heights;

#include "common/terrain.glsl"

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i < frame.count) {
        heights.h[i] = terrain_height(points.xz[i]);
    }
}
