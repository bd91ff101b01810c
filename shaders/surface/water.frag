#version 460
// Ocean surface shading (the full treatment comes with the rendering issue): normals from the
// simulation's slopes, Schlick Fresnel (F0 = 0.02, water n = 1.33) between the sky's reflection and
// a deep-water body colour, a Blinn-Phong sun highlight, foam from the simulation, and a distance
// haze that blends into the horizon sky.
#include "common/frame.glsl"
#include "common/sky.glsl"

layout(location = 0) in vec3 in_rel_pos;
layout(location = 1) in vec2 in_world_xz;
layout(location = 0) out vec4 out_colour;

const vec3 WATER_BODY = vec3(0.004, 0.035, 0.06);
const float F0 = 0.02;

// Slopes add across cascades (normals do not): n = normalize(-Σ ∂h/∂x, 1, -Σ ∂h/∂z). Each
// cascade fades out with distance before its waves alias. Returns (normal, foam).
vec4 ocean_normal_foam(vec2 world_xz, float dist) {
    vec2 slope = vec2(0.0);
    float foam = 0.0;
    int cascades = int(frame.ocean.x);
    for (int c = 0; c < cascades; ++c) {
        float weight;
        vec3 uv = ocean_uv(world_xz, c, dist, weight);
        vec4 s = texture(ocean_normals, uv);
        slope += weight * s.xy;
        foam = max(foam, weight * s.w);
    }
    return vec4(normalize(vec3(-slope.x, 1.0, -slope.y)), foam);
}

void main() {
    float dist = length(in_rel_pos);
    vec3 v = -in_rel_pos / dist; // toward the camera
    vec4 nf = ocean_normal_foam(in_world_xz, dist);
    vec3 n = nf.xyz;
    vec3 sun = frame.sun_dir.xyz;

    vec3 r = reflect(-v, n);
    r.y = abs(r.y); // a reflected ray never enters the water
    float cos_theta = clamp(dot(n, v), 0.0, 1.0);
    float fresnel = F0 + (1.0 - F0) * pow(1.0 - cos_theta, 5.0);

    vec3 reflected = sky_gradient(r, sun);
    float diffuse = max(dot(n, sun), 0.0) * 0.5 + 0.5;
    vec3 body = WATER_BODY * diffuse * (SKY_HORIZON + SUN_COLOUR);
    vec3 colour = mix(body, reflected, fresnel);
    colour = mix(colour, vec3(0.85, 0.9, 0.92) * (0.6 + 0.4 * max(sun.y, 0.0)), nf.w * 0.8);

    vec3 h = normalize(v + sun);
    float spec = pow(max(dot(n, h), 0.0), 720.0) * frame.sun_dir.w * 0.25;
    colour += SUN_COLOUR * spec * fresnel / F0 * 0.2;

    vec3 horizon = sky_gradient(normalize(vec3(-v.x, 0.0, -v.z) + vec3(0.0, 0.002, 0.0)), sun);
    float haze = 1.0 - exp(-dist / 9000.0);
    out_colour = vec4(mix(colour, horizon, haze), 1.0);
}
