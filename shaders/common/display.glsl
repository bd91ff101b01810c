// What a scene fragment shader writes: linear HDR radiance into the reflection and refraction
// textures (the water samples and mixes them), display colour into the main target. The main
// target has the output's 8-bit sRGB format, so the attachment write does the sRGB encoding and
// the frame ends with one copy into the output (a blit at --render-scale < 1, bilinear, or when
// a recreated swapchain changed the byte order): tone mapping per fragment, at the scene's own
// resolution, instead of a full-screen pass.
//
// Tone map: the ACES filmic fit of Narkowicz (2015, "ACES Filmic Tone Mapping Curve"), exposure 1.

// Set per pipeline (SceneTarget in src/render/passes/mod.rs, DISPLAY_CONSTANT_ID there).
layout(constant_id = 8) const bool DISPLAY_TARGET = false;

vec3 aces_fit(vec3 x) {
    const float a = 2.51, b = 0.03, c = 2.43, d = 0.59, e = 0.14;
    return clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0, 1.0);
}

vec4 target_colour(vec3 radiance) {
    return vec4(DISPLAY_TARGET ? aces_fit(max(radiance, vec3(0.0))) : radiance, 1.0);
}
