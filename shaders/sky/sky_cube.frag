#version 460
// Renders one face of the sky cubemap: the direction of each texel by the inverse of Vulkan's
// cube-face selection (spec table "Cube map face selection"), then the sky (common/sky.glsl):
// rgb its radiance, a the share of sunlight its clouds let through. Run for the six faces when
// the sun or the cloud cover changes.
// The multiple scattering's table (src/render/multiple_scattering.rs), read by common/sky.glsl.
layout(set = 0, binding = 0) uniform sampler2D sky_multiple_scattering;
#define SKY_MULTIPLE_SCATTERING
#include "common/sky.glsl"

// sky: x the cloud cover (0–1), y the sun's irradiance; sunlight and zenith: the sun's light at
// the sea and the clear sky's radiance at the zenith (rgb; SkyCube::update).
layout(push_constant) uniform Face {
    vec4 sun_dir;
    vec4 sky;
    vec4 sunlight;
    vec4 zenith;
    uint face;
} pc;

layout(location = 0) in vec2 in_uv;
layout(location = 1) in vec2 in_ndc;
layout(location = 0) out vec4 out_colour;

vec3 face_direction(uint face, vec2 st) {
    float a = st.x * 2.0 - 1.0;
    float b = st.y * 2.0 - 1.0;
    switch (face) {
        case 0u: return vec3(1.0, -b, -a);
        case 1u: return vec3(-1.0, -b, a);
        case 2u: return vec3(a, 1.0, b);
        case 3u: return vec3(a, -1.0, -b);
        case 4u: return vec3(a, -b, 1.0);
        default: return vec3(-a, -b, -1.0);
    }
}

void main() {
    vec3 dir = normalize(face_direction(pc.face, in_uv));
    out_colour = sky_radiance(dir, pc.sun_dir.xyz, pc.sky.x, pc.sky.y, pc.sunlight.rgb, pc.zenith.rgb);
}
