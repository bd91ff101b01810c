// Waves that feel the bottom (the Rust twin, with the physics and its sources, is
// src/ocean/shore.rs; tests/shared.rs compares the two). The simulated sea (deep water, or the
// `--depth` of the spectrum) is scaled at each point of the water by what linear theory and
// depth-limited breaking make of it over the local depth:
//   shoaling K_s = sqrt(c_g(ω̄, h_sim) / c_g(ω̄, d)) at the sea's mean frequency ω̄ = m1/m0;
//   breaking: the local significant height min(K_s·Hs, BREAKER_INDEX·d).
// frame.shore: x the sea's Hs (m), y ω̄ (rad/s), z c_g(ω̄) at the depth the sea is simulated
// for (m/s, computed on the CPU); frame.open_sea.y: K_s over the open sea's flat floor.
// Branch-free (see ocean_displacement_at in common/water.glsl for why).
#include "shared.glsl" // BREAKER_INDEX (src/shared.rs)

const float SHORE_G = 9.81; // spectrum::G
const float SHORE_TAU = 6.28318530718;

// k·h of a wave of angular frequency ω over depth h: ω² = g k tanh(kh). Guo (2002)'s explicit
// approximation (within 0.75 %) and one Newton step (within 2·10⁻⁵).
float shore_kh(float omega, float h) {
    float k0h = omega * omega * h / SHORE_G;
    float x = sqrt(k0h);
    // 1 − e^(−a) and tanh by their series where f32 would cancel (under a millimetre of water).
    float a = pow(x, 2.4908);
    float y = k0h * pow(max(a < 1e-3 ? a * (1.0 - 0.5 * a) : 1.0 - exp(-a), 1e-30), -1.0 / 2.4908);
    float t = y < 0.01 ? y * (1.0 - y * y / 3.0) : tanh(min(y, 10.0));
    return y - (y * t - k0h) / (t + y * (1.0 - t * t));
}

// Group velocity c_g = n·ω/k, n = ½(1 + 2kh / sinh 2kh) (m/s).
float shore_group_speed(float omega, float h) {
    float y = max(shore_kh(omega, h), 1e-6);
    float z = min(2.0 * y, 20.0);
    float n = 0.5 * (1.0 + z / sinh(z));
    return n * omega * h / y;
}

// The shoaling coefficient where the water is `depth` metres deep (the waterline: 1 cm).
float shore_shoaling(float depth) {
    float omega = max(frame.shore.y, 1e-3);
    return sqrt(frame.shore.z / shore_group_speed(omega, max(depth, 0.01)));
}

// With the shoaling coefficient `ks`, where the water is `depth` metres deep (≤ 0: dry land):
// x the factor on the simulated displacement and slopes (local Hs / the sea's Hs), y how hard
// the waves break there (0 where they do not, 1 where the shoaled height is twice what the depth
// holds), z the local significant wave height (m). water.tese evaluates `ks` per vertex and
// this per vertex (displacement) and, from the depth and `ks` between the vertices, per pixel
// (slopes, surf: water.frag).
vec3 shore_waves_at(float ks, float depth) {
    float hs = max(frame.shore.x, 1e-3);
    float limit = BREAKER_INDEX * max(depth, 0.0);
    float local_hs = min(ks * hs, limit);
    float breaking = clamp(ks * hs / max(limit, 1e-3) - 1.0, 0.0, 1.0);
    return vec3(local_hs / hs, breaking, local_hs);
}

vec3 shore_waves(float depth) { return shore_waves_at(shore_shoaling(depth), depth); }

// ---------------------------------------------------------------------------------------------
// The surf: what the breaking looks like (the physics above says where and how hard). Once the
// shoaled height passes what the depth holds, the waves of the inner surf zone travel as bores
// (broken waves with a turbulent front, Svendsen 1984's picture of the inner surf zone): drawn
// here as one train of crests at the sea's mean period P = 2π/ω̄ running shoreward at the
// phase speed ω̄/k(d), then running up the beach as swash.
//
// frame.shore.w is the surf's clock: t/P mod SURF_WAVES waves (reduced on the CPU in f64). A
// bore is at a point when its phase θ = clock + T/P + offset is a whole number, T the time the
// crest still takes to reach the waterline (shore_travel_s) and `offset` (shore_offset) a
// smooth alongshore shift, so the crests meet the shore at varying angles and times; θ's
// whole part names the wave (its strength, shore_strength).

const uint SURF_WAVES = 256u;
const float SURF_FRONT = 0.15;  // share of a period the bore's face takes to pass (its rise)
const float SURF_ROLLER = 0.1;  // share of a period the roller (white water) rides behind the face
const float SURF_SHARE = 0.8;   // the bores' largest share of the sea (the rest: its own waves)
const float SURF_SLOPE_MIN = 0.01; // below this bed slope no bore is drawn (a flat shelf)

