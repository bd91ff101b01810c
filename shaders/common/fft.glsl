// Shared by the two FFT kernels (fft.comp: a workgroup per row in shared memory, for GPUs;
// fft_rows.comp: rows in registers, one per SIMD lane, for CPU drivers). Both run Stockham
// radix-2 autosort stages (Govindaraju et al. 2008, "High Performance Discrete Fourier Transforms
// on Graphics Processors"), fused in registers into radix-8/16 groups:
//   a pass with R = 2^r values per group and Ns = product of the earlier passes' R:
//   for j < N/R: k = j mod Ns, v_q = x[j + q N/R] w^{qk} (w = e^{±2πi/(Ns R)}),
//                v = DFT_R(v) by r radix-2 stages, y[(j - k) R + k + q Ns] = v_q.
// Mirrors `stockham_model` and `pass_schedule` in src/ocean/fft.rs.
//
// The butterflies always run the inverse transform (roots e^{+2πi m/n}), so every root inside a
// group is a constant; a forward transform conjugates its input and output instead
// (DFT(x) = conj(IDFT(conj x))): `conj_if_forward` at the first load and the last store.
// Needs: `params.direction` (+1 inverse, -1 forward) declared before the include.

const float TAU = 6.283185307179586;

vec2 cmul(vec2 a, vec2 b) { return vec2(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }

// v for the inverse transform, its conjugate for the forward one.
vec2 conj_if_forward(vec2 v) { return vec2(v.x, v.y * params.direction); }

// v e^{+2πi m/n} for m and n constant after unrolling (n a power of two). The roots on the axes
// and diagonals (m/n a multiple of 1/8) are applied with adds and sign flips, without the
// multiplies by 0 and ±1 a general complex product would keep (IEEE rules forbid the compiler to
// drop them); the others multiply by a constant folded from cos/sin.
vec2 rotate(vec2 v, uint m, uint n) {
    m &= n - 1u;
    const float H = 0.70710678118654752;
    float a = float(m) * (TAU / float(n));
    vec2 r = cmul(v, vec2(cos(a), sin(a)));
    if ((m * 8u) % n == 0u) {
        uint e = m * 8u / n;
        r = e == 0u ? v
          : e == 1u ? H * vec2(v.x - v.y, v.x + v.y)
          : e == 2u ? vec2(-v.y, v.x)
          : e == 3u ? H * vec2(-v.x - v.y, v.x - v.y)
          : e == 4u ? -v
          : e == 5u ? H * vec2(v.y - v.x, -v.x - v.y)
          : e == 6u ? vec2(v.y, -v.x)
          : H * vec2(v.x + v.y, v.y - v.x);
    }
    return r;
}

// v = IDFT_R(v) in place, R = 2^LOG_R <= 16, by LOG_R radix-2 Stockham stages. `v` must be a
// register array of R vec2 and every loop unrolled, so every index is a constant.
#define DFT_IN_REGISTERS(v, LOG_R)                                                           \
    [[unroll]] for (uint ls = 0u; ls < LOG_R; ++ls) {                                        \
        uint s_ = 1u << ls;                                                                  \
        const uint R_ = 1u << LOG_R;                                                         \
        vec2 u_[R_];                                                                         \
        [[unroll]] for (uint jj = 0u; jj < R_ / 2u; ++jj) {                                  \
            uint kk = jj & (s_ - 1u);                                                        \
            vec2 a = v[jj];                                                                  \
            vec2 b = rotate(v[jj + R_ / 2u], kk, 2u * s_);                                   \
            u_[2u * jj - kk] = a + b;                                                        \
            u_[2u * jj - kk + s_] = a - b;                                                   \
        }                                                                                    \
        v = u_;                                                                              \
    }
