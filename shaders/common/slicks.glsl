// Natural slicks (src/render/slicks.rs, its CPU twin, has the law and the papers): bands of sea
// a film of surface-active matter smooths. `slick_at` says how much of the world point xz (m)
// lies in one (0–1): the clouds' fractal noise in a space stretched along the wind (cells
// SLICK_ALONG_M by SLICK_ACROSS_M), drifting with the wind, above the frame's threshold. The
// water's vertices take it (common/water_vertex.glsl); water.frag lets the unresolved slopes
// there have Cox & Munk's slick-surface mean square instead of the clean sea's.
// Needs common/frame.glsl (and so clouds.glsl) included before it.
#ifndef SLICKS_GLSL
#define SLICKS_GLSL

// SLICK_ALONG_M, SLICK_ACROSS_M, SLICK_EDGE, SLICK_NONE, SLICK_NOISE_OFFSET_X, _Y: src/shared.rs.

float slick_at(vec2 xz) {
    // No branch for "no slicks" (threshold SLICK_NONE, above the noise's range: the smoothstep
    // gives 0): on lavapipe (Mesa 22.3) the noise's loop inside a uniform branch of the water's
    // vertex stage leaked about 0.7 MB of host memory a frame (tests/soak.rs).
    float n = wind_shape(xz, frame.slick_space.zw, vec2(SLICK_ALONG_M, SLICK_ACROSS_M),
                         frame.slick_space.x, vec2(SLICK_NOISE_OFFSET_X, SLICK_NOISE_OFFSET_Y));
    return smoothstep(frame.slicks.w, frame.slicks.w + SLICK_EDGE, n);
}
#endif
