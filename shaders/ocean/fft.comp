#version 460
// Stockham radix-2 autosort FFT of the rows of a batch of N x N complex arrays, in shared memory,
// one workgroup per row; the result is written transposed. Running it twice (A -> B, B -> A)
// therefore transforms rows, then columns, and leaves the 2D transform in A in its original
// orientation — both passes read contiguous rows.
//
// Stage with half-span Ns = 1, 2, ..., N/2 (Govindaraju et al. 2008, "High Performance Discrete
// Fourier Transforms on Graphics Processors", Stockham formulation): for j < N/2, k = j mod Ns,
//   a = x[j], b = x[j + N/2] * W^(k N / (2 Ns)),  y[2j - k] = a + b,  y[2j - k + Ns] = a - b,
// with W = e^{±2πi/N}. Unnormalized. Mirrors `stockham_model` in src/ocean/fft.rs.
//
// Inputs: src (batch, N, N) vec2, twiddles e^{+2πi j/N} for j < N/2 (computed once, in f64).
// Output: dst (batch, N, N) vec2, transposed. Push constant: +1 inverse, -1 forward.
layout(constant_id = 0) const uint LOG2_N = 8;
// Invocations per workgroup (each does N/2/THREADS butterflies per stage): N/2 on GPUs; small on
// CPU drivers, where every workgroup barrier is a costly switch between SIMD groups.
layout(constant_id = 1) const uint THREADS = 128;
layout(local_size_x_id = 1) in;

layout(std430, set = 0, binding = 0) readonly buffer Src { vec2 src[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Dst { vec2 dst[]; };
layout(std430, set = 0, binding = 2) readonly buffer Twiddles { vec2 twiddle[]; };
layout(push_constant) uniform Params { float direction; } params;

const uint N = 1u << LOG2_N;
const uint HALF = N >> 1;
shared vec2 ping[N];
shared vec2 pong[N];

vec2 cmul(vec2 a, vec2 b) { return vec2(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }

// One stage from `from` to `to`; a macro, so both shared arrays stay statically indexed.
#define STAGE(from, to)                                                    \
    for (uint j = t; j < HALF; j += THREADS) {                             \
        uint k = j & (ns - 1u);                                            \
        vec2 w = twiddle[k << (LOG2_N - 1u - log_ns)];                     \
        w.y *= params.direction;                                           \
        vec2 a = from[j];                                                  \
        vec2 b = cmul(from[j + HALF], w);                                  \
        uint o = (j << 1) - k;                                             \
        to[o] = a + b;                                                     \
        to[o + ns] = a - b;                                                \
    }

void main() {
    uint row = gl_WorkGroupID.x;
    uint batch = gl_WorkGroupID.y;
    uint t = gl_LocalInvocationID.x;
    uint base = (batch * N + row) * N;
    for (uint i = t; i < N; i += THREADS) {
        ping[i] = src[base + i];
    }
    barrier();
    for (uint log_ns = 0u; log_ns < LOG2_N; ++log_ns) {
        uint ns = 1u << log_ns;
        if ((log_ns & 1u) == 0u) {
            STAGE(ping, pong)
        } else {
            STAGE(pong, ping)
        }
        barrier();
    }
    // After LOG2_N stages the result is in pong when LOG2_N is odd, else in ping.
    uint out_base = batch * N * N + row;
    for (uint i = t; i < N; i += THREADS) {
        dst[out_base + i * N] = (LOG2_N & 1u) == 1u ? pong[i] : ping[i];
    }
}
