#version 460
// Ocean surface shading (seed 001 §3.3–3.6, seed 003, seed 004):
// - normal from the simulation's slopes (summed over cascades, each fading out with distance);
// - reflection and refraction textures at this pixel's screen position, offset by a scrolling
//   DU/DV map (seed 001 eq. 4–5) plus the normal's slope; both offsets fade with distance;
// - water depth along the view ray from the refraction depth texture, Beer-Lambert colour;
// - Fresnel weight between reflection and refraction (`--fresnel`: Schlick, exact (seed 004),
//   or seed 001 eq. 6 r = cos θ^0.5);
// - Blinn-Phong sun highlight (seed 003), foam from the simulation, haze toward the horizon.
// Every texture here has one mip level, so lookups are textureLod(…, 0): the same result as
// texture() (minification and magnification filters are both linear) without the per-quad
// derivatives and LOD a CPU driver computes for it. The cascade loop's bound is the
// specialization constant of common/water.glsl.
#include "common/frame.glsl"
#include "common/water.glsl"
#include "common/display.glsl"

layout(location = 0) in vec3 in_rel_pos;
layout(location = 1) in vec2 in_xz;
layout(location = 2) in vec3 in_displacement;
layout(location = 0) out vec4 out_colour;

layout(set = 1, binding = 0) uniform sampler2D reflection_colour;
layout(set = 1, binding = 1) uniform sampler2D refraction_colour;
layout(set = 1, binding = 2) uniform sampler2D refraction_depth;
layout(set = 1, binding = 3) uniform sampler2D dudv_map;

// WATER_COLOUR (c_o: deep water, seen through nothing) and ABSORPTION_PER_M (red absorbed
// first) come from src/shared.rs.
const float N_WATER = 1.333;
const float F0 = 0.02;               // ((n - 1) / (n + 1))^2
const float DUDV_STRENGTH = 0.012;   // screen-space offset at full strength
const float SLOPE_STRENGTH = 0.05;   // screen-space offset per unit slope
const float SHININESS = 720.0;

vec4 ocean_normal_foam(vec2 xz, float dist) {
    vec2 slope = vec2(0.0);
    float foam = 0.0;
    for (int c = 0; c < CASCADES; ++c) {
        float weight;
        vec3 uv = ocean_uv(xz, c, dist, weight);
        vec4 s = ocean_texture(ocean_normals, uv);
        slope += weight * s.xy;
        foam = max(foam, weight * s.w);
    }
    return vec4(normalize(vec3(-slope.x, 1.0, -slope.y)), foam);
}

// Fraction of light reflected at incidence cos θ (θ between normal and view).
float fresnel(float cos_theta) {
    uint model = frame.modes.y;
    if (model == FRESNEL_EXACT) {
        // Exact unpolarised Fresnel equations (seed 004 §2.5), Snell: sin θt = sin θi / n.
        float ti = acos(clamp(cos_theta, 1e-4, 1.0));
        if (ti < 1e-3) {
            return F0;
        }
        float tt = asin(sin(ti) / N_WATER);
        float s = sin(tt - ti) / sin(tt + ti);
        float t = tan(tt - ti) / tan(tt + ti);
        return clamp(0.5 * (s * s + t * t), 0.0, 1.0);
    }
    if (model == FRESNEL_POWER) {
        // Seed 001 eq. 6: r_refract = θ^r with r = 0.5, θ taken as cos θ = N·V (the angle itself
        // would make straight-down views fully reflective).
        return 1.0 - pow(cos_theta, 0.5);
    }
    // Schlick's approximation.
    return F0 + (1.0 - F0) * pow(1.0 - cos_theta, 5.0);
}

