// The statistics of the slopes a pixel of the water does not resolve, for the sun's glitter
// (surface/water.frag; shaders/test/glitter_lobe.comp checks them against their world-frame
// covariance, tests/sun_glitter.rs).

// The covariance of slopes whose mean square over both directions is `total` and whose
// anisotropy is `a` (Σ(k_x² − k_z²)E, Σk_x k_z E), in the frame of the water's unit vector
// `along` and the one across it (along rotated a quarter turn from x toward z): (mean square
// along, mean square across, covariance of the two). With φ the angle of `along` from x:
// ½·total ± (½·a.x·cos 2φ + a.y·sin 2φ), and a.y·cos 2φ − ½·a.x·sin 2φ (the tensor
// ½[[total + a.x, 2a.y], [2a.y, total − a.x]] turned by φ; src/ocean/moments.rs' `slope_along`
// is the first one's twin).
vec3 slope_covariance(float total, vec2 a, vec2 along) {
    float cos2 = along.x * along.x - along.y * along.y;
    float sin2 = 2.0 * along.x * along.y;
    float anisotropic = 0.5 * a.x * cos2 + a.y * sin2;
    return vec3(0.5 * total + anisotropic, 0.5 * total - anisotropic,
                a.y * cos2 - 0.5 * a.x * sin2);
}

// The Beckmann distribution D(h) of facet normals around the drawn normal n whose slopes have
// covariance M = [[m.x, m.z], [m.z, m.y]] (`slope_covariance`'s order) in the frame of `along`
// and the direction across it: with the half vector h's slopes x = (x_a, x_c) along the two
// axes (tangent to n), D = exp(−xᵀM⁻¹x/2)/(2π √det M cos⁴θ_h), so D·cos⁴θ_h is the slopes'
// Gaussian density. A wind diagonal to the view shears the lobe through m.z (with M diagonal,
// as before 2026-12-03, the lobe was about 1.5 % of σ too wide at 45° to a 10 m/s wind).
float beckmann_lobe(vec3 n, vec3 h, vec2 along, vec3 m) {
    float nh = max(dot(n, h), 1e-4);
    vec3 a = vec3(along.x, 0.0, along.y);
    vec3 t_along = normalize(a - n * dot(a, n));
    vec3 t_across = cross(t_along, n); // `along` turned a quarter from x toward z, as M
    vec2 x = vec2(dot(h, t_along), dot(h, t_across)) / nh;
    float c2 = nh * nh;
    float det = m.x * m.y - m.z * m.z;
    float q = (x.x * x.x * m.y - 2.0 * x.x * x.y * m.z + x.y * x.y * m.x) / det;
    return exp(-0.5 * q) / (6.28318531 * sqrt(det) * c2 * c2);
}

// erfc(x) = erfc_factor(x)·e^(−x²) for x ≥ 0 (Abramowitz & Stegun 7.1.26, |error| < 1.5·10⁻⁷).
float erfc_factor(float x) {
    float t = 1.0 / (1.0 + 0.3275911 * x);
    return t * (0.254829592 + t * (-0.284496736 + t * (1.421413741
           + t * (-1.453152027 + t * 1.061405429))));
}

// The standard normal distribution's upper tail, 1 − Φ(a).
float normal_tail(float a) {
    float x = abs(a) * 0.70710678;
    float tail = 0.5 * erfc_factor(x) * exp(-x * x);
    return a >= 0.0 ? tail : 1.0 - tail;
}

// The mean slope toward the eye of the facets the eye sees, on a surface whose slopes along
// the view are Gaussian with standard deviation `sigma` about a plane the view meets at
// cot θ = `mu` (θ the angle of incidence). A facet of slope s toward the eye shows the eye
// μ + s of its area per unit of its plane's (the visible-normal distribution, Heitz 2014,
// "Understanding the masking-shadowing function", eq. 38, in slope space; Smith's masking
// takes the same share of every facet that faces the eye); facets with s < −μ face away. So
// s̄ = ∫ s (μ + s) p(s) ds / ∫ (μ + s) p(s) ds over s > −μ = σ Φ(a) / (a Φ(a) + φ(a)) with
// a = μ/σ: σ²/μ seen from high above (a ≫ 1), 1.25 σ at the horizon (a = 0). Φ from
// Abramowitz & Stegun 7.1.26 (`erfc_factor`). shaders/test/visible_slope.comp runs it for
// tests/reflection.rs, which integrates the distribution itself.
float mean_visible_slope(float mu, float sigma) {
    float a = max(mu, 0.0) / max(sigma, 1e-6);
    float x = a * 0.70710678;
    float gauss = exp(-x * x); // e^(−a²/2): erfc's factor and φ(a)'s are one
    float cdf = 1.0 - 0.5 * erfc_factor(x) * gauss;
    float pdf = 0.39894228 * gauss;
    return sigma * cdf / (a * cdf + pdf);
}
