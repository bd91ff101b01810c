#version 460
// Composite: HDR scene colour -> display. Exposure, then the ACES filmic fit of Narkowicz (2015,
// "ACES Filmic Tone Mapping Curve"). The target is an sRGB format, so the hardware encodes gamma.
layout(set = 0, binding = 0) uniform sampler2D hdr_colour;
layout(push_constant) uniform Composite { float exposure; } pc;

layout(location = 0) in vec2 in_uv;
layout(location = 1) in vec2 in_ndc;
layout(location = 0) out vec4 out_colour;

vec3 aces_fit(vec3 x) {
    const float a = 2.51, b = 0.03, c = 2.43, d = 0.59, e = 0.14;
    return clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0, 1.0);
}

void main() {
    vec3 hdr = texture(hdr_colour, in_uv).rgb;
    out_colour = vec4(aces_fit(hdr * pc.exposure), 1.0);
}
