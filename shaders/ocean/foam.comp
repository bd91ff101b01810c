#version 460
// The foam near the camera (src/ocean/simulation/foam_sim.rs): a clipmap of world-space levels, each
// SIZE² texels of side h (0.25 m for the finest, ×4 a level), at rest positions like the waves'
// images, so the foam rides the choppy displacement with the water it lies on. Per texel
// (foam = (A, S): A the whitecaps' foam, S the residual foam they leave):
//   1. the surface's Jacobian J_s from every cascade's derivatives at the texel's rest position
//      (bilinear in each cascade's lattice, from the image assemble.comp writes), and the whitecap source
//      clamp((threshold − J_s)·gain, 0, 1), as assemble.comp computes it on the lattice; and
//      the foam the sea makes where it meets land and things: the rollers of the surf's
//      bores where the shore's breaking criterion holds (common/shore.glsl), and a band
//      around each object standing in the water (the buoy, the pillars) where the waves wash
//      against it;
//   2. semi-Lagrangian advection: the previous frame's foam read where the water at the texel
//      was dt ago, x − u·dt (this level's previous placement, else the next coarser level's,
//      else none), with u = drift·ŵ + v_c·ŵ⊥: the surface drift downwind, and the lateral
//      flow of Langmuir circulation toward windrows (lines along the wind);
//   3. A = max(A'·e^(−dt/τ_A), source), the whitecaps' memory as on the lattice;
//      S = max(S'·e^(−dt/τ_S)·e^(−dt·∂v_c/∂c), residual·A): the residual foam lives longer and
//      is conserved by the flow, so it gathers where the flow converges (∂v_c/∂c < 0).
#include "common/ocean.glsl"
#include "shared.glsl"
layout(local_size_x = 8, local_size_y = 8) in;

// Per cascade (layer): (∂Dx/∂x, ∂Dz/∂z, ∂Dx/∂z, 0) before choppiness, sign-corrected
// (assemble.comp).
layout(set = 0, binding = 0, rgba32f) uniform readonly image2DArray derivatives;

// Where a level lies (src/ocean/simulation/foam_sim.rs `GpuLevel`); texel i's centre is at
// origin + (i + ½)·h.
struct Level {
    vec4 base01;   // cascades 0 and 1: texel (0, 0)'s centre in the cascade's lattice (texels)
    vec4 base23;   // cascades 2 and 3
    vec4 steps;    // cascade c's lattice texels per level texel (h·N/L_c)
    vec4 previous; // texel (0, 0)'s centre in the previous frame's texels of this level (xy)
                   // and of the next coarser level (zw)
    vec4 place;    // xy: texel (0, 0)'s centre along and across the wind (m, mod the windrows'
                   // period); z: h (m); w: h over the next coarser level's h
    vec4 anchor;   // xy: texel (0, 0)'s centre in world xz (m)
};
// The levels, and the scene's fields of the frame uniforms (as shaders/common/frame.glsl has
// them) that common/terrain.glsl and common/shore.glsl read.
layout(std140, set = 0, binding = 1) uniform Levels {
    Level levels[FOAM_MAX_LEVELS];
    vec4 terrain;    // island x, z, shelf depth, island radius
    vec4 shore;      // the sea's Hs, mean ω, c_g at the simulated depth
    vec4 open_sea;   // the open sea's floor depth, K_s there
    vec4 objects[4]; // (x, z, radius, top height) of the objects in the water; 0 height = none
} frame;
#include "common/terrain.glsl"
#include "common/shore.glsl"
layout(set = 0, binding = 2, rgba16f) uniform writeonly image2DArray foam;
layout(set = 0, binding = 3, rgba16f) uniform readonly image2DArray previous;
layout(push_constant) uniform Params {
    vec2 wind;             // unit vector the wind blows toward (x, z)
    float drift_m_s;       // surface drift downwind (m/s)
    float converge_m_s;    // the windrows' greatest lateral flow (m/s)
    float windrow_m;       // the windrows' mean spacing (m)
    float dt_s;
    float threshold;       // J_s below which whitecaps form (src/ocean/foam.rs)
    float gain;
    float decay_s;         // τ_A
    float residual_decay_s; // τ_S
    float residual;        // share of a whitecap's foam left behind as residual foam
    float spread_m2_s;     // turbulent diffusivity (m²/s)
    float choppiness;
    uint n;
    uint cascades;
    uint size;
    uint levels;
    float jet_m_s;         // the windrows' downwind jet (m/s): their surface flow's excess
    uint step;             // steps recorded so far (which diagonal the spreading takes)
    float surf_clock;      // the surf's clock at this step's time (frame.shore.w's, waves)
} params;

