#version 460
// For tests/reflection.rs only: `mean_visible_slope` (common/glitter.glsl) at eight view
// slopes μ (cot of the angle of incidence) for each of four slope deviations σ: out[4i + j]
// for μ_i and σ_j.
layout(local_size_x = 32) in;

layout(push_constant) uniform Inputs {
    vec4 mu[2];
    vec4 sigma;
} pc;
layout(std430, set = 0, binding = 0) writeonly buffer Out { float slope[]; } result;

#include "common/glitter.glsl"

void main() {
    uint k = gl_GlobalInvocationID.x;
    if (k < 32u) {
        uint i = k / 4u;
        result.slope[k] = mean_visible_slope(pc.mu[i / 4u][i % 4u], pc.sigma[k % 4u]);
    }
}
