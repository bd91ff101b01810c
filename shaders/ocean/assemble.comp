#version 460
// Assemble the inverse-FFT output into the images the renderer samples (one layer per cascade):
//   displacement = (λ Dx, h, λ Dz, 0),  normals = (-n.x / n.y, -n.z / n.y, J, foam)
// with the sign correction (-1)^(m+n) (element n holds wave number n - N/2), the Jacobian
// J = (1 + λ ∂Dx/∂x)(1 + λ ∂Dz/∂z) - (λ ∂Dx/∂z)² (Tessendorf 2001, eq. 45), the exact normal n
// of the displaced surface P = (x + λDx, h, z + λDz), n = ∂P/∂z × ∂P/∂x (n.y = J, floored at
// NORMAL_MIN_JACOBIAN; `exact_slopes` in src/ocean/cpu.rs), and, in layer 0 only, persistent
// foam (src/ocean/foam.rs) from the Jacobian of the whole surface the renderer shows, every
// cascade summed at the rest position x = (n, m)·L_0/N:
//   J_s = (1 + Σ λDxx)(1 + Σ λDzz) − (Σ λDxz)²   (cascade c read at x mod L_c, bilinear)
//   foam = max(foam_prev · exp(−dt / decay), clamp((threshold − J_s) · gain, 0, 1))
// foam_prev is the previous slot's layer 0 at the same texel: foam lives at rest positions, so it
// rides the choppy displacement with the water it formed in. `surface_jacobian` in
// src/ocean/cpu.rs is the CPU reference. It also writes each cascade's sign-corrected
// derivatives (∂Dx/∂x, ∂Dz/∂z, ∂Dx/∂z, 0) before choppiness, as `field_derivatives_at` reads
// them at a texel, for foam.comp: four image loads a bilinear lookup instead of eight buffer
// reads and their index and sign arithmetic (only when the foam step runs).
#include "common/ocean.glsl"
#include "shared.glsl"
layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, set = 0, binding = 0) readonly buffer Fields { vec2 fields[]; };
#include "common/fields.glsl"
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2DArray displacement;
layout(set = 0, binding = 2, rgba32f) uniform writeonly image2DArray normals;
layout(set = 0, binding = 3, rgba32f) uniform readonly image2DArray previous_normals;
layout(set = 0, binding = 4, rgba32f) uniform writeonly image2DArray derivatives;
layout(push_constant) uniform Params {
    vec4 patch_m; // side of each cascade's patch (m)
    float choppiness;
    float dt_s;
    float foam_threshold;
    float foam_decay_s;
    float foam_gain;
    uint n;
    uint cascades;
    uint derivatives; // 1: write `derivatives` (the foam step runs)
} params;

void main() {
    uint n = params.n;
    uvec3 id = gl_GlobalInvocationID;
    if (id.x >= n || id.y >= n) {
        return;
    }
    uint c = id.z;
    uint plane = n * n;
    uint at = id.y * n + id.x;
    float sign = ((id.x + id.y) & 1u) == 1u ? -1.0 : 1.0;
    vec2 p0 = fields[(c * 4u + 0u) * plane + at] * sign; // (Dx, h)
    vec2 p1 = fields[(c * 4u + 1u) * plane + at] * sign; // (Dz, ∂h/∂x)
    vec2 p2 = fields[(c * 4u + 2u) * plane + at] * sign; // (∂h/∂z, ∂Dx/∂x)
    vec2 p3 = fields[(c * 4u + 3u) * plane + at] * sign; // (∂Dz/∂z, ∂Dx/∂z)
    float l = params.choppiness;
    float jacobian = (1.0 + l * p2.y) * (1.0 + l * p3.x) - (l * p3.y) * (l * p3.y);

    ivec3 texel = ivec3(id.xy, c);
    float foam = 0.0;
    if (c == 0u) {
        vec3 d = vec3(p2.y, p3.x, p3.y);
        for (uint o = 1u; o < params.cascades; ++o) {
            d += field_derivatives_at(o, vec2(id.xy) * (params.patch_m.x / params.patch_m[o]), n);
        }
        d *= l;
        float surface_j = surface_jacobian(d);
        float source = clamp((params.foam_threshold - surface_j) * params.foam_gain, 0.0, 1.0);
        foam = max(imageLoad(previous_normals, texel).w * exp(-params.dt_s / params.foam_decay_s), source);
    }

    imageStore(displacement, texel, vec4(l * p0.x, p0.y, l * p1.x, 0.0));
    if (params.derivatives != 0u) {
        imageStore(derivatives, texel, vec4(p2.y, p3.x, p3.y, 0.0));
    }
    // p1.y = ∂h/∂x, p2.x = ∂h/∂z, p2.y = ∂Dx/∂x, p3.x = ∂Dz/∂z, p3.y = ∂Dx/∂z.
    float j = max(jacobian, NORMAL_MIN_JACOBIAN);
    vec2 slope = vec2(p1.y * (1.0 + l * p3.x) - p2.x * l * p3.y,
                      p2.x * (1.0 + l * p2.y) - p1.y * l * p3.y) / j;
    imageStore(normals, texel, vec4(slope, jacobian, foam));
}
