#version 460
#extension GL_EXT_control_flow_attributes : require
#extension GL_KHR_shader_subgroup_shuffle : require
#extension GL_ARB_gpu_shader_int64 : require
// FFT of the columns of a batch of N x N complex arrays for CPU drivers (lavapipe), each column
// written out as a row: dst[b][c][k] = Σ_i src[b][i][c] w^{ik}. Two dispatches make the 2D
// transform in the original orientation (the second transposes the first's transpose back).
//
// On a CPU driver each SIMD lane is one invocation; arithmetic runs 8 lanes wide and a texel
// fetch is a branch-free gather, but a store to a storage buffer is a loop over the lanes with a
// branch per lane and per component (llvmpipe 22.3), so the kernel is shaped around its stores:
// - a lane writes its result as a contiguous row, four complex values (32 bytes) per store as
//   64-bit components: four scalar writes per lane where vec2 stores take eight;
// - the strided side of the transpose is on the loads: a lane fetches two neighbouring columns,
//   one RGBA32F texel per row holding both, and transforms them one after the other;
// - the whole column lives in registers: passes exchange values by renaming registers, never
//   through memory; no shared memory and no barrier;
// - every root of unity is a constant: the butterflies run the inverse transform (a forward one
//   conjugates on load and store) and the passes are written out, not looped, so after
//   specialization every twiddle folds to a constant or to adds and sign flips
//   (common/fft.glsl `rotate`). A pass loop carrying the stride in a variable kept them
//   runtime values and took about 25 % longer.
//
// A column of N values lives in the registers of T invocations (T = 1 up to N = 256, 2 for
// N = 512, 4 for N = 1024), M = N/T values each. T > 1 is one step of a four-step FFT (Bailey
// 1990, "FFTs in external or hierarchical memory"): lane t transforms x[t + T i], i < M, in
// registers (Y_t), and the T lanes finish with a T-point DFT over t through subgroup shuffles:
//   X[k1 + M k2] = Σ_t w_T^{t k2} (w_N^{t k1} Y_t[k1]),  w_n = e^{2πi/n}.
// T = 4 runs it as two radix-2 stages (t = t0 + 2 t1, k2 = a0 + 2 a1: w_4^{t k2} =
// (-1)^{t1 a0} w_4^{t0 a0} (-1)^{t0 a1}): a butterfly across lanes t ^ 2, the twiddle w_4 on
// lane 3 (t0 = a0 = 1), a butterfly across lanes t ^ 1. Lane t then holds k2 = a0 + 2 a1 with
// a0 = t >> 1, a1 = t & 1: the two bits of t reversed.
//
// Inputs: src4 = the source as RGBA32F texels (two neighbouring values of a row). Output: dst
// (batch, N, N) complex values as (re, im) bit pairs in 64-bit words. Push constant: +1
// inverse, -1 forward.
layout(constant_id = 0) const uint LOG2_N = 8;
// log2 of the invocations (subgroup lanes) per column: 0, 1 or 2.
layout(constant_id = 1) const uint LOG2_T = 0;
// Column pairs per workgroup.
layout(constant_id = 2) const uint PAIRS = 8;
// Invocations per workgroup, T * PAIRS (a 1D workgroup: llvmpipe runs 2D ones several times
// slower here).
layout(constant_id = 3) const uint GROUP_SIZE = 8;
layout(local_size_x_id = 3) in;

layout(set = 0, binding = 0) uniform samplerBuffer src4;
layout(std430, set = 0, binding = 1) writeonly buffer Dst { u64vec4 dst[]; };
layout(push_constant) uniform Params { float direction; } params;

#include "common/fft.glsl"

const uint N = 1u << LOG2_N;
const uint T = 1u << LOG2_T;
const uint LOG2_M = LOG2_N - LOG2_T;
const uint M = 1u << LOG2_M;

vec2 x[M];
vec2 y[M];
vec2 second[M]; // the second column, waiting for its turn

// One Stockham pass over the M registers (see common/fft.glsl), radix R = 2^LOG_R, after
// passes whose radices multiply to NS.
#define REGISTER_PASS(LOG_R, NS)                                                             \
    {                                                                                        \
        const uint R = 1u << LOG_R;                                                          \
        const uint ns = NS;                                                                  \
        [[unroll]] for (uint j = 0u; j < M / R; ++j) {                                       \
            uint k = j & (ns - 1u);                                                          \
            vec2 v[R];                                                                       \
            [[unroll]] for (uint q = 0u; q < R; ++q) {                                       \
                v[q] = rotate(x[j + q * (M / R)], q * k * (M / (ns * R)), M);                \
            }                                                                                \
            DFT_IN_REGISTERS(v, LOG_R)                                                       \
            [[unroll]] for (uint q = 0u; q < R; ++q) {                                       \
                y[(j - k) * R + k + q * ns] = v[q];                                          \
            }                                                                                \
        }                                                                                    \
        [[unroll]] for (uint i = 0u; i < M; ++i) {                                           \
            x[i] = y[i];                                                                     \
        }                                                                                    \
    }

