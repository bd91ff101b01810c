#version 460
// The spray (src/ocean/simulation/spray_sim.rs, constants and sources in src/ocean/spray.rs):
// puffs of spume drops torn off breaking crests, each of one drop radius r, flying through the
// wind with drag until they fall back into the sea. Particles live in two buffers, one per
// slot: a frame reads the previous slot's live particles and appends the survivors and the
// newborn to its own, counting them with an atomic; the counts stay on the GPU (an indirect
// dispatch next frame, an indirect draw this frame). One shader, four kernels (MODE):
//   0 reset:    this slot's count to 0;
//   1 update:   one invocation per live particle of the previous slot (indirect dispatch):
//               dv/dt = g − k·(v − u_air), k = 3ρ_a·C_D·|v − u_air| / (8ρ_w·r) (Schiller &
//               Naumann's C_D), integrated exactly for k held over the step; u_air from the
//               logarithmic profile at the height above the water it flew over (the height
//               of the water under it is kept from step to step). A particle under the
//               surface lands (it adds residual foam where it falls) and one older than
//               SPRAY_MAX_AGE_S is dropped; the rest are appended;
//   2 emit:     one invocation per point of a SPRAY_EMIT_GRID² grid around the camera,
//               jittered each frame: where the surface's Jacobian says a crest is breaking
//               (the whitecaps' source, as foam.comp computes it) a puff is born with a
//               probability of rate · source · cell area · dt, at the displaced crest;
//   3 finalize: the count clamped to SPRAY_CAPACITY, written as the next frame's dispatch
//               arguments and this frame's draw arguments.
#include "common/ocean.glsl"
#include "shared.glsl"
layout(local_size_x = SPRAY_GROUP) in;
layout(constant_id = 0) const uint MODE = 0u;

layout(std430, set = 0, binding = 0) readonly buffer Fields { vec2 fields[]; };
#include "common/fields.glsl"

// src/ocean/simulation/spray_sim.rs `GpuSprayFrame`.
layout(std140, set = 0, binding = 1) uniform SprayFrame {
    vec4 base01;  // the emission grid's corner in cascade 0 and 1's lattices (texels)
    vec4 base23;  // cascades 2 and 3
    vec4 per_m;   // cascade c's lattice texels per metre (N / L_c)
    vec4 grid;    // xy: the grid's corner, world xz (m); z: its spacing (m)
    vec4 wind;    // xy: unit vector the wind blows toward; z: U10 (m/s); w: roughness z0 (m)
    vec4 step;    // y: J below which crests break; z: the source's gain; w: λ
    vec4 launch;  // x: downwind speed (m/s); y, z: upward speed range (m/s); w: landing foam
    vec4 drops;   // x, y: drop radius range (m); z: air density; w: air viscosity
    vec4 water;   // x: drop density (kg/m³); y: g (m/s²)
    vec4 levels[FOAM_MAX_LEVELS]; // foam level l: xy texel (0, 0)'s corner (world xz, m); z its
                                  // texel (m); w its side (texels)
} spray;
// What changes from step to step (the first frame's warm-up records several), and the counts
// the loops run over, as push constants: lavapipe specializes a shader on the values of uniforms
// that bound its loops, and would compile it again whenever the block changes.
layout(push_constant) uniform Counts {
    uint n;         // grid size N
    uint cascades;
    uint levels;    // foam levels
    uint step;      // steps recorded so far (the jitter's seed)
    float dt_s;
    float chance;   // the chance a fully breaking candidate emits this step
} sizes;

struct Particle {
    vec4 position_age;    // world position (m), age (s)
    vec4 velocity_radius; // velocity (m/s), drop radius (m)
    vec4 surface;         // x: the water's height under it at its last step (m)
};
layout(std430, set = 0, binding = 2) readonly buffer Previous { Particle previous[]; };
layout(std430, set = 0, binding = 3) writeonly buffer Current { Particle current[]; };
// [0..2] the update's dispatch arguments, [3] the live count, [4..7] the draw's arguments
// (VkDrawIndirectCommand), [8] puffs landed this frame, [9] puffs born this frame (those
// stored: none are when the buffer is full).
layout(std430, set = 0, binding = 4) readonly buffer PreviousCounts { uint previous_counts[16]; };
layout(std430, set = 0, binding = 5) buffer CurrentCounts { uint counts[16]; };
layout(set = 0, binding = 6, rgba16f) uniform image2DArray foam;

