#version 460
// Assemble the inverse-FFT output into the images the renderer samples (one layer per cascade):
//   displacement = (λ Dx, h, λ Dz, 0),  normals = (-n.x / n.y, -n.z / n.y, J, foam)
// with the sign correction (-1)^(m+n) (element n holds wave number n - N/2), the Jacobian
// J = (1 + λ ∂Dx/∂x)(1 + λ ∂Dz/∂z) - (λ ∂Dx/∂z)² (Tessendorf 2001, eq. 45), the exact normal n
// of the displaced surface P = (x + λDx, h, z + λDz), n = ∂P/∂z × ∂P/∂x (n.y = J, floored at
// NORMAL_MIN_JACOBIAN; `exact_slopes` in src/ocean/cpu.rs), and persistent foam:
//   foam = foam_prev · exp(-dt / decay) + clamp((threshold - J) · gain, 0, 1), clamped to [0, 1],
// read from the previous slot's normal image (foam grows where the surface folds, J < threshold,
// and fades exponentially).
#include "common/ocean.glsl"
#include "shared.glsl"
layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, set = 0, binding = 0) readonly buffer Fields { vec2 fields[]; };
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2DArray displacement;
layout(set = 0, binding = 2, rgba32f) uniform writeonly image2DArray normals;
layout(set = 0, binding = 3, rgba32f) uniform readonly image2DArray previous_normals;
layout(push_constant) uniform Params {
    float choppiness;
    float dt_s;
    float foam_threshold;
    float foam_decay_s;
    float foam_gain;
    uint n;
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
    float foam = imageLoad(previous_normals, texel).w * exp(-params.dt_s / params.foam_decay_s);
    foam = clamp(foam + clamp((params.foam_threshold - jacobian) * params.foam_gain, 0.0, 1.0), 0.0, 1.0);

    imageStore(displacement, texel, vec4(l * p0.x, p0.y, l * p1.x, 0.0));
    // p1.y = ∂h/∂x, p2.x = ∂h/∂z, p2.y = ∂Dx/∂x, p3.x = ∂Dz/∂z, p3.y = ∂Dx/∂z.
    float j = max(jacobian, NORMAL_MIN_JACOBIAN);
    vec2 slope = vec2(p1.y * (1.0 + l * p3.x) - p2.x * l * p3.y,
                      p2.x * (1.0 + l * p2.y) - p1.y * l * p3.y) / j;
    imageStore(normals, texel, vec4(slope, jacobian, foam));
}
