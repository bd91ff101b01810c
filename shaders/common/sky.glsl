// Procedural sky radiance: zenith-to-horizon gradient, a darker haze below the horizon and a
// forward-scattering glow around the sun, rendered into the sky cube (sky/sky_cube.frag) that
// every pass looks up, so reflections and the sky agree. The sun's disc is not in the cube (its
// texels drew a blocky 13 px disc): the sky pass draws it per pixel (`sun_disc`), and the water's
// specular term is its reflection. Radiance is linear HDR; common/display.glsl tone-maps it in
// the main view.

const vec3 SKY_ZENITH = vec3(0.09, 0.25, 0.62);
const vec3 SKY_HORIZON = vec3(0.60, 0.72, 0.85);
const vec3 SKY_BELOW = vec3(0.28, 0.36, 0.44);
const vec3 SUN_COLOUR = vec3(1.0, 0.90, 0.72);
// The sun's mean apparent diameter is 0.533° (Allen's Astrophysical Quantities, 4th ed., §14.1):
// angular radius 0.00465 rad.
const float SUN_ANGULAR_RADIUS = 0.00465;
// Linear limb darkening I(μ)/I(1) = 1 − u(1 − μ), μ the cosine of the angle from the disc's normal
// to the line of sight, u ≈ 0.6 in the visible (Allen's Astrophysical Quantities, §14.7).
const float SUN_LIMB_U = 0.6;

// Sky without the sun disc (what the sky cube holds).
vec3 sky_gradient(vec3 dir, vec3 sun) {
    float up = dir.y;
    vec3 col;
    if (up >= 0.0) {
        // Horizon brightening: 1 at the horizon, 0 toward the zenith.
        col = mix(SKY_ZENITH, SKY_HORIZON, pow(1.0 - up, 5.0));
    } else {
        col = mix(SKY_HORIZON, SKY_BELOW, clamp(-up * 6.0, 0.0, 1.0));
    }
    float cos_sun = max(dot(dir, sun), 0.0);
    col += SUN_COLOUR * (0.25 * pow(cos_sun, 8.0) + 0.8 * pow(cos_sun, 256.0));
    return col;
}

// The sun's disc along `dir`, relative to its centre's radiance: the share of a pixel
// `pixel_rad` wide (in radians) the disc covers, times the limb darkening where it does. The
// angle from the sun comes from |dir × sun| = sin θ, exact in f32 near θ = 0 (acos of the dot
// product resolves steps of 3.5·10⁻⁴ rad, 8 % of the radius).
float sun_disc(vec3 dir, vec3 sun, float pixel_rad) {
    float theta = dot(dir, sun) > 0.0 ? asin(min(length(cross(dir, sun)), 1.0)) : 3.0;
    float cover = clamp((SUN_ANGULAR_RADIUS - theta) / pixel_rad + 0.5, 0.0, 1.0);
    float r = min(theta / SUN_ANGULAR_RADIUS, 1.0);
    float mu = sqrt(1.0 - r * r);
    return cover * (1.0 - SUN_LIMB_U * (1.0 - mu));
}
