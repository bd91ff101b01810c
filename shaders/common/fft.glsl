// Shared by the two FFT kernels (fft.comp: a workgroup per row in shared memory, for GPUs;
// fft_rows.comp: rows in registers, one per SIMD lane, for CPU drivers). Both run Stockham
// radix-2 autosort stages (Govindaraju et al. 2008, "High Performance Discrete Fourier Transforms
// on Graphics Processors"), fused in registers into radix-8/16 groups:
//   a pass with R = 2^r values per group and Ns = product of the earlier passes' R:
//   for j < N/R: k = j mod Ns, v_q = x[j + q N/R] w^{qk} (w = e^{±2πi/(Ns R)}),
//                v = DFT_R(v) by r radix-2 stages, y[(j - k) R + k + q Ns] = v_q.
// Mirrors `stockham_model` and `pass_schedule` in src/ocean/fft.rs.
// Needs: `params.direction` (+1 inverse, -1 forward) declared before the include.

vec2 cmul(vec2 a, vec2 b) { return vec2(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }

// w for the inverse transform, its conjugate for the forward one.
vec2 conj_if_forward(vec2 w) { return vec2(w.x, w.y * params.direction); }

// e^{+2πi m/16}, m < 16: the roots inside an 8- or 16-point group.
const vec2 ROOTS16[16] = vec2[](
    vec2(1.0, 0.0), vec2(0.92387953, 0.38268343), vec2(0.70710678, 0.70710678), vec2(0.38268343, 0.92387953),
    vec2(0.0, 1.0), vec2(-0.38268343, 0.92387953), vec2(-0.70710678, 0.70710678), vec2(-0.92387953, 0.38268343),
    vec2(-1.0, 0.0), vec2(-0.92387953, -0.38268343), vec2(-0.70710678, -0.70710678), vec2(-0.38268343, -0.92387953),
    vec2(0.0, -1.0), vec2(0.38268343, -0.92387953), vec2(0.70710678, -0.70710678), vec2(0.92387953, -0.38268343));

// v = DFT_R(v) in place, R = 2^LOG_R <= 16, by LOG_R radix-2 Stockham stages. `v` must be a
// register array of R vec2 and every loop unrolled, so every index is a constant.
#define DFT_IN_REGISTERS(v, LOG_R)                                                           \
    [[unroll]] for (uint ls = 0u; ls < LOG_R; ++ls) {                                        \
        uint s_ = 1u << ls;                                                                  \
        const uint R_ = 1u << LOG_R;                                                         \
        vec2 u_[R_];                                                                         \
        [[unroll]] for (uint jj = 0u; jj < R_ / 2u; ++jj) {                                  \
            uint kk = jj & (s_ - 1u);                                                        \
            vec2 a = v[jj];                                                                  \
            vec2 b = cmul(v[jj + R_ / 2u], conj_if_forward(ROOTS16[kk * (16u / (2u * s_))])); \
            u_[2u * jj - kk] = a + b;                                                        \
            u_[2u * jj - kk + s_] = a - b;                                                   \
        }                                                                                    \
        v = u_;                                                                              \
    }
