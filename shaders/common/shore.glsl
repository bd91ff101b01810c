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

// k·h of a wave of angular frequency ω over depth h: ω² = g k tanh(kh). Guo (2002)'s explicit
// approximation (within 0.75 %) and one Newton step (within 2·10⁻⁵).
float shore_kh(float omega, float h) {
    float k0h = omega * omega * h / SHORE_G;
    float x = sqrt(k0h);
    float y = k0h * pow(max(1.0 - exp(-pow(x, 2.4908)), 1e-30), -1.0 / 2.4908);
    float t = tanh(min(y, 10.0));
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
