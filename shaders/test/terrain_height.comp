#version 460
// For tests/shared.rs only: at each point of `points`, `terrain_height` of
// shaders/common/terrain.glsl and `shore_waves`, `shore_travel_s` and `shore_runup_m` of
// common/shore.glsl over the depth there, to compare with their Rust twins (`terrain_height` in
// src/render/scene.rs, the others in src/ocean/shore.rs).
layout(local_size_x = 64) in;

// The fields of the frame uniforms terrain.glsl and shore.glsl read, as in
// shaders/common/frame.glsl: (island x, z, sea floor depth, island radius), (Hs, mean ω, c_g at
// the simulated depth, -) and (open sea's floor depth, K_s there, -, -).
layout(push_constant) uniform Frame {
    vec4 terrain;
    vec4 shore;
    vec4 open_sea;
    uint count;
} frame;
layout(std430, set = 0, binding = 0) readonly buffer Points { vec2 xz[]; } points;
// Per point: (terrain height, shore scale, breaking, local Hs), then the surf's (travel time to
// the waterline over a bed of slope m_i, run-up on a beach of slope m_i, -, -) with
// m_i = 0.005 + 0.3·fract(0.618·i).
layout(std430, set = 0, binding = 1) writeonly buffer Heights { vec4 h[]; } heights;

#include "common/terrain.glsl"
#include "common/shore.glsl"

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i < frame.count) {
        float h = terrain_height(points.xz[i]);
        heights.h[2u * i] = vec4(h, shore_waves(-h));
        float m = 0.005 + 0.3 * fract(0.618 * float(i));
        float omega = frame.shore.y;
        heights.h[2u * i + 1u] = vec4(shore_travel_s(omega, -h, m),
                                      shore_runup_m(frame.shore.x, omega, m), 0.0, 0.0);
    }
}
