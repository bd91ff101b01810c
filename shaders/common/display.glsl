// What a scene fragment shader writes: linear HDR radiance into the reflection and refraction
// textures (the water samples and mixes them), display colour into the main target. The main
// target has the output's 8-bit sRGB format (or UNORM, encoded below), so the attachment write does the sRGB encoding and
// the frame ends with one copy into the output (a blit at --render-scale < 1, bilinear, or when
// a recreated swapchain changed the byte order): tone mapping per fragment, at the scene's own
// resolution, instead of a full-screen pass.
//
// Tone map: the ACES filmic fit of Narkowicz (2015, "ACES Filmic Tone Mapping Curve"), after the
// exposure the light calls for (frame.sky_light.w, src/render/atmosphere.rs `Sky::exposure`).

// Set per pipeline (SceneTarget in src/render/passes/mod.rs, DISPLAY_CONSTANT_ID there):
// 0 = linear HDR radiance; 1 = display colour into an sRGB format (the attachment encodes);
// 2 = display colour into a UNORM format (a window surface without an 8-bit sRGB format):
// encoded here with the sRGB transfer function (IEC 61966-2-1).
layout(constant_id = 8) const int DISPLAY_TARGET = 0;

vec3 aces_fit(vec3 x) {
    const float a = 2.51, b = 0.03, c = 2.43, d = 0.59, e = 0.14;
    return clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0, 1.0);
}

vec3 srgb_encode(vec3 c) {
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}

vec4 target_colour(vec3 radiance) {
    if (DISPLAY_TARGET == 0) {
        return vec4(radiance, 1.0);
    }
    vec3 display = aces_fit(max(radiance * frame.sky_light.w, vec3(0.0)));
    return vec4(DISPLAY_TARGET == 2 ? srgb_encode(display) : display, 1.0);
}

// A value shown as it is, without exposure or tone map (debug views whose numbers matter: the
// foam's reflectance in --view foam reads back exactly, to 8-bit sRGB rounding).
vec4 target_value(vec3 value) {
    vec3 v = clamp(value, 0.0, 1.0);
    return vec4(DISPLAY_TARGET == 2 ? srgb_encode(v) : v, 1.0);
}
