#version 460
// Evolve the spectrum to time t and build the spectral fields the inverse FFT turns into the
// surface (Tessendorf 2001, eqs. 43-45; conventions in src/ocean/spectrum.rs and cpu.rs):
//   h(k,t) = h0(k) e^{iωt} + conj(h0(-k)) e^{-iωt}
//   Dx = i kx/k h, Dz = i kz/k h, ∂h/∂x = i kx h, ∂h/∂z = i kz h,
//   ∂Dx/∂x = -kx²/k h, ∂Dz/∂z = -kz²/k h, ∂Dx/∂z = -kx kz/k h,
// (the displacement's sign is the one that moves the water toward the crests: src/ocean/cpu.rs),
// packed two real fields per complex array: (Dx + i h), (Dz + i ∂h/∂x), (∂h/∂z + i ∂Dx/∂x),
// (∂Dz/∂z + i ∂Dx/∂z). Element [m][n] of cascade c has k = (2π(n - N/2), 2π(m - N/2)) / L_c.
// Time: ω is quantized to whole multiples m of ω0 = 2π/T (Tessendorf 2001 §3.2, T =
// REPEAT_PERIOD_S in src/ocean/spectrum.rs), and t arrives as t mod T in ticks of T/2^32, both
// computed on the CPU (m in f64 from the dispersion relation, ticks in f64 from the frame time).
// The phase ω'·t/2π mod 1 = m·ticks/2^32 mod 1 is then exact in a wrapping 32-bit multiply, at any
// simulation time: no f32 product ω·t that loses the phase after hours.
// Inputs: h0 (K, N, N), omega_steps (K, N, N). Output: spectra (K * 4, N, N), the FFT's data buffer.
#include "common/ocean.glsl"
layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, set = 0, binding = 0) readonly buffer H0 { vec2 h0[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Spectra { vec2 spectra[]; };
layout(std430, set = 0, binding = 2) readonly buffer OmegaSteps { uint omega_steps[]; };
layout(push_constant) uniform Params {
    vec4 patch_m;   // patch side of cascades 0..3 (m)
    uint ticks;     // t mod T in units of T / 2^32
    uint n;
} params;

void main() {
    uint n = params.n;
    uvec3 id = gl_GlobalInvocationID;
    if (id.x >= n || id.y >= n) {
        return;
    }
    uint c = id.z;
    uint base = c * n * n;
    float dk = 2.0 * PI / params.patch_m[c];
    vec2 k = (vec2(id.xy) - vec2(n / 2u)) * dk;
    float k_len = length(k);
    // Turns in [-1/2, 1/2): the wrapped product read as a signed 32-bit fraction.
    float turns = float(int(omega_steps[base + id.y * n + id.x] * params.ticks)) * (1.0 / 4294967296.0);
    float phase = 2.0 * PI * turns;
    vec2 e = vec2(cos(phase), sin(phase));
    vec2 a = h0[base + id.y * n + id.x];
    // -k sits at (N - n, N - m); the Nyquist row and column have no partner and hold zero.
    vec2 b = (id.x == 0u || id.y == 0u) ? vec2(0.0) : conj2(h0[base + (n - id.y) * n + (n - id.x)]);
    vec2 h = cmul(a, e) + cmul(b, conj2(e));

    vec2 u = k_len > 0.0 ? k / k_len : vec2(0.0);
    vec2 dx = times_i(u.x * h);
    vec2 dz = times_i(u.y * h);
    vec2 sx = times_i(k.x * h);
    vec2 sz = times_i(k.y * h);
    vec2 dxx = -u.x * k.x * h;
    vec2 dzz = -u.y * k.y * h;
    vec2 dxz = -u.x * k.y * h;

    uint plane = n * n;
    uint at = id.y * n + id.x;
    spectra[(c * 4u + 0u) * plane + at] = dx + times_i(h);
    spectra[(c * 4u + 1u) * plane + at] = dz + times_i(sx);
    spectra[(c * 4u + 2u) * plane + at] = sz + times_i(dxx);
    spectra[(c * 4u + 3u) * plane + at] = dzz + times_i(dxz);
}
