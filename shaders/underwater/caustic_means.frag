#version 460
// The caustics' means (common/caustics.glsl): for the floor depth and pixel footprint of this
// texel (`caustic_mean_texel`), the mean of the area ratio the floor (r: one fixed-point step)
// and the light shafts and the mirrored floor (g: none) take, over floor points on a jittered
// CAUSTIC_MEAN_GRID² grid across the largest cascade's patch (its bounded window in Gerstner
// mode), from this frame's normal images. The sea's statistics do not change with time, so
// src/render/passes/caustic_means.rs draws this again only when the sun, the waves or the view's
// focal length change. A pixel footprint `pixel_m` is seen from `pixel_m` · focal length away
// (a floor facing the eye), which sets the cascades' fade with distance (`ocean_uv`).
#include "common/frame.glsl"
#include "common/water.glsl"
#define CAUSTIC_MEANS_PASS
#include "common/caustics.glsl"

layout(location = 1) in vec2 in_ndc;
layout(location = 0) out vec4 out_means;

// Floor points per side: the mean of 9,216 ratios per texel (48² left the means ±2 % apart
// from one moment of the sea to the next, this about half that).
const int CAUSTIC_MEAN_GRID = 96;

// A hash of two integers to [0, 1) (the jitter within a grid cell).
vec2 cell_jitter(ivec2 cell) {
    uvec2 v = uvec2(cell) * uvec2(1664525u, 1013904223u) + uvec2(374761393u, 668265263u);
    v.x += v.y * 1664525u;
    v.y += v.x * 1664525u;
    v ^= v >> 16u;
    v.x += v.y * 1664525u;
    v.y += v.x * 1664525u;
    v ^= v >> 16u;
    return vec2(v & 0xffffu) / 65536.0;
}

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    float depth = CAUSTIC_MEAN_DEPTH0_M * exp2(0.5 * float(texel.x));
    float pixel_m = CAUSTIC_MEAN_PIXEL0_M * exp2(float(texel.y));
    float dist = pixel_m * frame.lod.x;
    // The square the points cover, relative to the water grid's centre: a whole patch of the
    // largest cascade, or the middle of the Gerstner waves' window (where ocean_uv's weight
    // is 1).
    bool window = frame.modes.z == 1u;
    float side = frame.patch_m[0] * (window ? 0.7 : 1.0);
    vec2 centre = window ? (0.5 - frame.cascade_uv[0].xy) * frame.patch_m[0] : vec2(0.0);
    vec3 l = frame.sun_dir.xyz;
    float stepped = 0.0;
    float level = 0.0;
    for (int i = 0; i < CAUSTIC_MEAN_GRID; ++i) {
        for (int j = 0; j < CAUSTIC_MEAN_GRID; ++j) {
            vec2 jitter = cell_jitter(ivec2(i, j) + 97 * texel);
            vec2 cell = (vec2(i, j) + jitter) / float(CAUSTIC_MEAN_GRID);
            vec2 xz = centre + (cell - 0.5) * side;
            // As caustic_raw with one step and with none, sharing the first surface.
            vec2 s;
            mat2 hess;
            float bundle_m;
            caustic_surface(xz - depth * caustic_run(vec2(0.0), l), depth, dist, pixel_m, s, hess,
                            bundle_m);
            level += caustic_area_ratio(s, hess, bundle_m, depth);
            caustic_surface(xz - depth * caustic_run(s, l), depth, dist, pixel_m, s, hess,
                            bundle_m);
            stepped += caustic_area_ratio(s, hess, bundle_m, depth);
        }
    }
    float n = float(CAUSTIC_MEAN_GRID * CAUSTIC_MEAN_GRID);
    out_means = vec4(stepped / n, level / n, 0.0, 1.0);
}