// The time (s) a crest of angular frequency ω takes from depth d to the waterline over a bed of
// slope m, at the phase speed c = ω/k: T = ∫ ds/c = (1/(m·ω))·∫₀^d k(h) dh. The integral by
// three-point Gauss–Legendre in u with h = d·u² (integrand 2·kh(d u²)/u, smooth: exact in
// shallow water, where k·√h is constant, and in deep water). In shallow water T → 2√d/(m√(g)).
float shore_travel_s(float omega, float depth, float slope) {
    float d = max(depth, 0.0);
    float s = 0.0;
    for (int i = 0; i < 3; ++i) {
        float u = 0.5 + 0.38729833 * float(i - 1); // nodes ½ ± ½√(3/5), ½
        float w = i == 1 ? 8.0 / 18.0 : 5.0 / 18.0;
        s += w * 2.0 * shore_kh(omega, max(d * u * u, 1e-6)) / u;
    }
    return d > 0.0 ? s / (max(slope, SURF_SLOPE_MIN) * omega) : 0.0;
}

// The 2 % run-up (m above the still water) after Stockdon et al. (2006), eq. 19: R₂ =
// 1.1·(0.35·β·√(H₀L₀) + ½·√(H₀L₀·(0.563·β² + 0.004))), set-up plus half the swash, with
// H₀ the deep-water significant height, L₀ = g·T²/2π at the sea's mean period (Stockdon fit
// it to the peak period, about 1.2 times longer for these spectra: a lower run-up) and β the
// beach slope.
float shore_runup_m(float hs, float omega, float slope) {
    float l0 = SHORE_TAU * SHORE_G / max(omega * omega, 1e-6);
    float hl = hs * l0;
    return 1.1 * (0.35 * slope * sqrt(hl) + 0.5 * sqrt(hl * (0.563 * slope * slope + 0.004)));
}

// A 32-bit integer hash (xor-shifts and odd multipliers) for the surf's noise.
uint shore_hash(uint x) {
    x ^= x >> 16u;
    x *= 0x7feb352du;
    x ^= x >> 15u;
    x *= 0x846ca68bu;
    x ^= x >> 16u;
    return x;
}

// A lattice cell's value (0–1) for `seed`.
float shore_hash01(ivec2 cell, uint seed) {
    return float(shore_hash(uint(cell.x) * 0x9e3779b9u ^ shore_hash(uint(cell.y) ^ seed)) >> 8u)
         / 16777215.0;
}

// Value noise (0–1) over world xz in cells of `cell_m`, a different pattern for each seed.
float shore_noise(vec2 xz, float cell_m, uint seed) {
    vec2 p = xz / cell_m;
    vec2 i = floor(p);
    vec2 f = p - i;
    f = f * f * (3.0 - 2.0 * f);
    ivec2 c = ivec2(i);
    return mix(mix(shore_hash01(c, seed), shore_hash01(c + ivec2(1, 0), seed), f.x),
               mix(shore_hash01(c + ivec2(0, 1), seed), shore_hash01(c + ivec2(1, 1), seed), f.x),
               f.y);
}

// The crests' alongshore shift (waves): ±0.3 of a period over 70 m cells.
float shore_offset(vec2 world_xz) { return 0.6 * (shore_noise(world_xz, 70.0, 0x5eedu) - 0.5); }

// How strong wave n is where it reaches `world_xz` (0.55–1): sets of larger waves, each bore
// stronger along some stretches of the shore than others (40 m cells).
float shore_strength(vec2 world_xz, float wave) {
    uint n = uint(int(wave)) % SURF_WAVES;
    return 0.55 + 0.45 * shore_noise(world_xz, 40.0, n * 0x2545f491u + 1u);
}

// The bore's height profile over a period (φ = fract(θ): 0 where the face has just passed,
// rising toward 1 as the next one nears): a sawtooth of mean 0 and crest-to-trough 1, falling
// behind the crest and rising over the face, the last `front` of the period (SURF_FRONT, or
// more where the lattice or the pixels could not hold so steep a face: shore_front). x the
// height, y its derivative in φ.
vec2 shore_bore(float phase, float front) {
    float f = fract(phase);
    float back = 1.0 - f / (1.0 - front);
    float t = clamp((f - (1.0 - front)) / front, 0.0, 1.0);
    float face = t * t * (3.0 - 2.0 * t);
    float on_face = step(1.0 - front, f);
    float h = mix(back, face, on_face) - 0.5;
    float dh = mix(-1.0 / (1.0 - front), 6.0 * t * (1.0 - t) / front, on_face);
    return vec2(h, dh);
}

