#version 460
// Height queries (src/ocean/simulation/queries.rs): for each asked world point (x, z), the
// surface above it as the water draws it from this slot's images, and how fast it rises.
//
// The water displaces a rest point (α, β) by the sum over cascades of the images, bilinear
// between texels, scaled by the shore's factor at the rest point (common/water_vertex.glsl).
// The point that lands on (x, z) is found by fixed-point iteration, α ← α + x − X(α, β), as
// `SurfaceQuery::rest_position` does on the CPU (it converges where the surface does not fold,
// J > 0). Texels are read exactly (imageLoad, fp32 weights): hardware filtering weighs with
// as few as 8 bits, millimetres on a steep crest, and the answers are meant to match the CPU's
// to well under that. Not included: the surf's bores near the shore (as on the CPU).
//
// The vertical velocity is the rate at the fixed point (x, z): the height found the same way in
// the previous slot's images (the frame before, at params.rate = 1/Δt; 0 when there is none),
// differenced.
#include "shared.glsl"
layout(local_size_x = 64) in;

// The placement and the scene's fields of the frame uniforms (as shaders/common/frame.glsl has
// them) that common/terrain.glsl and common/shore.glsl read.
layout(std140, set = 0, binding = 0) uniform Placement {
    // Per cascade: the anchor's texel coordinate (node units, reduced on the CPU in f64) in this
    // slot's images (xy) and in the previous slot's (zw).
    vec4 base[4];
    vec4 texels_per_m; // per cascade: 1 / node spacing
    vec4 place;        // xy: the anchor's world xz (m); z: unused; w: water level (m)
    vec4 terrain;      // island x, z, shelf depth, island radius
    vec4 shore;        // the sea's Hs, mean ω, c_g at the simulated depth
    vec4 open_sea;     // the open sea's floor depth, K_s there
    vec4 wake_base;    // the anchor's texel coordinate in this slot's wake image (xy), the
                       // previous slot's (zw)
    vec4 wake;         // x: the wake's texels per metre; y: 1 with a wake (--boat)
} frame;
#include "common/terrain.glsl"
#include "common/shore.glsl"

// The points, relative to the anchor (m).
layout(std430, set = 0, binding = 1) readonly buffer Points { vec2 points[]; };
// Two per point: (λD_x, h, λD_z, ∂h/∂t) of the surface above it; (normal, residual of the
// inversion in m: over a millimetre where the surface folds).
layout(std430, set = 0, binding = 2) writeonly buffer Answers { vec4 answers[]; };
layout(set = 0, binding = 3, rgba32f) uniform readonly image2DArray displacement;
layout(set = 0, binding = 4, rgba32f) uniform readonly image2DArray normals;
layout(set = 0, binding = 5, rgba32f) uniform readonly image2DArray previous;
// The boat's wake (src/ocean/wake.rs), this slot's and the previous slot's: (h, ∂h/∂x, ∂h/∂z, foam)
// with texel i at the grid's origin + i·spacing; 1×1 without a boat.
layout(set = 0, binding = 6, rgba32f) uniform readonly image2DArray wake_here;
layout(set = 0, binding = 7, rgba32f) uniform readonly image2DArray wake_before;
layout(push_constant) uniform Params {
    uint count;    // points asked
    uint cascades;
    uint periodic; // 1: the FFT's tiling cascades; 0: the Gerstner window (clamped)
    uint shore;    // 1: the waves scaled over the island's shallows; 0: no island (scale 1)
    // 1/Δt to the previous slot's images (0: none). A push constant, as every value a branch
    // tests: Mesa 22.3's lavapipe compiles a fresh variant for a uniform that steers control
    // flow at every dispatch (13 ms a frame here; README, "Measured on lavapipe").
    float rate;
} params;

// Iterations of the inversion (the CPU's bound) and the step below which it stops (m; fp32
// resolves about 4 µm at 50 m from the anchor).
const int INVERT_STEPS = 16;
const float INVERT_DONE_M = 2e-5;

ivec2 texel(ivec2 t, int n) {
    return params.periodic == 1u ? ((t % n) + n) % n : clamp(t, ivec2(0), ivec2(n - 1));
}

// Texel t of cascade c of image `which` (0: displacement, 1: normals, 2: previous displacement).
vec4 load(int which, ivec2 t, int c) {
    int n = imageSize(displacement).x;
    ivec3 p = ivec3(texel(t, n), c);
    if (which == 0) return imageLoad(displacement, p);
    if (which == 1) return imageLoad(normals, p);
    return imageLoad(previous, p);
}