uint pcg(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// A uniform number in [0, 1), advancing the state.
float random(inout uint state) {
    state = pcg(state);
    return float(state >> 8u) / 16777216.0;
}

// Cascade c's lattice position (texels, ≥ 0) of world point xz.
vec2 lattice(uint c, vec2 xz) {
    vec2 base = c < 2u ? (c == 0u ? spray.base01.xy : spray.base01.zw)
                       : (c == 2u ? spray.base23.xy : spray.base23.zw);
    float n = float(sizes.n);
    return mod(base + (xz - spray.grid.xy) * spray.per_m[c], n);
}

// The surface's displacement (λDx, h, λDz) at rest position xz, every cascade summed.
vec3 displacement_at(vec2 xz) {
    vec3 d = vec3(0.0);
    for (uint c = 0u; c < sizes.cascades; ++c) {
        d += field_displacement_at(c, lattice(c, xz), sizes.n);
    }
    return vec3(spray.step.w * d.x, d.y, spray.step.w * d.z);
}

// The height of the drawn surface over world point xz and the rest position it comes from: one
// fixed-point step of r = xz − D(r), exact where the horizontal displacement D is uniform and
// off by about |∇D|·|D| where it is not (most at steep crests, where a puff may land a step
// early or late: small against a puff's size of a metre and more).
float surface_over(vec2 xz, out vec2 rest) {
    rest = xz - displacement_at(xz).xz;
    return displacement_at(rest).y;
}

// The whitecaps' source at rest position xz (foam.comp's, from the whole surface's Jacobian).
float breaking(vec2 xz) {
    vec3 d = vec3(0.0);
    for (uint c = 0u; c < sizes.cascades; ++c) {
        d += field_derivatives_at(c, lattice(c, xz), sizes.n);
    }
    float j = surface_jacobian(spray.step.w * d);
    return clamp((spray.step.y - j) * spray.step.z, 0.0, 1.0);
}

// Drag rate k (1/s) of a drop of radius r at relative speed `speed` (src/ocean/spray.rs
// `drag_rate`), in the form with the speed cancelled out: k = 3ρ_a·C_D·|v| / (8ρ_w·r) with
// C_D = 24/Re·(1 + 0.15·Re^0.687) is the Stokes rate 9μ/(2ρ_w·r²) times (1 + 0.15·Re^0.687),
// finite at any speed (no division by a vanishing Re).
float drag_rate(float r, float speed) {
    float rho_a = spray.drops.z, mu = spray.drops.w, rho_w = spray.water.x;
    float re = 2.0 * r * speed * rho_a / mu;
    return 9.0 * mu / (2.0 * rho_w * r * r) * (1.0 + 0.15 * pow(re, 0.687));
}

// The wind (m/s, along the wind) at height z above the water: the logarithmic profile through
// U10 at 10 m (src/ocean/spray.rs `wind_at`).
float wind_at(float z) {
    float z0 = spray.wind.w;
    return spray.wind.z * log(max(z, 10.0 * z0) / z0) / log(10.0 / z0);
}

// Residual foam where a puff falls: the finest foam level holding the rest position. Two puffs
// landing on one texel in one dispatch race (load, add, store): one of the two additions may be
// lost. That is harmless (a texel's foam is a look, and the sum is clamped to 1 anyway) and
// cheaper than an atomic on a float image, which Vulkan 1.3 does not require.
void land(vec2 rest) {
    for (uint l = 0u; l < sizes.levels; ++l) {
        vec4 level = spray.levels[l];
        ivec2 t = ivec2(floor((rest - level.xy) / level.z));
        if (all(greaterThanEqual(t, ivec2(0))) && all(lessThan(t, ivec2(level.w)))) {
            ivec3 at = ivec3(t, l);
            vec4 f = imageLoad(foam, at);
            f.y = min(f.y + spray.launch.w, 1.0);
            imageStore(foam, at, f);
            return;
        }
    }
}

// Appends p to this slot's particles; false when they are full (p is dropped).
bool append(Particle p) {
    uint at = atomicAdd(counts[3], 1u);
    if (at < SPRAY_CAPACITY) {
        current[at] = p;
        return true;
    }
    return false;
}

void update(uint i) {
    if (i >= previous_counts[3]) {
        return;
    }
    Particle p = previous[i];
    vec3 x = p.position_age.xyz;
    vec3 v = p.velocity_radius.xyz;
    float r = p.velocity_radius.w;
    float dt = sizes.dt_s;
    // The wind at its height over the water it flew over last step.
    float u = wind_at(x.y - p.surface.x);
    vec3 air = vec3(spray.wind.x * u, 0.0, spray.wind.y * u);
    vec3 rel = v - air;
    // dv_rel/dt = g − k·v_rel with k held: v_rel(t) = v_rel·e^(−kt) + (g/k)(1 − e^(−kt)).
    float k = drag_rate(r, length(rel));
    float e = exp(-k * dt);
    vec3 gk = vec3(0.0, -spray.water.y, 0.0) / k;
    x += air * dt + rel * (1.0 - e) / k + gk * (dt - (1.0 - e) / k);
    v = air + rel * e + gk * (1.0 - e);
    float age = p.position_age.w + dt;
    vec2 rest;
    float below = surface_over(x.xz, rest);
    if (x.y < below) {
        atomicAdd(counts[8], 1u);
        land(rest);
        return;
    }
    if (age > SPRAY_MAX_AGE_S) {
        return;
    }
    append(Particle(vec4(x, age), vec4(v, r), vec4(below, 0.0, 0.0, 0.0)));
}

void emit(uint id) {
    uint side = SPRAY_EMIT_GRID;
    if (id >= side * side) {
        return;
    }
    uvec2 cell = uvec2(id % side, id / side);
    // The cell's world index (the corner is a whole number of spacings) keys the randomness,
    // so a point of the sea draws the same numbers wherever the grid lies.
    ivec2 world_cell = ivec2(round(spray.grid.xy / spray.grid.z)) + ivec2(cell);
    uint state = pcg(uint(world_cell.x) * 0x9e3779b1u ^ pcg(uint(world_cell.y) ^ sizes.step));
    vec2 rest = spray.grid.xy + (vec2(cell) + vec2(random(state), random(state))) * spray.grid.z;
    float chance = sizes.chance * breaking(rest);
    if (random(state) >= chance) {
        return;
    }
    vec3 d = displacement_at(rest);
    vec3 x = vec3(rest.x + d.x, d.y + 0.05, rest.y + d.z);
    vec2 wind = spray.wind.xy;
    vec2 across = vec2(-wind.y, wind.x);
    vec2 side_speed = wind * spray.launch.x * (0.6 + 0.8 * random(state))
                      + across * (random(state) - 0.5);
    float up = mix(spray.launch.y, spray.launch.z, random(state));
    float r = exp(mix(log(spray.drops.x), log(spray.drops.y), random(state)));
    if (append(Particle(vec4(x, 0.0), vec4(side_speed.x, up, side_speed.y, r),
                        vec4(d.y, 0.0, 0.0, 0.0)))) {
        atomicAdd(counts[9], 1u);
    }
}

void main() {
    uint id = gl_GlobalInvocationID.x;
    if (MODE == 0u) {
        if (id == 0u) {
            counts[3] = 0u;
            counts[8] = 0u;
            counts[9] = 0u;
        }
    } else if (MODE == 1u) {
        update(id);
    } else if (MODE == 2u) {
        emit(id);
    } else if (id == 0u) {
        uint n = min(counts[3], SPRAY_CAPACITY);
        counts[0] = (n + SPRAY_GROUP - 1u) / SPRAY_GROUP;
        counts[1] = 1u;
        counts[2] = 1u;
        counts[3] = n;
        counts[4] = 6u;
        counts[5] = n;
        counts[6] = 0u;
        counts[7] = 0u;
    }
}
