#version 460
// Lit water plane (placeholder for the FFT ocean): Schlick Fresnel (F0 = 0.02, water n = 1.33)
// between the sky's reflection and a deep-water body colour, a Blinn-Phong sun highlight, and a
// distance haze that blends into the horizon sky. Small analytic ripples perturb the normal near
// the camera and fade with distance (no aliasing at the horizon).
#include "common/frame.glsl"
#include "common/sky.glsl"

layout(location = 0) in vec3 in_rel_pos;
layout(location = 1) in vec2 in_world_xz;
layout(location = 0) out vec4 out_colour;

const vec3 WATER_BODY = vec3(0.004, 0.035, 0.06);
const float F0 = 0.02;

vec3 ripple_normal(vec2 xz, float t, float fade) {
    // Gradient of a sum of four sines; amplitudes are slopes (dimensionless).
    vec2 slope = vec2(0.0);
    const vec4 dirs_x = vec4(0.98, 0.60, -0.35, 0.15);
    const vec4 dirs_z = vec4(0.20, 0.80, 0.94, -0.99);
    const vec4 k = vec4(0.21, 0.47, 0.93, 1.71);     // rad/m
    const vec4 amp = vec4(0.05, 0.035, 0.025, 0.015); // slope amplitude
    for (int i = 0; i < 4; ++i) {
        vec2 d = vec2(dirs_x[i], dirs_z[i]);
        float omega = sqrt(9.81 * k[i]); // deep-water dispersion
        slope += d * amp[i] * cos(k[i] * dot(d, xz) - omega * t);
    }
    slope *= fade;
    return normalize(vec3(-slope.x, 1.0, -slope.y));
}

void main() {
    float dist = length(in_rel_pos);
    vec3 v = -in_rel_pos / dist; // toward the camera
    float fade = exp(-dist / 300.0);
    vec3 n = ripple_normal(in_world_xz, frame.camera_pos.w, fade);
    vec3 sun = frame.sun_dir.xyz;

    vec3 r = reflect(-v, n);
    r.y = abs(r.y); // a reflected ray never enters the water
    float cos_theta = clamp(dot(n, v), 0.0, 1.0);
    float fresnel = F0 + (1.0 - F0) * pow(1.0 - cos_theta, 5.0);

    vec3 reflected = sky_gradient(r, sun);
    float diffuse = max(dot(n, sun), 0.0) * 0.5 + 0.5;
    vec3 body = WATER_BODY * diffuse * (SKY_HORIZON + SUN_COLOUR);
    vec3 colour = mix(body, reflected, fresnel);

    vec3 h = normalize(v + sun);
    float spec = pow(max(dot(n, h), 0.0), 720.0) * frame.sun_dir.w * 0.25;
    colour += SUN_COLOUR * spec * fresnel / F0 * 0.2;

    vec3 horizon = sky_gradient(normalize(vec3(-v.x, 0.0, -v.z) + vec3(0.0, 0.002, 0.0)), sun);
    float haze = 1.0 - exp(-dist / 9000.0);
    out_colour = vec4(mix(colour, horizon, haze), 1.0);
}