// The face's share of a period where the water's triangles or pixels are `spacing_m` apart
// and the bores 1/|gradient| long: at least SURF_FRONT, and at least two spacings (a sharper
// face would alias into a saw-toothed crest), at most half the period.
float shore_front(vec2 gradient, float spacing_m) {
    return clamp(2.0 * spacing_m * length(gradient), SURF_FRONT, 0.5);
}

// The white water a bore carries (0–1) at phase θ, its face `front` of a period: on the face as
// it steepens, full on the roller behind it, thinning to half over the next 0.4 of the period
// and half from there to the next face (the bore's own foam: the inner surf zone stays white
// between bores; the foam field adds what each leaves behind and its lace: ocean/foam.comp).
float shore_roller(float phase, float front) {
    float f = fract(phase);
    float face = smoothstep(1.0 - front, 1.0 - 0.3 * front, f);
    float behind = mix(1.0, 0.5, smoothstep(SURF_ROLLER, SURF_ROLLER + 0.4, f));
    return max(face, behind);
}

// Crest-to-trough height of a bore over the local significant height: a sawtooth H high has
// a standard deviation of H/√12, so its Hs = 4σ = 1.155·H, and H = (√3/2)·Hs.
const float SURF_BORE = 0.8660254;

// The gradient of the water's depth at `world_xz` (central differences of terrain_height over
// 1 m): it points toward deeper water.
vec2 shore_depth_gradient(vec2 world_xz) {
    vec2 e = vec2(0.5, 0.0);
    return vec2(terrain_height(world_xz - e.xy) - terrain_height(world_xz + e.xy),
                terrain_height(world_xz - e.yx) - terrain_height(world_xz + e.yx));
}

// The bores at a point of the water `depth` deep where the waves break `breaking` hard
// (shore_waves_at's y), the surf's clock at `clock` (frame.shore.w; foam.comp passes each
// step's own). x their phase θ (waves); y their share of the sea there (0–SURF_SHARE: none
// where the waves do not break, nor where the bed is flat, as the storm's shelf is: crests
// along its depth contours would wander with the ridges); zw θ's gradient (waves per metre:
// ∇θ = ∇T/P = k·∇d/(2π·m) for the bed's slope m held, so |∇θ| = 1/L, the local wavelength's
// inverse; the alongshore offset's gradient is left out).
vec4 shore_surf(vec2 world_xz, float depth, float breaking, float clock) {
    vec2 grad = shore_depth_gradient(world_xz);
    float slope = length(grad);
    float omega = max(frame.shore.y, 1e-3);
    float theta = clock + shore_travel_s(omega, depth, slope) * omega / SHORE_TAU
                  + shore_offset(world_xz);
    float weight = SURF_SHARE * smoothstep(0.0, 0.5, breaking)
                   * smoothstep(SURF_SLOPE_MIN, 3.0 * SURF_SLOPE_MIN, slope);
    float d = max(depth, 0.01);
    vec2 dtheta = shore_kh(omega, d) / d / (SHORE_TAU * max(slope, SURF_SLOPE_MIN)) * grad;
    return vec4(theta, weight, dtheta);
}

// The swash at a point of the beach whose slope is `slope`: each bore reaches the waterline
// when θ (T = 0 there) passes a whole number and runs up and back as a ballistic sheet (Shen &
// Meyer 1963: the edge rises as u₀·sin β·τ − ½·g·sin²β·τ² after τ seconds, the height reached
// u₀²/2g), wave n reaching R₂·shore_strength (so the set's largest waves reach Stockdon's R₂).
// A sheet can run longer than a period (the storm): the last four waves' sheets, the highest
// wins. x the height of the water's edge above the still water (m); y the highest any of them
// has reached (m); z 1 while the edge rises (uprush), 0 while it falls (backwash).
vec3 shore_swash(vec2 world_xz, float slope) {
    float omega = max(frame.shore.y, 1e-3);
    float period = SHORE_TAU / omega;
    float theta = frame.shore.w + shore_offset(world_xz);
    float runup = shore_runup_m(frame.shore.x, omega, slope);
    float sin_b = slope / sqrt(1.0 + slope * slope);
    float a = SHORE_G * sin_b * sin_b;
    vec3 swash = vec3(0.0);
    for (int k = 0; k < 4; ++k) {
        float wave = floor(theta) - float(k);
        float tau = (theta - wave) * period;
        float r = runup * shore_strength(world_xz, wave);
        float v = sqrt(2.0 * SHORE_G * r) * sin_b; // the edge's vertical speed at the start
        float z = v * tau - 0.5 * a * tau * tau;
        float rising = step(a * tau, v);
        swash.y = max(swash.y, mix(r, z, rising));
        if (z > swash.x) {
            swash.xz = vec2(z, rising);
        }
    }
    return swash;
}
