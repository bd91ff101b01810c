// The inverse FFT's output as the ocean kernels read it (assemble.comp, foam.comp, spray.comp):
// the includer declares `buffer Fields { vec2 fields[]; }`, four complex planes per cascade of
// N×N elements, element n holding wave number n − N/2 (hence the sign (−1)^(m+n) of every
// texel). Planes 0 and 1 hold (Dx, h) and (Dz, ∂h/∂x), planes 2 and 3 (∂h/∂z, ∂Dx/∂x) and
// (∂Dz/∂z, ∂Dx/∂z).

// (∂Dx/∂x, ∂Dz/∂z, ∂Dx/∂z) of cascade c at texel `texel` (sign-corrected), grid size n.
vec3 field_derivatives(uint c, uvec2 texel, uint n) {
    uint plane = n * n;
    uint at = texel.y * n + texel.x;
    float sign = ((texel.x + texel.y) & 1u) == 1u ? -1.0 : 1.0;
    vec2 p2 = fields[(c * 4u + 2u) * plane + at];
    vec2 p3 = fields[(c * 4u + 3u) * plane + at];
    return sign * vec3(p2.y, p3.x, p3.y);
}

// The same at a fractional texel position p of cascade c (periodic bilinear; p ≥ 0).
vec3 field_derivatives_at(uint c, vec2 p, uint n) {
    vec2 f = fract(p);
    uvec2 a = uvec2(floor(p)) % n;
    uvec2 b = (a + 1u) % n;
    return mix(mix(field_derivatives(c, a, n), field_derivatives(c, uvec2(b.x, a.y), n), f.x),
               mix(field_derivatives(c, uvec2(a.x, b.y), n), field_derivatives(c, b, n), f.x),
               f.y);
}

// The Jacobian of the choppy surface from its summed derivatives d = λ(Dxx, Dzz, Dxz)
// (Tessendorf 2001, eq. 45).
float surface_jacobian(vec3 d) { return (1.0 + d.x) * (1.0 + d.y) - d.z * d.z; }

// (Dx, h, Dz) of cascade c at texel `texel` (sign-corrected; Dx and Dz before choppiness).
vec3 field_displacement(uint c, uvec2 texel, uint n) {
    uint plane = n * n;
    uint at = texel.y * n + texel.x;
    float sign = ((texel.x + texel.y) & 1u) == 1u ? -1.0 : 1.0;
    vec2 p0 = fields[(c * 4u + 0u) * plane + at];
    vec2 p1 = fields[(c * 4u + 1u) * plane + at];
    return sign * vec3(p0.x, p0.y, p1.x);
}

// The same at a fractional texel position p of cascade c (periodic bilinear; p ≥ 0).
vec3 field_displacement_at(uint c, vec2 p, uint n) {
    vec2 f = fract(p);
    uvec2 a = uvec2(floor(p)) % n;
    uvec2 b = (a + 1u) % n;
    return mix(mix(field_displacement(c, a, n), field_displacement(c, uvec2(b.x, a.y), n), f.x),
               mix(field_displacement(c, uvec2(a.x, b.y), n), field_displacement(c, b, n), f.x),
               f.y);
}
