#version 460
// Output pass, drawn (src/render/passes/output.rs): where the output image takes no copies
// (a swapchain without TRANSFER_DST usage), or the picture is scaled, it is drawn into the
// output as a colour attachment instead of copied or blitted. Input: the main or anti-aliased
// colour (binding 0), sampled nearest at the same size, bilinearly when scaling. Output: the
// output image; an sRGB pair decodes on sampling and encodes on writing, a UNORM pair passes
// the bytes through. Vertex shader: common/fullscreen.vert.
//
// Scaling up with `--upscale edge` is edge-directed: across the local edge the bilinear sample
// is sharpened, along it left alone. The edge is the luma gradient n of the 2x2 texels the
// bilinear sample blends (one gather of green, the perceptual luma's largest share); the sample
// loses a share of its second difference along n (bilinear samples one texel either side), and
// is clamped to the range of those three, so it cannot ring. The ramp two output pixels wide
// that bilinear scaling draws across a step becomes steeper; along the edge, and where the
// texels agree, nothing changes. After edge-aware upscalers (Lottes' EASU in AMD FidelityFX
// FSR 1, 2021, a Lanczos kernel narrowed across the edge and stretched along it, its negative
// lobes clamped to the neighbourhood); written from the idea, 4 lookups instead of 12. Moving
// the sample across the edge toward the nearer texel instead (tried first) drew stair steps.
layout(set = 0, binding = 0) uniform sampler2D picture;

// 1: scaling up edge-directed; 0: sampling as the sampler filters (output.rs makes a pipeline
// for each: lavapipe would pay for an untaken branch's lookups).
layout(constant_id = 0) const int EDGE = 0;

layout(location = 0) in vec2 in_uv;
layout(location = 0) out vec4 out_colour;

// The luma step across the 2x2 texels (perceptual: square roots of linear green) below which
// nothing is sharpened (EDGE_LO) and from which fully (EDGE_HI).
const float EDGE_LO = 0.01;
const float EDGE_HI = 0.06;
// The share of the second difference taken off at a full edge.
const float SHARPEN = 0.75;

void main() {
    if (EDGE == 0) {
        out_colour = textureLod(picture, in_uv, 0.0);
        return;
    }
    vec2 size = vec2(textureSize(picture, 0));
    vec2 p = in_uv * size; // texel space: texel centres at i + 0.5
    vec2 corner = floor(p - 0.5) + 1.0; // where the four texels the sample blends meet
    // Gather order: (0, 1), (1, 1), (1, 0), (0, 0) of the 2x2 block (x right, y down).
    vec4 g = sqrt(max(textureGather(picture, corner / size, 1), 0.0));
    vec2 gradient = vec2(g.y + g.z - g.x - g.w, g.x + g.y - g.z - g.w) * 0.5;
    float step_size = length(gradient);
    float edge = smoothstep(EDGE_LO, EDGE_HI, step_size);
    vec2 n = step_size > 1e-6 ? gradient / step_size : vec2(0.0);
    vec3 centre = textureLod(picture, in_uv, 0.0).rgb;
    vec2 step_uv = n / size;
    vec3 before = textureLod(picture, in_uv - step_uv, 0.0).rgb;
    vec3 after = textureLod(picture, in_uv + step_uv, 0.0).rgb;
    vec3 sharp = centre - SHARPEN * edge * (before + after - 2.0 * centre);
    sharp = clamp(sharp, min(centre, min(before, after)), max(centre, max(before, after)));
    out_colour = vec4(sharp, 1.0);
}
