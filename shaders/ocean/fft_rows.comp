#version 460
#extension GL_EXT_control_flow_attributes : require
#extension GL_KHR_shader_subgroup_shuffle : require
// FFT of the rows of a batch of N x N complex arrays for CPU drivers (lavapipe), written
// transposed like fft.comp, so two dispatches make the 2D transform.
//
// On a CPU driver each SIMD lane is one invocation and every load or store of shared or storage
// memory is a per-lane scalar access, so the cost is memory operations, not arithmetic, and
// workgroup barriers are coroutine switches. Here each row of N values lives in the registers of
// T invocations (T = 1 up to N = 256, 2 for N = 512), M = N/T values each; passes exchange values
// by renaming registers, never through memory; rows are fetched as RGBA32F texels (two values a
// fetch, one vector gather per texel on llvmpipe, where a storage-buffer load is a branch per
// lane and component); no shared memory and no barrier.
//
// T = 2 is one step of a four-step FFT (Bailey 1990, "FFTs in external or hierarchical memory"):
// lane t transforms x[t + 2i], i < M, in registers (Y_t), and the pair finishes with one radix-2
// butterfly over t through a subgroup shuffle:
//   X[k1 + M k2] = Σ_t (-1)^{t k2} (w_N^{t k1} Y_t[k1]),  w_n = e^{±2πi/n}.
//
// Inputs: src4 = the source as RGBA32F texels (x[2i], x[2i+1]). Output: dst (batch, N, N) vec2,
// transposed. Push constant: +1 inverse, -1 forward. Twiddles are compile-time constants
// (folded from cos/sin of constant angles).
layout(constant_id = 0) const uint LOG2_N = 8;
// log2 of the invocations (subgroup lanes) per row: 0 or 1.
layout(constant_id = 1) const uint LOG2_T = 0;
// Rows per workgroup.
layout(constant_id = 2) const uint ROWS = 8;
// Invocations per workgroup, T * ROWS (a 1D workgroup: llvmpipe runs 2D ones several times
// slower here).
layout(constant_id = 3) const uint GROUP_SIZE = 8;
layout(local_size_x_id = 3) in;

layout(set = 0, binding = 0) uniform samplerBuffer src4;
layout(std430, set = 0, binding = 1) writeonly buffer Dst { vec2 dst[]; };
layout(push_constant) uniform Params { float direction; } params;

#include "common/fft.glsl"

const uint N = 1u << LOG2_N;
const uint T = 1u << LOG2_T;
const uint LOG2_M = LOG2_N - LOG2_T;
const uint M = 1u << LOG2_M;
const float TAU = 6.283185307179586;

// e^{±2πi m/n} for constant m and n (a power of two): folded at compile time.
vec2 root(uint m, uint n) {
    float a = float(m & (n - 1u)) * (TAU / float(n));
    return conj_if_forward(vec2(cos(a), sin(a)));
}

vec2 x[M];
vec2 y[M];

// One Stockham pass over the M registers (see common/fft.glsl), radix R = 2^LOG_R.
#define REGISTER_PASS(LOG_R)                                                                 \
    {                                                                                        \
        const uint R = 1u << LOG_R;                                                          \
        [[unroll]] for (uint j = 0u; j < M / R; ++j) {                                       \
            uint k = j & (ns - 1u);                                                          \
            vec2 v[R];                                                                       \
            [[unroll]] for (uint q = 0u; q < R; ++q) {                                       \
                v[q] = x[j + q * (M / R)];                                                   \
                if (q * k != 0u) {                                                           \
                    v[q] = cmul(v[q], root(q * k * (M / (ns * R)), M));                                  \
                }                                                                            \
            }                                                                                \
            DFT_IN_REGISTERS(v, LOG_R)                                                       \
            [[unroll]] for (uint q = 0u; q < R; ++q) {                                       \
                y[(j - k) * R + k + q * ns] = v[q];                                          \
            }                                                                                \
        }                                                                                    \
        [[unroll]] for (uint i = 0u; i < M; ++i) {                                           \
            x[i] = y[i];                                                                     \
        }                                                                                    \
        ns *= R;                                                                             \
    }

void main() {
    uint t = gl_LocalInvocationID.x & (T - 1u);
    uint r = gl_LocalInvocationID.x >> LOG2_T;
    uint row = gl_WorkGroupID.x * ROWS + r;
    uint batch = gl_WorkGroupID.y;
    uint row_base = (batch * N + row) * N;
    uint out_base = batch * N * N + row;

    // x[i] = row[t + T i]; texel j holds row[2j] and row[2j + 1].
    if (T == 1u) {
        [[unroll]] for (uint j = 0u; j < M / 2u; ++j) {
            vec4 pair = texelFetch(src4, int((row_base >> 1u) + j));
            x[2u * j] = pair.xy;
            x[2u * j + 1u] = pair.zw;
        }
    } else {
        [[unroll]] for (uint i = 0u; i < M; ++i) {
            vec4 pair = texelFetch(src4, int((row_base >> 1u) + i));
            x[i] = t == 0u ? pair.xy : pair.zw;
        }
    }

    // Y_t = DFT_M(x): ceil(LOG2_M / 4) passes of 3 or 4 fused stages, the larger first.
    const uint PASSES = (LOG2_M + 3u) / 4u;
    const uint BASE_R = LOG2_M / PASSES;
    const uint EXTRA = LOG2_M % PASSES;
    uint ns = 1u;
    [[unroll]] for (uint p = 0u; p < PASSES; ++p) {
        if (BASE_R + (p < EXTRA ? 1u : 0u) == 4u) {
            REGISTER_PASS(4u)
        } else {
            REGISTER_PASS(3u)
        }
    }

    if (T == 1u) {
        [[unroll]] for (uint k = 0u; k < N; ++k) {
            dst[out_base + k * N] = x[k];
        }
        return;
    }

    // Two lanes: lane 1 scales Y_1[k1] by w_N^{k1}, then one radix-2 butterfly across the pair
    // (a subgroup shuffle, no memory): X[k1] = Y_0 + Y'_1 on lane 0, X[k1 + M] = Y_0 - Y'_1 on
    // lane 1.
    [[unroll]] for (uint k1 = 0u; k1 < M; ++k1) {
        vec2 z = t == 0u ? x[k1] : cmul(x[k1], root(k1, N));
        vec2 partner = subgroupShuffleXor(z, 1u);
        dst[out_base + (k1 + M * t) * N] = t == 0u ? z + partner : partner - z;
    }
}