// Level `l`'s previous foam at texel position q (texel centres at whole numbers), bilinear;
// `inside` is 0 where q is not within the level.
vec2 previous_at(uint l, vec2 q, out float inside) {
    float last = float(params.size) - 1.0;
    inside = float(all(greaterThanEqual(q, vec2(0.0))) && all(lessThanEqual(q, vec2(last))));
    q = clamp(q, vec2(0.0), vec2(last));
    ivec2 a = ivec2(floor(q));
    ivec2 b = min(a + 1, ivec2(params.size - 1u));
    vec2 f = q - vec2(a);
    vec2 s00 = imageLoad(previous, ivec3(a, l)).xy;
    vec2 s10 = imageLoad(previous, ivec3(b.x, a.y, l)).xy;
    vec2 s01 = imageLoad(previous, ivec3(a.x, b.y, l)).xy;
    vec2 s11 = imageLoad(previous, ivec3(b, l)).xy;
    return mix(mix(s00, s10, f.x), mix(s01, s11, f.x), f.y);
}

// Cascade c's derivatives at a fractional texel position p (periodic bilinear; p ≥ 0; n a
// power of two): the same values as `field_derivatives_at` on the FFT output.
vec3 derivatives_at(uint c, vec2 p, uint n) {
    vec2 f = fract(p);
    uint wrap = n - 1u;
    ivec2 a = ivec2(uvec2(floor(p)) & wrap);
    ivec2 b = ivec2((uvec2(a) + 1u) & wrap);
    int layer = int(c);
    vec3 d00 = imageLoad(derivatives, ivec3(a, layer)).xyz;
    vec3 d10 = imageLoad(derivatives, ivec3(b.x, a.y, layer)).xyz;
    vec3 d01 = imageLoad(derivatives, ivec3(a.x, b.y, layer)).xyz;
    vec3 d11 = imageLoad(derivatives, ivec3(b, layer)).xyz;
    return mix(mix(d00, d10, f.x), mix(d01, d11, f.x), f.y);
}

// A hash of a lattice point (0–1).
float hash(uvec2 p) {
    uint h = p.x * 0x8da6b343u ^ p.y * 0xd8163841u;
    h ^= h >> 15u;
    h *= 0x2c1b3c6du;
    h ^= h >> 12u;
    return float(h & 0xffffu) / 65535.0;
}

// Value noise (0–1) with cells of one unit, periodic over `period` cells, and its derivative.
vec3 noise(vec2 p, uvec2 period) {
    vec2 i = floor(p);
    vec2 f = p - i;
    ivec2 p_i = ivec2(period);
    uvec2 a = uvec2((ivec2(i) % p_i + p_i) % p_i); // i may be negative
    uvec2 b = (a + 1u) % period;
    vec2 u = f * f * (3.0 - 2.0 * f);
    vec2 du = 6.0 * f * (1.0 - f);
    float v00 = hash(a), v10 = hash(uvec2(b.x, a.y)), v01 = hash(uvec2(a.x, b.y)), v11 = hash(b);
    float value = mix(mix(v00, v10, u.x), mix(v01, v11, u.x), u.y);
    vec2 d = du * vec2(mix(v10 - v00, v11 - v01, u.y), mix(v01 - v00, v11 - v10, u.x));
    return vec3(value, d);
}

// The windrows' flow at (along, across) = (s, c): x the lateral flow v_c (m/s, across the
// wind), y the downwind jet u_j (m/s, on top of the drift), z the flow's divergence
// ∂v_c/∂c + ∂u_j/∂s (1/s). v_c = −V·g·sin 2πφ with φ = c/λ + 1.2·(ψ − ½), so the flow
// converges on the lines φ ∈ ℤ, about λ apart. ψ (value noise in cells 4λ long and 2λ wide)
// lets the lines wander (up to ±0.6 of a spacing) and join; φ keeps rising across the wind
// (∂φ/∂c ≥ (1 − 0.6·1.5)/λ > 0: the noise's slope is at most 1.5 a cell), so no line folds
// back. g = ½ + ψ (0.5–1.5) makes some lines strong and others faint along their length.
// u_j = J·g·cos 2πφ: the water runs faster downwind along the lines than between them, so
// the shear draws whatever floats out along the wind as the lines gather it.
vec3 windrow_flow(vec2 sc) {
    float l = params.windrow_m;
    vec3 psi = noise(sc / vec2(4.0 * l, 2.0 * l), uvec2(FOAM_WINDROW_PERIOD / 4u,
                                                         FOAM_WINDROW_PERIOD / 2u));
    float phi = sc.y / l + 1.2 * (psi.x - 0.5);
    float psi_s = psi.y / (4.0 * l); // ∂ψ/∂s
    float psi_c = psi.z / (2.0 * l); // ∂ψ/∂c
    float phi_c = 1.0 / l + 1.2 * psi_c;
    float g = 0.5 + psi.x;
    float v = params.converge_m_s;
    float j = params.jet_m_s;
    float s = sin(2.0 * PI * phi);
    float c = cos(2.0 * PI * phi);
    float lateral_c = -v * (psi_c * s + g * 2.0 * PI * c * phi_c);
    float jet_s = j * psi_s * (c - g * 2.0 * PI * s * 1.2);
    return vec3(-v * g * s, j * g * c, lateral_c + jet_s);
}

