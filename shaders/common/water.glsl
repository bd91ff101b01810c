// The tessellated ocean surface (shaders/surface/water.*): a grid of PATCHES² quad patches
// centred on the camera (snapped to WATER_SNAP_M in src/render/uniforms.rs, so the patches do not
// slide over the waves), their corners spread by a cubic warp from a few metres under the camera
// to FAR_M at the horizon. Each patch is an axis-aligned rectangle and shares its edges exactly
// with its neighbours. Positions ("xz") are relative to the grid's centre (camera-relative
// rendering: frame.water).
#include "shared.glsl"             // PATCHES: per side (src/shared.rs)
const float INNER_M = 48.0;        // linear part of the warp
const float FAR_M = 20000.0;       // half-side of the grid

float warp(float u) { return sign(u) * (INNER_M * abs(u) + (FAR_M - INNER_M) * abs(u) * abs(u) * abs(u)); }

// x*(1-t) + y*t, exact at t = 0 and t = 1 (shared patch edges evaluate to identical points).
vec2 lerp2(vec2 x, vec2 y, float t) { return x * (1.0 - t) + y * t; }

// Camera position relative to the grid centre: xz from frame.water, y the camera's height.
vec3 water_eye() { return vec3(frame.water.x, frame.views[0].eye.y, frame.water.y); }

// Water's refractive index (water.frag's Fresnel and view from below, common/caustics.glsl).
const float N_WATER = 1.333;

// Cascades in the ocean images: specialized by WaterPass (src/render/passes/water.rs).
layout(constant_id = 0) const int CASCADES = 3;

// Set by WaterPass where the device cannot filter RGBA32F images linearly: the ocean sampler is
// then NEAREST and ocean_texture interpolates the four texels around uv itself (repeat wrapping
// comes from the sampler). Same result as the hardware's bilinear filter, to float rounding.
layout(constant_id = 1) const bool OCEAN_MANUAL_FILTER = false;

// SLOPE_MIPS: the normal images have mip levels (src/ocean/simulation/slope_mips.rs, above a
// 64² grid). water.frag looks each cascade up at the level of the pixel's footprint, along the
// view and across it, and common/caustics.glsl low-passes each cascade's slopes with them.
// Without them (`--quality low`) a cascade's slopes fade out as a whole once the footprint
// passes its shortest waves, which took its longer waves with them: at 10–20 m from a camera
// 3 m up (320x180) the sea held 0.4 times the detail of a supersampled picture.
layout(constant_id = 6) const bool SLOPE_MIPS = false;

// A level's texel of side a is a box of side a, and its bilinear lookup a tent of half-width a
// on top: variance a²/12 + a²/6 = a²/4 along each axis. A pixel's footprint f (the spacing of
// pixel centres) is a box of variance f²/12, the same when a = f/√3: the level's LOD is
// log2(f / texel) − log2 √3. (Measured against 4x4 supersampling, tests/far_field.rs: 0.7 times
// its detail at 10–30 m with no bias, 0.93 with this one.)
const float SLOPE_LOD_BIAS = 0.79;

// Cascade c's entry at mip level `lod` (fractional) of a [level][cascade] table of what the
// levels leave of it (frame.slope_mips: src/ocean/moments.rs),
// trilinear between levels like the lookup.
float mip_gain(vec4 table[SLOPE_LEVELS], int c, float lod) {
    float l = clamp(lod, 0.0, float(SLOPE_LEVELS - 1u));
    int i = int(l);
    int j = min(i + 1, int(SLOPE_LEVELS) - 1);
    return mix(table[i][c], table[j][c], l - float(i));
}

// The shortest waves cascade c's normal image draws (m; `texels` per side): two texels, and
// for every cascade but the finest no shorter than its patch / 26, where the next cascade's
// waves take over. The slope and caustic fades compare a pixel's footprint with it.
float cascade_shortest_m(int c, float texels) {
    float patch_m = frame.patch_m[c];
    return c == CASCADES - 1 ? 2.0 * patch_m / texels : max(patch_m / 26.0, 2.0 * patch_m / texels);
}

// Bilinear by hand within mip level `level` (OCEAN_MANUAL_FILTER).
vec4 bilinear_by_hand(sampler2DArray images, vec3 uv, int level) {
    vec2 size = vec2(textureSize(images, level).xy);
    vec2 p = uv.xy * size - 0.5;
    vec2 f = fract(p);
    vec2 c = (floor(p) + 0.5) / size; // centre of the lower-left texel
    vec2 d = 1.0 / size;
    float l = float(level);
    vec4 a = textureLod(images, vec3(c, uv.z), l);
    vec4 b = textureLod(images, vec3(c + vec2(d.x, 0.0), uv.z), l);
    vec4 e = textureLod(images, vec3(c + vec2(0.0, d.y), uv.z), l);
    vec4 g = textureLod(images, vec3(c + d, uv.z), l);
    return mix(mix(a, b, f.x), mix(e, g, f.x), f.y);
}

vec4 ocean_texture(sampler2DArray images, vec3 uv) {
    if (!OCEAN_MANUAL_FILTER) {
        return textureLod(images, uv, 0.0);
    }
    return bilinear_by_hand(images, uv, 0);
}

// The same at mip level `lod` (≥ 0), trilinear: by hand, the two levels around it blended.
vec4 ocean_texture_lod(sampler2DArray images, vec3 uv, float lod) {
    if (!OCEAN_MANUAL_FILTER) {
        return textureLod(images, uv, lod);
    }
    float l = min(lod, float(textureQueryLevels(images) - 1));
    int i = int(l);
    int j = min(i + 1, textureQueryLevels(images) - 1);
    return mix(bilinear_by_hand(images, uv, i), bilinear_by_hand(images, uv, j), l - float(i));
}

// The wake's (h, ∂h/∂x, ∂h/∂z, foam) at a point `xz` metres from the water grid's centre
// (common/frame.glsl's `wake_field`, bilinear as the height queries read it); zero off its grid
// (its absorbing edge has already taken the wake to zero there) and without a boat.
// WAKE: the run has a boat (`--boat`; src/render/passes/water.rs specializes the water's
// pipelines by it). Without one the lookups are left out, not multiplied by frame.wake.w = 0:
// lavapipe paid 0.5 ms a frame at --quality low for the three of them.
layout(constant_id = 7) const bool WAKE = true;
vec4 wake_at(vec2 xz) {
    if (!WAKE) {
        return vec4(0.0);
    }
    vec2 uv = frame.wake.xy + xz * frame.wake.z;
    float inside = step(0.0, uv.x) * step(uv.x, 1.0) * step(0.0, uv.y) * step(uv.y, 1.0);
    return frame.wake.w * inside * ocean_texture(wake_field, vec3(uv, 0.0));
}

// Sum of every cascade's displacement at an undisplaced point (relative to the grid centre).
// No branch here depends on a uniform: Mesa 22.3's lavapipe "inlines" uniforms that steer control
// flow into a fresh evaluation-shader variant at every bind of the pipeline and never frees it
// (about 350 kB and a shader compile per frame; README, "Measured on lavapipe"). Hence the
// specialized loop bound and ocean_uv's branch-free weight.
vec3 ocean_displacement_at(vec2 xz, float dist) {
    vec3 d = vec3(0.0);
    for (int c = 0; c < CASCADES; ++c) {
        float weight;
        vec3 uv = ocean_uv(xz, c, dist, weight);
        d += weight * ocean_texture(ocean_displacement, uv).xyz;
    }
    d.y += wake_at(xz).x;
    return d;
}
