// What the two draws of the anti-aliasing pass share (post/fxaa_edges.frag marks the pixels on
// an edge, post/fxaa.frag anti-aliases them): FXAA's luma, its edge thresholds and the local
// contrast test (Lottes 2009, "FXAA", NVIDIA whitepaper). Input: the main colour (display
// colour at --render-scale) through a linear, clamped sampler.

// DISPLAY_TARGET of common/display.glsl: 1 = the target has an sRGB format, so samples are
// linear (decoded) and the attachment encodes; 2 = a UNORM target holding encoded values.
layout(constant_id = 0) const int DISPLAY_TARGET = 1;
// Lottes' fastest preset (FXAA 3.11's quality preset 10, 3 search steps, and his "low quality"
// edge threshold, 0.25) instead of his defaults (preset 12, 0.166): `--quality low`
// (src/render/passes/anti_aliasing.rs).
layout(constant_id = 1) const bool FXAA_FAST = false;

layout(set = 0, binding = 0) uniform sampler2D display_colour;

// Lottes' defaults (FXAA 3.11, "quality" preset 12), or his low quality (FXAA_FAST). The
// local contrast needed, relative to the brightest luma:
const float EDGE_THRESHOLD = FXAA_FAST ? 0.25 : 0.166;
const float EDGE_THRESHOLD_MIN = 0.0833; // ... and at least this (dark regions stay untouched)

// Perceptual luma (the whitepaper's: Rec. 601 weights on gamma-encoded colour; the square root
// stands in for the encoding of linear samples).
float luma(vec3 c) {
    float y = dot(c, vec3(0.299, 0.587, 0.114));
    return DISPLAY_TARGET == 1 ? sqrt(y) : y;
}

float luma_at(ivec2 p, ivec2 size) {
    return luma(texelFetch(display_colour, clamp(p, ivec2(0), size - 1), 0).rgb);
}

// The pixel's luma and its 4 neighbours': (centre, north, south, west, east), y down.
struct Cross {
    float m, n, s, w, e;
};

Cross cross_at(ivec2 p, ivec2 size, vec3 centre) {
    return Cross(luma(centre), luma_at(p + ivec2(0, -1), size), luma_at(p + ivec2(0, 1), size),
                 luma_at(p + ivec2(-1, 0), size), luma_at(p + ivec2(1, 0), size));
}

// Local contrast of the cross: (max − min, max).
vec2 contrast(Cross c) {
    float lo = min(c.m, min(min(c.n, c.s), min(c.w, c.e)));
    float hi = max(c.m, max(max(c.n, c.s), max(c.w, c.e)));
    return vec2(hi - lo, hi);
}

// Whether a pixel of this contrast is on an edge: it reaches both thresholds.
bool on_edge(vec2 contrast) {
    return contrast.x >= max(EDGE_THRESHOLD_MIN, contrast.y * EDGE_THRESHOLD);
}
