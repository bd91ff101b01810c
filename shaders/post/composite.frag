#version 460
// Composite: HDR colour -> display. Exposure, then the ACES filmic fit of Narkowicz (2015,
// "ACES Filmic Tone Mapping Curve"). The target is an sRGB format, so the hardware encodes gamma.
// Debug views show an intermediate full screen instead: the reflection or refraction texture,
// or the DU/DV map (tiled 4x, du in red, dv in green).
layout(set = 0, binding = 0) uniform sampler2D hdr_colour;
layout(set = 0, binding = 1) uniform sampler2D reflection_colour;
layout(set = 0, binding = 2) uniform sampler2D refraction_colour;
layout(set = 0, binding = 3) uniform sampler2D dudv_map;
layout(push_constant) uniform Composite { float exposure; uint view; } pc;

layout(location = 0) in vec2 in_uv;
layout(location = 1) in vec2 in_ndc;
layout(location = 0) out vec4 out_colour;

vec3 aces_fit(vec3 x) {
    const float a = 2.51, b = 0.03, c = 2.43, d = 0.59, e = 0.14;
    return clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0, 1.0);
}

void main() {
    if (pc.view == 3u) {
        out_colour = vec4(texture(dudv_map, in_uv * 4.0).rg, 0.0, 1.0);
        return;
    }
    vec3 hdr;
    if (pc.view == 1u) {
        hdr = texture(reflection_colour, in_uv).rgb;
    } else if (pc.view == 2u) {
        hdr = texture(refraction_colour, in_uv).rgb;
    } else {
        hdr = texture(hdr_colour, in_uv).rgb;
    }
    out_colour = vec4(aces_fit(hdr * pc.exposure), 1.0);
}
