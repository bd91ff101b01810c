// Shared by the ocean compute shaders: complex helpers and the dispersion relation
// (src/ocean/spectrum.rs `dispersion`, same clamping).
const float PI = 3.14159265358979;
const float G = 9.81;
const float MAX_KH = 20.0; // tanh(20) == 1 in float; keeps cosh/tanh finite on every driver

vec2 cmul(vec2 a, vec2 b) { return vec2(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }
vec2 conj2(vec2 a) { return vec2(a.x, -a.y); }
vec2 times_i(vec2 a) { return vec2(-a.y, a.x); }

// ω(k) = sqrt(g k tanh(k h)); depth <= 0 means deep water, ω = sqrt(g k).
float dispersion(float k, float depth_m) {
    k = max(k, 0.0);
    if (depth_m <= 0.0) {
        return sqrt(G * k);
    }
    float kh = min(k * max(depth_m, 1e-3), MAX_KH);
    return sqrt(max(G * k * tanh(kh), 0.0));
}
