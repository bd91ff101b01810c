#version 460
// The wake's exact step in Fourier space (eWave, Tessendorf 2014; src/ocean/wake.rs): the state
// z = h + iφ after a forward FFT holds Z = H + iΦ, and each mode turns by ωΔt:
//   H' = cos(ωΔt) H + (ω/g) sin(ωΔt) Φ,   Φ' = −(g/ω) sin(ωΔt) H + cos(ωΔt) Φ,
// ω = √(g k tanh k d). H(k) = (Z(k) + Z̄(−k))/2 and Φ(k) = (Z(k) − Z̄(−k))/(2i), and as h and φ
// are real H(−k) = H̄(k), Φ(−k) = Φ̄(k): one invocation writes k and −k (the lower index of
// the pair), so the pass runs in place. The grid's move by `shift` texels (z'(n) = z(n + s))
// is the phase e^{2πi k·s/N} on Z(k). `scale` (1/N²) normalizes the inverse FFT that follows.
// Element [j][i] has k = dk (i', j'), i' = i below N/2 and i − N above.
#include "common/ocean.glsl"
layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, set = 0, binding = 0) buffer State { vec2 z[]; };
layout(push_constant) uniform Params {
    ivec2 shift;   // texels the grid moved since the last step
    float dt;      // step (s)
    float dk;      // 2π / the grid's side (rad/m)
    float depth;   // water depth (m); 0: deep water
    float scale;   // 1 / N²
    uint n;
} params;

const float G = 9.81;

int signed_index(uint i, uint n) { return i < n / 2u ? int(i) : int(i) - int(n); }

void main() {
    uint n = params.n;
    uvec2 id = gl_GlobalInvocationID.xy;
    if (id.x >= n || id.y >= n) {
        return;
    }
    uvec2 m = (uvec2(n) - id) & uvec2(n - 1u);
    uint a = id.y * n + id.x;
    uint b = m.y * n + m.x;
    if (b < a) {
        return;
    }
    ivec2 ks = ivec2(signed_index(id.x, n), signed_index(id.y, n));
    float k = params.dk * length(vec2(ks));
    float kd = params.depth > 0.0 ? tanh(min(k * params.depth, 20.0)) : 1.0;
    float w = sqrt(G * k * kd);
    // (cos, sin) normalized, and the shift's phase too: Vulkan lets sin and cos be off by 2^-11,
    // and a rotation whose cos² + sin² is not 1 damps or grows every mode at every step. On
    // SwiftShader the wake's RMS came out 1.7 % low after the first frame's 400 steps, 2.6 %
    // off lavapipe's; normalized, 0.2 % (tools/swiftshader compares the dumps).
    vec2 cs = normalize(vec2(cos(w * params.dt), sin(w * params.dt)));
    float c = cs.x;
    float s = cs.y;
    float to_h = w > 0.0 ? w / G * s : 0.0;
    float to_phi = w > 0.0 ? G / w * s : G * params.dt;
    // Turns of the shift's phase, exact in integers (N is a power of two: & is mod N).
    int turns = (ks.x * params.shift.x + ks.y * params.shift.y) & int(n - 1u);
    float phase = 2.0 * PI * float(turns) / float(n);
    vec2 e = normalize(vec2(cos(phase), sin(phase)));
    vec2 zk = cmul(z[a], e);
    vec2 zm = cmul(z[b], conj2(e));
    vec2 hk = 0.5 * (zk + conj2(zm));
    // (zk − conj(zm)) / (2i) = −i (zk − conj(zm)) / 2
    vec2 pk = -times_i(0.5 * (zk - conj2(zm)));
    vec2 h2 = c * hk + to_h * pk;
    vec2 p2 = c * pk - to_phi * hk;
    z[a] = params.scale * (h2 + times_i(p2));
    if (b != a) {
        z[b] = params.scale * (conj2(h2) + times_i(conj2(p2)));
    }
}
