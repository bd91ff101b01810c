#version 460
// The spray's puffs (src/render/passes/spray.rs): one camera-facing square per live particle of
// the frame's slot (an indirect draw of 6 vertices per instance, counted by
// shaders/ocean/spray.comp), lit per puff here. A puff spreads as it flies (its radius grows
// with the square root of its age, as a cloud of drops diffusing), is drawn stretched along its
// motion, and thins as it spreads (its water over a larger area: the opacity falls as
// 1/radius²); it fades in over its first tenth of a second and out over its last second, and
// near the eye. Lit as a scattering medium: the sun through a forward-peaked phase function
// (cloud drops scatter mostly forward; Henyey–Greenstein with g = 0.7) and the sky from all
// around, white under white light.
#include "common/frame.glsl"
#include "common/ocean.glsl"

struct Particle {
    vec4 position_age;    // world position (m), age (s)
    vec4 velocity_radius; // velocity (m/s), drop radius (m)
    vec4 surface;         // x: the water's height under it (m)
};
layout(std430, set = 1, binding = 0) readonly buffer Particles { Particle particles[]; };

layout(location = 0) out vec2 out_corner;
layout(location = 1) out vec4 out_colour; // rgb radiance, a opacity at the centre

// Radius of a new puff (m), its growth (m/√s), and its opacity while that small.
const float BIRTH_RADIUS_M = 0.3;
const float GROWTH_M = 0.9;
const float BIRTH_OPACITY = 0.9;
// Seconds of flight a puff is stretched over along its motion (a streak, as the eye sees a
// cloud of fast drops).
const float STREAK_S = 0.12;

float henyey_greenstein(float mu, float g) {
    float d = 1.0 + g * g - 2.0 * g * mu;
    return (1.0 - g * g) / (4.0 * PI * d * sqrt(d));
}

void main() {
    const vec2 CORNERS[6] = vec2[](vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(1.0, 1.0),
                                   vec2(-1.0, -1.0), vec2(1.0, 1.0), vec2(-1.0, 1.0));
    Particle p = particles[gl_InstanceIndex];
    vec2 c = CORNERS[gl_VertexIndex];
    float age = p.position_age.w;
    float radius = BIRTH_RADIUS_M + GROWTH_M * sqrt(age);
    vec3 rel = p.position_age.xyz - VIEW.eye.xyz;
    float distance = length(rel);
    // (A puff at the eye is invisible, faded out below; any direction does for it.)
    vec3 forward = distance > 1e-4 ? rel / distance : vec3(0.0, 0.0, 1.0);
    // The square's axes: along the motion as seen across the view, and across; stretched along
    // by the distance flown in STREAK_S. A puff moving along the view gets a sideways axis: the
    // horizontal one across the view, or, looking straight up or down, the x axis's.
    vec3 v = p.velocity_radius.xyz;
    vec3 along = v - dot(v, forward) * forward;
    float seen = length(along);
    if (seen > 1e-3) {
        along /= seen;
    } else {
        vec3 reference = abs(forward.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
        along = normalize(cross(forward, reference));
        seen = 0.0;
    }
    vec3 across = cross(along, forward);
    vec3 corner = rel + along * c.x * (radius + 0.5 * STREAK_S * seen) + across * c.y * radius;
    gl_Position = VIEW.view_proj * vec4(corner, 1.0);
    out_corner = c;

    float spread = BIRTH_RADIUS_M / radius;
    // Faded out within a few metres of the eye (a puff there would fill the view).
    float opacity = BIRTH_OPACITY * spread * spread * smoothstep(0.0, 0.1, age)
                    * (1.0 - smoothstep(SPRAY_MAX_AGE_S - 1.0, SPRAY_MAX_AGE_S, age))
                    * smoothstep(2.0, 6.0, distance);
    vec3 l = frame.sun_dir.xyz;
    vec3 sun = sun_light_at(p.position_age.xyz) * henyey_greenstein(dot(forward, l), 0.7);
    vec3 sky = sky_ambient(vec3(0.0, 1.0, 0.0));
    out_colour = vec4(sun + sky, opacity);
}