// Four complex values as one 32-byte store (see the top of the file).
void store4(uint at, vec2 a, vec2 b, vec2 c, vec2 d) {
    dst[at >> 2u] = u64vec4(packUint2x32(floatBitsToUint(a)), packUint2x32(floatBitsToUint(b)),
                            packUint2x32(floatBitsToUint(c)), packUint2x32(floatBitsToUint(d)));
}

void main() {
    uint t = gl_LocalInvocationID.x & (T - 1u);
    uint column = (gl_WorkGroupID.x * PAIRS + (gl_LocalInvocationID.x >> LOG2_T)) * 2u;
    uint batch = gl_WorkGroupID.y;
    uint in_base = batch * N * N + column;

    // x[i] = column[t + T i], second[i] = the next column's; texel (row, column / 2) holds both.
    [[unroll]] for (uint i = 0u; i < M; ++i) {
        vec4 pair = texelFetch(src4, int((in_base + (t + T * i) * N) >> 1u));
        x[i] = conj_if_forward(pair.xy);
        second[i] = conj_if_forward(pair.zw);
    }

    // Y_t = DFT_M(x) in two passes (M = 64..256): radix 8 x 8, 16 x 8 or 16 x 16, as
    // `pass_schedule` in src/ocean/fft.rs.
    const uint LOG_R0 = (LOG2_M + 1u) / 2u;
    const uint LOG_R1 = LOG2_M / 2u;
    [[unroll]] for (uint c = 0u; c < 2u; ++c) {
        if (LOG_R0 == 4u) {
            REGISTER_PASS(4u, 1u)
        } else {
            REGISTER_PASS(3u, 1u)
        }
        if (LOG_R1 == 4u) {
            REGISTER_PASS(4u, 1u << LOG_R0)
        } else {
            REGISTER_PASS(3u, 1u << LOG_R0)
        }

        if (T == 2u) {
            // Lane 1 scales Y_1[k1] by w_N^{k1}, then one radix-2 butterfly across the pair (a
            // subgroup shuffle, no memory): X[k1] = Y_0 + Y'_1 on lane 0, X[k1 + M] = Y_0 -
            // Y'_1 on lane 1.
            [[unroll]] for (uint k1 = 0u; k1 < M; ++k1) {
                vec2 z = t == 0u ? x[k1] : rotate(x[k1], k1, N);
                vec2 partner = subgroupShuffleXor(z, 1u);
                x[k1] = t == 0u ? z + partner : partner - z;
            }
        } else if (T == 4u) {
            // Lane t scales Y_t[k1] by w_N^{t k1} (one of three constants, picked by t: each
            // folded from the f32 angle a, not through `rotate`'s exact axis cases; within the
            // tests' tolerance like the rest), then the two radix-2 stages across lanes
            // described at the top.
            [[unroll]] for (uint k1 = 0u; k1 < M; ++k1) {
                float a = float(k1) * (TAU / float(N));
                vec2 w = t == 0u ? vec2(1.0, 0.0)
                       : t == 1u ? vec2(cos(a), sin(a))
                       : t == 2u ? vec2(cos(2.0 * a), sin(2.0 * a))
                       : vec2(cos(3.0 * a), sin(3.0 * a));
                vec2 z = cmul(x[k1], w);
                vec2 partner = subgroupShuffleXor(z, 2u);
                z = (t & 2u) == 0u ? z + partner : partner - z;
                z = t == 3u ? vec2(-z.y, z.x) : z;
                partner = subgroupShuffleXor(z, 1u);
                x[k1] = (t & 1u) == 0u ? z + partner : partner - z;
            }
        }
        // Lane t holds X[k2 M + k], k < M: a contiguous run of the output row (k2 = t, or t's
        // two bits reversed for T = 4).
        uint k2 = T == 4u ? ((t >> 1u) | ((t & 1u) << 1u)) : t;
        uint out_base = (batch * N + column + c) * N + k2 * M;
        [[unroll]] for (uint k = 0u; k < M; k += 4u) {
            store4(out_base + k, conj_if_forward(x[k]), conj_if_forward(x[k + 1u]),
                   conj_if_forward(x[k + 2u]), conj_if_forward(x[k + 3u]));
        }
        [[unroll]] for (uint i = 0u; i < M; ++i) {
            x[i] = second[i];
        }
    }
}
