// The tessellated ocean surface (shaders/surface/water.*): a grid of PATCHES² quad patches
// centred on the camera (snapped to SNAP_M so the patches do not slide over the waves), their
// corners spread by a cubic warp from a few metres under the camera to FAR_M at the horizon.
// Each patch is an axis-aligned rectangle and shares its edges exactly with its neighbours.
const uint PATCHES = 32u;          // per side (WaterPass::PATCHES in src/render/passes/water.rs)
const float INNER_M = 48.0;        // linear part of the warp
const float FAR_M = 20000.0;       // half-side of the grid
const float SNAP_M = 8.0;          // about the innermost patch's side

float warp(float u) { return sign(u) * (INNER_M * abs(u) + (FAR_M - INNER_M) * abs(u) * abs(u) * abs(u)); }

// x*(1-t) + y*t, exact at t = 0 and t = 1 (shared patch edges evaluate to identical points).
vec2 lerp2(vec2 x, vec2 y, float t) { return x * (1.0 - t) + y * t; }

// Cascades in the ocean images: specialized by WaterPass (src/render/passes/water.rs).
layout(constant_id = 0) const int CASCADES = 3;

// Sum of every cascade's displacement at an undisplaced world point.
// No branch here depends on a uniform: Mesa 22.3's lavapipe "inlines" uniforms that steer control
// flow into a fresh evaluation-shader variant at every bind of the pipeline and never frees it
// (about 350 kB and a shader compile per frame; README, "Measured on lavapipe"). Hence the
// specialized loop bound and ocean_uv's branch-free weight.
vec3 ocean_displacement_at(vec2 world_xz, float dist) {
    vec3 d = vec3(0.0);
    for (int c = 0; c < CASCADES; ++c) {
        float weight;
        vec3 uv = ocean_uv(world_xz, c, dist, weight);
        d += weight * textureLod(ocean_displacement, uv, 0.0).xyz;
    }
    return d;
}
