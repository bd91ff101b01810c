#version 460
// For tests/sun_glitter.rs only: the glitter's slope density on a grid of world slopes s =
// (∂h/∂x, ∂h/∂z), a facet normal h = normalize(−s_x, 1, −s_z) around n = up:
// `beckmann_lobe` · cos⁴θ_h, with the covariance `slope_covariance` gives the slopes of mean
// square `total` and anisotropy `a` in the frame of `along` (common/glitter.glsl). Its moments
// over the grid must be the slopes' world covariance whatever `along` is.
layout(local_size_x = 8, local_size_y = 8) in;

layout(push_constant) uniform Lobe {
    vec2 a;      // (Σ(k_x² − k_z²)E, Σk_x k_z E)
    vec2 along;  // unit vector over the water (x, z)
    float total; // mean square over both directions
    float reach; // the grid spans slopes −reach … reach on each axis
    uint side;   // grid points per axis
} pc;
layout(std430, set = 0, binding = 0) writeonly buffer Density { float p[]; } density;

#include "common/glitter.glsl"

void main() {
    uvec2 i = gl_GlobalInvocationID.xy;
    if (i.x < pc.side && i.y < pc.side) {
        vec2 s = (vec2(i) + 0.5) / float(pc.side) * 2.0 * pc.reach - pc.reach;
        vec3 h = normalize(vec3(-s.x, 1.0, -s.y));
        vec3 m = slope_covariance(pc.total, pc.a, pc.along);
        float c2 = h.y * h.y;
        density.p[i.y * pc.side + i.x] = beckmann_lobe(vec3(0.0, 1.0, 0.0), h, pc.along, m) * c2 * c2;
    }
}
