#version 460
// Anti-aliasing pass, first draw (`--aa fxaa`): copies the main colour into the anti-aliased
// target, sharpened off the edges (`--sharpen`), and marks the pixels FXAA will change, those
// whose local contrast reaches its edge thresholds (common/fxaa.glsl), with depth 0 (the rest
// 1). The second draw (post/fxaa.frag) is depth-tested against the mark, so the rasterizer
// skips its shader where no pixel is on an edge: lavapipe runs every pixel of a 4x4 block
// through the whole shader, branch or not.
//
// The sharpening is contrast-adaptive, after the idea of Lottes' CAS (AMD FidelityFX, 2019):
// the pixel less a share of its four neighbours, (c + w Σ n) / (1 + 4w) with w ≤ 0, the share
// scaled per channel by the headroom the neighbourhood leaves below 1 and above 0
// (√(min(lo, 1 − hi) / hi)), so a pixel next to black or white, or on a strong gradient, is
// sharpened little and the result cannot leave the displayable range. It runs at the scene
// target's size, before the output pass scales it up (bilinearly, or edge-directed: --upscale;
// a quarter of the output's pixels at --quality low), and offsets the blur that scaling adds.
// The pixels FXAA then changes (on edges) keep FXAA's result: edges are smoothed along their
// direction, the texture between them sharpened.
#include "common/fxaa.glsl"

// The sharpening, 0 (a copy: w = 0 leaves the pixel's bits as they are) to 1.
layout(push_constant) uniform Sharpen {
    float amount;
} pc;

layout(location = 0) out vec4 out_colour;

// The neighbours' weight at full sharpening: CAS's strongest lobe, −1/5.
const float SHARPEN_LOBE = -0.2;

vec3 at(ivec2 p, ivec2 size) {
    return texelFetch(display_colour, clamp(p, ivec2(0), size - 1), 0).rgb;
}

void main() {
    ivec2 size = textureSize(display_colour, 0);
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec3 centre = at(p, size);
    vec3 n = at(p + ivec2(0, -1), size);
    vec3 s = at(p + ivec2(0, 1), size);
    vec3 w = at(p + ivec2(-1, 0), size);
    vec3 e = at(p + ivec2(1, 0), size);
    vec3 lo = min(centre, min(min(n, s), min(w, e)));
    vec3 hi = max(centre, max(max(n, s), max(w, e)));
    vec3 headroom = clamp(min(lo, 1.0 - hi) / max(hi, vec3(1e-4)), 0.0, 1.0);
    vec3 weight = sqrt(headroom) * (SHARPEN_LOBE * pc.amount);
    vec3 sharp = (centre + weight * (n + s + w + e)) / (1.0 + 4.0 * weight);
    out_colour = vec4(clamp(sharp, 0.0, 1.0), 1.0);
    // The mark: 0 on an edge, 1 elsewhere; fxaa.frag, drawn at depth 0 with GREATER_OR_EQUAL,
    // runs where it is 0 (the scene's reversed-Z direction: NVIDIA's Z-cull keeps one).
    Cross c = Cross(luma(centre), luma(n), luma(s), luma(w), luma(e));
    gl_FragDepth = on_edge(contrast(c)) ? 0.0 : 1.0;
}