// Image `which` at the rest point `rest` (m from the anchor), bilinear, summed over cascades.
vec4 sum_at(int which, vec2 rest) {
    vec4 sum = vec4(0.0);
    for (int c = 0; c < int(params.cascades); ++c) {
        vec2 base = which == 2 ? frame.base[c].zw : frame.base[c].xy;
        vec2 u = base + rest * frame.texels_per_m[c];
        vec2 f = floor(u);
        vec2 w = u - f;
        ivec2 i = ivec2(f);
        vec4 a = load(which, i, c);
        vec4 b = load(which, i + ivec2(1, 0), c);
        vec4 d = load(which, i + ivec2(0, 1), c);
        vec4 e = load(which, i + ivec2(1, 1), c);
        sum += mix(mix(a, b, w.x), mix(d, e, w.x), w.y);
    }
    return sum;
}

// What the depth under the rest point makes of the waves (`shore_scale` on the CPU): past
// the island's slope the floor is flat, its K_s given (frame.open_sea.y), as the water's
// vertices take it (common/water_vertex.glsl).
float shore_scale(vec2 rest) {
    if (params.shore == 0u) return 1.0;
    vec2 world = frame.place.xy + rest;
    if (!near_island(world)) return shore_waves_at(frame.open_sea.y, frame.open_sea.x).x;
    float depth = frame.place.w - terrain_height(world);
    return shore_waves_at(shore_shoaling(depth), depth).x;
}

// The wake's (h, ∂h/∂x, ∂h/∂z) at the rest point, bilinear, as the water adds it to the
// height and slopes there (common/frame.glsl `wake_at`); zero off its grid. `before`: the
// previous slot's.
vec3 wake_at(bool before, vec2 rest) {
    vec2 u = (before ? frame.wake_base.zw : frame.wake_base.xy) + rest * frame.wake.x;
    int n = imageSize(wake_here).x;
    if (frame.wake.y == 0.0 || any(lessThan(u, vec2(0.0))) || any(greaterThan(u, vec2(n - 1)))) {
        return vec3(0.0);
    }
    ivec2 i = min(ivec2(floor(u)), ivec2(n - 2));
    vec2 w = u - vec2(i);
    vec4 a, b, d, e;
    if (before) {
        a = imageLoad(wake_before, ivec3(i, 0));
        b = imageLoad(wake_before, ivec3(i + ivec2(1, 0), 0));
        d = imageLoad(wake_before, ivec3(i + ivec2(0, 1), 0));
        e = imageLoad(wake_before, ivec3(i + ivec2(1, 1), 0));
    } else {
        a = imageLoad(wake_here, ivec3(i, 0));
        b = imageLoad(wake_here, ivec3(i + ivec2(1, 0), 0));
        d = imageLoad(wake_here, ivec3(i + ivec2(0, 1), 0));
        e = imageLoad(wake_here, ivec3(i + ivec2(1, 1), 0));
    }
    return mix(mix(a, b, w.x), mix(d, e, w.x), w.y).xyz;
}

// The rest point carried to `p` in image `which` (0 or 2) from the first guess `rest`, and
// its scaled displacement there.
vec3 invert(int which, vec2 p, inout vec2 rest) {
    for (int k = 0; k < INVERT_STEPS; ++k) {
        vec3 d = shore_scale(rest) * sum_at(which, rest).xyz;
        vec2 e = p - (rest + d.xz);
        rest += e;
        if (max(abs(e.x), abs(e.y)) < INVERT_DONE_M) break;
    }
    // The displacement at the final rest point (the one the answer describes).
    return shore_scale(rest) * sum_at(which, rest).xyz;
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= params.count) return;
    vec2 p = points[i];
    vec2 rest = p;
    vec3 d = invert(0, p, rest);
    float residual = length(p - (rest + d.xz));
    float scale = shore_scale(rest);
    vec3 wake = wake_at(false, rest);
    d.y += scale * wake.x;
    vec2 slope = scale * (sum_at(1, rest).xy + wake.yz);
    vec3 normal = normalize(vec3(-slope.x, 1.0, -slope.y));
    float rate = 0.0;
    if (params.rate > 0.0) {
        // A frame earlier the rest point was nearly the same: a few steps from there.
        vec2 before_rest = rest;
        vec3 before = invert(2, p, before_rest);
        before.y += shore_scale(before_rest) * wake_at(true, before_rest).x;
        rate = (d.y - before.y) * params.rate;
    }
    answers[2 * i] = vec4(d, rate);
    answers[2 * i + 1] = vec4(normal, residual);
}
