// Procedural sky radiance: zenith-to-horizon gradient, a darker haze below the horizon, a sun disc
// with a forward-scattering glow. Shared by the sky pass and by the water's reflections so the two
// always agree. Radiance is linear HDR; common/display.glsl tone-maps it in the main view.

const vec3 SKY_ZENITH = vec3(0.09, 0.25, 0.62);
const vec3 SKY_HORIZON = vec3(0.60, 0.72, 0.85);
const vec3 SKY_BELOW = vec3(0.28, 0.36, 0.44);
const vec3 SUN_COLOUR = vec3(1.0, 0.90, 0.72);
const float SUN_ANGULAR_RADIUS = 0.0093; // rad: about twice the real sun, so it reads at 720p

// Sky without the sun disc (also what a rough reflection sees).
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

// Full sky radiance including the sun disc (intensity from sun.w via the caller's scale).
vec3 sky_radiance(vec3 dir, vec3 sun, float sun_scale) {
    float disc = smoothstep(cos(SUN_ANGULAR_RADIUS * 1.15), cos(SUN_ANGULAR_RADIUS), dot(dir, sun));
    return sky_gradient(dir, sun) + SUN_COLOUR * sun_scale * disc;
}
