#version 460
// Composite, in compute: HDR colour -> display bytes, one invocation per output pixel.
// Exposure, then the ACES filmic fit of Narkowicz (2015, "ACES Filmic Tone Mapping Curve"), then
// the sRGB transfer function (IEC 61966-2-1) by hand: the result goes to an RGBA8 UNORM storage
// image (8-bit sRGB formats are rarely storage-capable) that is copied bit for bit into the sRGB
// output, in BGRA order when the output is a BGRA swapchain. The scene target may be smaller than
// the output (--render-scale): the bilinear lookup scales it up.
// Debug views show an intermediate full screen instead: the reflection or refraction texture,
// or the DU/DV map (tiled 4x, du in red, dv in green).
// A compute pass rather than a full-screen triangle (src/render/passes/composite.rs says why).
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D hdr_colour;
layout(set = 0, binding = 1) uniform sampler2D reflection_colour;
layout(set = 0, binding = 2) uniform sampler2D refraction_colour;
layout(set = 0, binding = 3) uniform sampler2D dudv_map;
layout(set = 0, binding = 4, rgba8) uniform writeonly image2D display;
layout(push_constant) uniform Composite { float exposure; uint view; uint bgra; } pc;

vec3 aces_fit(vec3 x) {
    const float a = 2.51, b = 0.03, c = 2.43, d = 0.59, e = 0.14;
    return clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0, 1.0);
}

// Linear [0, 1] -> sRGB-encoded [0, 1]. Above the linear toe, 1.055 c^(1/2.4) − 0.055 is
// replaced by Taylor's fit in square roots (I. Taylor, "sRGB approximations for HLSL",
// chilliant.com, 2012): within 0.25/255 of the exact curve over [0, 1], so the stored byte
// differs by at most 1, and three square roots cost far less than pow on a CPU driver.
vec3 srgb_encode(vec3 c) {
    vec3 s1 = sqrt(c);
    vec3 s2 = sqrt(s1);
    vec3 s3 = sqrt(s2);
    vec3 hi = 0.662002687 * s1 + 0.684122060 * s2 - 0.323583601 * s3 - 0.0225411470 * c;
    return mix(hi, 12.92 * c, lessThanEqual(c, vec3(0.0031308)));
}

// Pixels per invocation, side by side in x. On lavapipe a dispatch of one invocation per pixel
// that returned at once still cost 12–15 ms at 1280x720; runs of 8 took the whole pass from
// 30–37 ms to 25–29 ms there (src/render/passes/composite.rs: RUN).
const int RUN = 8;

vec3 shade(vec2 uv) {
    if (pc.view == 3u) {
        return vec3(texture(dudv_map, uv * 4.0).rg, 0.0);
    }
    vec3 hdr;
    if (pc.view == 1u) {
        hdr = texture(reflection_colour, uv).rgb;
    } else if (pc.view == 2u) {
        hdr = texture(refraction_colour, uv).rgb;
    } else {
        hdr = texture(hdr_colour, uv).rgb;
    }
    return aces_fit(hdr * pc.exposure);
}

void main() {
    ivec2 size = imageSize(display);
    ivec2 first = ivec2(gl_GlobalInvocationID.x * RUN, gl_GlobalInvocationID.y);
    if (first.y >= size.y) {
        return;
    }
    for (int i = 0; i < RUN; ++i) {
        ivec2 p = first + ivec2(i, 0);
        if (p.x >= size.x) {
            break;
        }
        vec2 uv = (vec2(p) + 0.5) / vec2(size);
        vec4 encoded = vec4(srgb_encode(clamp(shade(uv), 0.0, 1.0)), 1.0);
        imageStore(display, p, pc.bgra != 0u ? encoded.bgra : encoded);
    }
}
