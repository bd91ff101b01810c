// The inverse FFT's output as the ocean kernels read it (assemble.comp, foam.comp, spray.comp):
// the includer declares `buffer Fields { vec2 fields[]; }`, four complex planes per cascade of
// N×N elements, element n holding wave number n − N/2 (hence the sign (−1)^(m+n) of every
// texel). Planes 0 and 1 hold (Dx, h) and (Dz, ∂h/∂x), planes 2 and 3 (∂h/∂z, ∂Dx/∂x) and
// (∂Dz/∂z, ∂Dx/∂z).

// Planes `first` and `first + 1` of cascade c at texel `texel` (sign-corrected), grid size n,
// as one vec4.
vec4 field_planes(uint c, uint first, uvec2 texel, uint n) {
    uint plane = n * n;
    uint at = texel.y * n + texel.x;
    float sign = ((texel.x + texel.y) & 1u) == 1u ? -1.0 : 1.0;
    return sign * vec4(fields[(c * 4u + first) * plane + at],
                       fields[(c * 4u + first + 1u) * plane + at]);
}

// The same at a fractional texel position p of cascade c (periodic bilinear; p ≥ 0). n is a
// power of two (every FFT size): the wrap is a mask, as an integer division has no vector
// instruction on a CPU (lavapipe split each into eight: two thirds of foam.comp's time).
vec4 field_planes_at(uint c, uint first, vec2 p, uint n) {
    vec2 f = fract(p);
    uint wrap = n - 1u;
    uvec2 a = uvec2(floor(p)) & wrap;
    uvec2 b = (a + 1u) & wrap;
    return mix(mix(field_planes(c, first, a, n), field_planes(c, first, uvec2(b.x, a.y), n), f.x),
               mix(field_planes(c, first, uvec2(a.x, b.y), n), field_planes(c, first, b, n), f.x),
               f.y);
}

// (∂Dx/∂x, ∂Dz/∂z, ∂Dx/∂z) of cascade c at fractional texel position p (planes 2 and 3).
vec3 field_derivatives_at(uint c, vec2 p, uint n) { return field_planes_at(c, 2u, p, n).yzw; }

// (Dx, h, Dz) of cascade c at fractional texel position p (planes 0 and 1; Dx and Dz before
// choppiness).
vec3 field_displacement_at(uint c, vec2 p, uint n) { return field_planes_at(c, 0u, p, n).xyz; }
