#version 460
#extension GL_EXT_control_flow_attributes : require
// Stockham autosort FFT of the rows of a batch of N x N complex arrays, one workgroup per row;
// the row is written transposed, so running the shader twice (A -> B, B -> A) transforms rows,
// then columns, and leaves the 2D transform in A in its original orientation, with both passes
// reading contiguous rows.
//
// The kernel for GPUs (fft_rows.comp is the one for CPU drivers). Radix-2 Stockham stages fused
// in registers (common/fft.glsl): each thread loads R = 8 or 16 values, applies the inter-pass
// twiddles and runs log2(R) radix-2 stages on them, so shared memory is touched once per pass
// (2 passes for N <= 256, 3 for N <= 1024) instead of once per stage, and global memory only on
// the first load and the last store. Unnormalized.
//
// Inputs: src (batch, N, N) vec2; twiddles e^{+2πi m/N}, m < N (computed once, in f64).
// Output: dst (batch, N, N) vec2, transposed. Push constant: +1 inverse, -1 forward.
layout(constant_id = 0) const uint LOG2_N = 8;
// Invocations per workgroup; each handles N/R/THREADS groups of R values per pass.
layout(constant_id = 1) const uint THREADS = 16;
layout(local_size_x_id = 1) in;

layout(std430, set = 0, binding = 0) readonly buffer Src { vec2 src[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Dst { vec2 dst[]; };
layout(std430, set = 0, binding = 2) readonly buffer Twiddles { vec2 twiddle[]; };
layout(push_constant) uniform Params { float direction; } params;

#include "common/fft.glsl"

const uint N = 1u << LOG2_N;
shared vec2 buf[2][N];

// One pass with R = 2^LOG_R values per group. `in_slot`/`out_slot` pick the shared buffers;
// the first pass reads src, the last writes dst (transposed). A macro keeps the register arrays
// sized by a constant and every index constant after unrolling. The `first`/`last` branches
// stand outside the unrolled loads and stores, never inside them: with a branch in each of the
// R unrolled iterations SwiftShader's compiler grew to 16.9 GB creating this pipeline (issue
// 32); hoisted, it takes 0.09 s and lavapipe's output is bit-identical.
#define PASS(LOG_R)                                                                          \
    {                                                                                        \
        const uint R = 1u << LOG_R;                                                          \
        for (uint j = t; j < N / R; j += THREADS) {                                          \
            uint k = j & (ns - 1u);                                                          \
            vec2 v[R];                                                                       \
            if (first) {                                                                     \
                [[unroll]] for (uint q = 0u; q < R; ++q) {                                   \
                    v[q] = conj_if_forward(src[row_base + j + q * (N / R)]);                 \
                }                                                                            \
            } else {                                                                         \
                [[unroll]] for (uint q = 0u; q < R; ++q) {                                   \
                    v[q] = buf[in_slot][j + q * (N / R)];                                    \
                }                                                                            \
            }                                                                                \
            if (ns > 1u) {                                                                   \
                vec2 w1 = twiddle[k * (N / (ns * R))];                                       \
                vec2 w = w1;                                                                 \
                [[unroll]] for (uint q = 1u; q < R; ++q) {                                   \
                    v[q] = cmul(v[q], w);                                                    \
                    w = cmul(w, w1);                                                         \
                }                                                                            \
            }                                                                                \
            DFT_IN_REGISTERS(v, LOG_R)                                                       \
            uint o = (j - k) * R + k;                                                        \
            if (last) {                                                                      \
                [[unroll]] for (uint q = 0u; q < R; ++q) {                                   \
                    dst[out_base + (o + q * ns) * N] = conj_if_forward(v[q]);                \
                }                                                                            \
            } else {                                                                         \
                [[unroll]] for (uint q = 0u; q < R; ++q) {                                   \
                    buf[out_slot][o + q * ns] = v[q];                                        \
                }                                                                            \
            }                                                                                \
        }                                                                                    \
        ns *= R;                                                                             \
    }

void main() {
    uint row = gl_WorkGroupID.x;
    uint batch = gl_WorkGroupID.y;
    uint t = gl_LocalInvocationID.x;
    uint row_base = (batch * N + row) * N;
    uint out_base = batch * N * N + row;

    // pass_schedule: ceil(LOG2_N / 4) passes of 3 or 4 fused stages, the larger first.
    const uint PASSES = (LOG2_N + 3u) / 4u;
    const uint BASE_R = LOG2_N / PASSES;
    const uint EXTRA = LOG2_N % PASSES;
    uint ns = 1u;
    for (uint p = 0u; p < PASSES; ++p) {
        bool first = p == 0u;
        bool last = p + 1u == PASSES;
        uint in_slot = (p + 1u) & 1u;
        uint out_slot = p & 1u;
        if (BASE_R + (p < EXTRA ? 1u : 0u) == 4u) {
            PASS(4u)
        } else {
            PASS(3u)
        }
        if (!last) {
            barrier();
        }
    }
}