void main() {
    uvec3 id = gl_GlobalInvocationID;
    if (id.x >= params.size || id.y >= params.size) {
        return;
    }
    uint l = id.z;
    Level level = frame.levels[l];
    vec2 i = vec2(id.xy);
    float h = level.place.z;

    // 1. The whitecap source at the rest position.
    vec3 d = vec3(0.0);
    for (uint c = 0u; c < params.cascades; ++c) {
        vec2 base = (c & 1u) == 0u ? (c < 2u ? level.base01.xy : level.base23.xy)
                                   : (c < 2u ? level.base01.zw : level.base23.zw);
        d += derivatives_at(c, base + i * level.steps[c], params.n);
    }
    float source = clamp((params.threshold - surface_jacobian(params.choppiness * d)) * params.gain,
                         0.0, 1.0);
    vec2 world = level.anchor.xy + i * h;
    // The surf, where the waves break over the island's slope (branches: almost every
    // workgroup skips them): the bores' rollers (common/shore.glsl), at full strength while
    // the roller passes (its first SURF_ROLLER of a period) and, when a step is longer than
    // that (the warm-up's), as much as the field's decay leaves of what the face laid down
    // within the step: each bore leaves a band of foam behind it that thins with age, not a
    // band wherever the step happened to land.
    float depth = 0.0;
    float breaking = 0.0;
    if (near_island(world)) {
        depth = -terrain_height(world);
        breaking = shore_waves(depth).y;
    }
    if (breaking > 0.0) {
        vec4 surf = shore_surf(world, depth, breaking, params.surf_clock);
        float period = SHORE_TAU / max(frame.shore.y, 1e-3);
        float age = fract(surf.x) * period; // since the face passed (s)
        float roller = SURF_ROLLER * period;
        float fresh = step(age, max(params.dt_s, roller))
                      * exp(-max(age - roller, 0.0) / params.decay_s);
        source = max(source, surf.y / SURF_SHARE * fresh * shore_strength(world, floor(surf.x)));
    }
    // Contact: a band FOAM_CONTACT_M wide around each object, as strong as the sea is high
    // (full from FOAM_CONTACT_HS_M of significant height).
    float contact = 0.0;
    for (int o = 0; o < 4; ++o) {
        vec4 object = frame.objects[o];
        float gap = length(world - object.xy) - object.z;
        contact = max(contact, step(0.001, object.w) * (1.0 - smoothstep(0.0, FOAM_CONTACT_M, gap)));
    }
    source = max(source, contact * clamp(frame.shore.x / FOAM_CONTACT_HS_M, 0.0, 1.0));

    // 2. Where the water was dt ago: drift downwind, the windrows' flow across it.
    vec2 wind = params.wind;
    vec2 across = vec2(-wind.y, wind.x);
    vec2 sc = level.place.xy + vec2(dot(i * h, wind), dot(i * h, across));
    vec3 flow = windrow_flow(sc);
    vec2 u = (params.drift_m_s + flow.y) * wind + flow.x * across;
    vec2 back = i - u * params.dt_s / h; // in this level's texels
    // Turbulent spreading (diffusivity K, the same every way): the mean of the two points a
    // random walk reaches along one diagonal of the wind, the other diagonal the next step.
    // Over two steps the variance is 4K·dt along both diagonals, so 2K·dt a step along and
    // across the wind: the windrows stay a metre or so wide where the flow gathers them (width
    // √(K/k) for a convergence rate k), and a whitecap's crest-long patch is not drawn out
    // across the wind more than along it. At most a texel either way: two taps further apart
    // would leave two copies rather than a blur (the warm-up's 5 s steps spread less than K
    // asks).
    vec2 diagonal = (wind + ((params.step & 1u) == 0u ? across : -across)) * sqrt(0.5);
    vec2 spread = diagonal * min(sqrt(4.0 * params.spread_m2_s * params.dt_s) / h, 1.0);
    float inside, inside2;
    vec2 here = 0.5 * (previous_at(l, level.previous.xy + back + spread, inside)
                       + previous_at(l, level.previous.xy + back - spread, inside2));
    // The next coarser level for water that just came into this one (the camera moved); a
    // branch, as almost every texel skips it.
    vec2 before = here;
    if (inside * inside2 < 0.5) {
        before = vec2(0.0);
        if (l + 1u < params.levels) {
            vec2 q = level.previous.zw + back * level.place.w;
            vec2 d = spread * level.place.w;
            before = 0.5 * (previous_at(l + 1u, q + d, inside) + previous_at(l + 1u, q - d, inside2))
                     * inside * inside2;
        }
    }

    // 3. Decay, the source, and the residual foam the flow gathers.
    float a = max(before.x * exp(-params.dt_s / params.decay_s), source);
    float s = before.y * exp(-params.dt_s / params.residual_decay_s) * exp(-params.dt_s * flow.z);
    s = clamp(max(s, params.residual * a), 0.0, 1.0);
    imageStore(foam, ivec3(id), vec4(a, s, 0.0, 0.0));
}
