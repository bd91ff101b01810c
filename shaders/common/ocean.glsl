// Shared by the ocean compute shaders: complex helpers and the choppy surface's Jacobian. (The
// dispersion relation is evaluated on the CPU, src/ocean/spectrum.rs `omega_steps`, and read by
// evolve.comp from a buffer.)
const float PI = 3.14159265358979;

vec2 cmul(vec2 a, vec2 b) { return vec2(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }
vec2 conj2(vec2 a) { return vec2(a.x, -a.y); }
vec2 times_i(vec2 a) { return vec2(-a.y, a.x); }

// The Jacobian of the choppy surface from its summed derivatives d = λ(Dxx, Dzz, Dxz)
// (Tessendorf 2001, eq. 45).
float surface_jacobian(vec3 d) { return (1.0 + d.x) * (1.0 + d.y) - d.z * d.z; }

