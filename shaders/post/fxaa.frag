#version 460
// Anti-aliasing pass, second draw (`--aa fxaa`): FXAA, after Lottes (2009), "FXAA", NVIDIA
// whitepaper (and the edge search of his FXAA 3 "quality" variant), on the pixels the first
// draw (post/fxaa_edges.frag) marked: a depth test passes only there. Written from the
// algorithm:
//   1. luma of the display colour at the pixel and its 8 neighbours (the first draw tested the
//      local contrast of the 4 nearest against the edge thresholds);
//   2. the 3x3 neighbourhood's second differences say whether the edge runs horizontally or
//      vertically, and the steeper of the two neighbours across it which side the edge is on;
//   3. along the edge, halfway between the pixel and that neighbour (a bilinear sample, the
//      mean of the two), search both ways until the luma leaves the edge's: its two ends;
//   4. a pixel near an end whose luma is on the other side of the edge's from that end's moves
//      its sample across the edge by 0.5 − distance / edge length (a stair step becomes a ramp);
//      the sub-pixel term (how far the pixel stands out of its 3x3 low-pass) moves it at least
//      that far, which softens aliasing finer than a pixel (a one-pixel line, a speck).
// Input: the main colour (common/fxaa.glsl). Output: the anti-aliased colour, same size and
// format, over the first draw's copy. Both draws use common/fullscreen.vert.
#include "common/fxaa.glsl"

layout(early_fragment_tests) in;
layout(location = 0) out vec4 out_colour;

const float SUBPIXEL = 0.75; // share of sub-pixel aliasing removed (Lottes' default; 0 = none)
// Search steps along the edge (pixels; his preset 12): ends within 20.5 px of the pixel are
// found; with FXAA_FAST his preset 10's three, within 16.5 px.
const int SEARCH_STEPS = FXAA_FAST ? 3 : 5;
const float STEP[5] = float[](1.0, 1.5, 2.0, 4.0, 12.0);
const float FAST_STEP[5] = float[](1.5, 3.0, 12.0, 0.0, 0.0);

float luma_sampled(vec2 uv) {
    return luma(textureLod(display_colour, uv, 0.0).rgb);
}

void main() {
    ivec2 size = textureSize(display_colour, 0);
    vec2 texel = 1.0 / vec2(size);
    ivec2 p = ivec2(gl_FragCoord.xy);
    Cross c = cross_at(p, size, texelFetch(display_colour, p, 0).rgb);
    float m = c.m, n = c.n, s = c.s, w = c.w, e = c.e;
    float range = contrast(c).x;
    float nw = luma_at(p + ivec2(-1, -1), size);
    float ne = luma_at(p + ivec2(1, -1), size);
    float sw = luma_at(p + ivec2(-1, 1), size);
    float se = luma_at(p + ivec2(1, 1), size);

    // Sub-pixel aliasing: the centre against the 3x3 low-pass, relative to the local contrast.
    float low_pass = (2.0 * (n + s + w + e) + nw + ne + sw + se) / 12.0;
    float subpixel = smoothstep(0.0, 1.0, clamp(abs(low_pass - m) / range, 0.0, 1.0));
    subpixel = subpixel * subpixel * SUBPIXEL;

    // Orientation: second differences down the three columns (a horizontal edge) against
    // along the three rows (a vertical edge), the middle one weighted twice.
    float down_columns = 2.0 * abs(n + s - 2.0 * m) + abs(nw + sw - 2.0 * w) + abs(ne + se - 2.0 * e);
    float along_rows = 2.0 * abs(w + e - 2.0 * m) + abs(nw + ne - 2.0 * n) + abs(sw + se - 2.0 * s);
    bool horizontal = down_columns >= along_rows;
    float before = horizontal ? n : w;
    float after = horizontal ? s : e;
    vec2 across = horizontal ? vec2(0.0, texel.y) : vec2(texel.x, 0.0);
    vec2 along = horizontal ? vec2(texel.x, 0.0) : vec2(0.0, texel.y);
    float gradient_before = abs(before - m);
    float gradient_after = abs(after - m);
    if (gradient_before >= gradient_after) {
        across = -across;
    }
    // The search stops where the luma differs from the edge's by a quarter of the step.
    float gradient = 0.25 * max(gradient_before, gradient_after);

    // Walk both ways along the boundary between the pixel and its neighbour across the edge.
    vec2 centre_uv = (vec2(p) + 0.5) * texel;
    vec2 start = centre_uv + 0.5 * across;
    float edge_luma = luma_sampled(start);
    float to_neg = 0.0, to_pos = 0.0;     // distances to the ends (pixels)
    float delta_neg = 0.0, delta_pos = 0.0; // luma there minus the edge's
    bool done_neg = false, done_pos = false;
    for (int i = 0; i < SEARCH_STEPS && !(done_neg && done_pos); i++) {
        if (!done_neg) {
            to_neg += FXAA_FAST ? FAST_STEP[i] : STEP[i];
            delta_neg = luma_sampled(start - to_neg * along) - edge_luma;
            done_neg = abs(delta_neg) >= gradient;
        }
        if (!done_pos) {
            to_pos += FXAA_FAST ? FAST_STEP[i] : STEP[i];
            delta_pos = luma_sampled(start + to_pos * along) - edge_luma;
            done_pos = abs(delta_pos) >= gradient;
        }
    }

    // Blend only toward the nearer end, and only if the luma there leans the other way from the
    // pixel's (else the pixel is on the far side of that end's step).
    bool nearer_neg = to_neg < to_pos;
    float end_delta = nearer_neg ? delta_neg : delta_pos;
    bool pixel_below = m < edge_luma;
    float edge_offset = (end_delta < 0.0) != pixel_below
        ? 0.5 - min(to_neg, to_pos) / (to_neg + to_pos)
        : 0.0;
    float offset = max(edge_offset, subpixel);
    out_colour = vec4(textureLod(display_colour, centre_uv + offset * across, 0.0).rgb, 1.0);
}