void main() {
    float dist = length(in_rel_pos);
    vec3 v = -in_rel_pos / dist; // toward the camera
    vec4 nf = ocean_normal_foam(in_xz, dist);
    vec3 n = nf.xyz;
    uint view = debug_view();
    if (view == VIEW_DISPLACEMENT) {
        out_colour = target_colour(0.5 + 0.25 * in_displacement.xzy);
        return;
    }
    if (view == VIEW_NORMALS) {
        out_colour = target_colour(n * 0.5 + 0.5);
        return;
    }
    if (view == VIEW_FOAM) {
        out_colour = target_colour(vec3(nf.w));
        return;
    }
    if (view == VIEW_WIREFRAME) {
        out_colour = target_colour(vec3(0.9, 0.95, 1.0));
        return;
    }
    vec3 sun = frame.sun_dir.xyz;

    // Distortion (seed 001 eq. 4-5): DU/DV sampled twice, scrolling in opposite directions
    // (tile coordinates and phase reduced on the CPU: frame.dudv_origin, frame.dudv).
    float t = frame.dudv.z;
    vec2 tile = in_xz * frame.dudv.x;
    vec2 dudv = textureLod(dudv_map, frame.dudv_origin.xy + tile + vec2(t, 0.0), 0.0).rg * 2.0 - 1.0;
    dudv += textureLod(dudv_map, frame.dudv_origin.zw + tile * frame.dudv.y + vec2(-t, t), 0.0).rg * 2.0 - 1.0;
    float fade = clamp(1.0 - dist / 3000.0, 0.0, 1.0) / max(1.0, dist / 40.0);
    vec2 offset = (dudv * DUDV_STRENGTH + n.xz * SLOPE_STRENGTH) * fade;
    vec2 screen = gl_FragCoord.xy * frame.viewport.zw;

    vec3 c_reflect = textureLod(reflection_colour, clamp(screen + offset, 0.001, 0.999), 0.0).rgb;

    // Water thickness along the ray: refraction depth behind the surface minus the surface's.
    float near_m = frame.water.w; // Camera::near_m (depth = near / view distance)
    float water_view = near_m / gl_FragCoord.z;
    vec2 refr_uv = clamp(screen + offset, 0.001, 0.999);
    float floor_ndc = textureLod(refraction_depth, refr_uv, 0.0).r;
    if (near_m / max(floor_ndc, 1e-30) < water_view) {
        // The offset reached something in front of the water: use the undistorted point.
        refr_uv = screen;
        floor_ndc = textureLod(refraction_depth, refr_uv, 0.0).r;
    }
    vec3 c_refract = textureLod(refraction_colour, refr_uv, 0.0).rgb;
    float floor_view = floor_ndc > 0.0 ? near_m / floor_ndc : 1e9;
    float thickness = max(floor_view - water_view, 0.0) * dist / water_view;
    // Seed 001 eq. 7 fades the whole colour toward c_o with depth, which removes reflections
    // over deep water; the depth fade belongs to the refracted light only (Beer-Lambert).
    vec3 transmitted = mix(WATER_COLOUR, c_refract, exp(-thickness * ABSORPTION_PER_M));

    float cos_theta = clamp(dot(n, v), 0.0, 1.0);
    float f = fresnel(cos_theta);
    vec3 colour = mix(transmitted, c_reflect, f);

    // Foam: white, lit by the sun and sky.
    colour = mix(colour, vec3(0.85, 0.9, 0.92) * (0.6 + 0.4 * max(sun.y, 0.0)), nf.w * 0.8);
    // c_h: Blinn-Phong sun highlight (seed 003).
    vec3 h = normalize(v + sun);
    float spec = pow(max(dot(n, h), 0.0), SHININESS) * frame.sun_dir.w * 0.05;
    colour += vec3(1.0, 0.9, 0.72) * spec;

    vec3 horizon = sky_lookup(normalize(vec3(-v.x, 0.0, -v.z) + vec3(0.0, 0.002, 0.0)));
    float haze = 1.0 - exp(-dist / 9000.0);
    out_colour = target_colour(mix(colour, horizon, haze));
}
