// What a scene fragment shader writes: linear HDR radiance into the reflection and refraction
// textures (the water samples and mixes them), display colour into the main target. The main
// target has the output's 8-bit sRGB format (or UNORM, encoded below), so the attachment write does the sRGB encoding and
// the frame ends with one copy into the output (a draw at --render-scale < 1, bilinear or
// edge-directed, or when a recreated swapchain changed the byte order): tone mapping per fragment, at the scene's own
// resolution, instead of a full-screen pass.
//
// Tone map: the ACES filmic fit of Narkowicz (2015, "ACES Filmic Tone Mapping Curve"), after the
// exposure the light calls for (frame.sky_light.w, src/render/atmosphere.rs `Sky::exposure`).

// Set per pipeline (SceneTarget in src/render/passes/mod.rs, DISPLAY_CONSTANT_ID there):
// 0 = linear HDR radiance; 1 = display colour into an sRGB format (the attachment encodes);
// 2 = display colour into a UNORM format (a window surface without an 8-bit sRGB format):
// encoded here with the sRGB transfer function (IEC 61966-2-1).
layout(constant_id = 8) const int DISPLAY_TARGET = 0;
// How much of the hue the tone map keeps: p⁴ / (p⁴ + 0.5⁴) of the brightest channel's exposed
// radiance p (a tenth at 0.3, half at 0.5, 94 % at 1). The hue-kept colour is darker than the
// per-channel one, so a blend that moved to it faster made brighter light look darker: over
// 0.4–1.5 by smoothstep, a saturated blue lost 13 % of its luminance as the exposure rose. With
// this weight, swept exposures of 300 random colours lose none (to 2·10⁻⁵).
const float TONE_HUE_MID4 = 0.0625;
// Where it starts turning white, where it is as white as it gets, and how white that is: a
// sun low enough to be orange keeps some of its colour.
const float TONE_WHITE_FROM = 3.0;
const float TONE_WHITE_FULL = 12.0;
const float TONE_WHITE_SHARE = 0.7;

vec3 aces_fit(vec3 x) {
    const float a = 2.51, b = 0.03, c = 2.43, d = 0.59, e = 0.14;
    return clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0, 1.0);
}

// The curve on each channel, as the fit is meant, where the colour is dark; in the highlights
// the brightest channel's curve scales all three, so a bright colour keeps its hue:
// per channel, an orange sky near a low sun (linear (4, 1.6, 0.3)) would map to a lemon
// yellow (0.95, 0.87, 0.37) as its red and green both near 1. Far brighter light (the sun's
// disc and its glitter) turns white, as it does in the eye and on film.
vec3 tone_map(vec3 x) {
    const float a = 2.51, b = 0.03, c = 2.43, d = 0.59, e = 0.14;
    float peak = max(max(x.r, x.g), x.b);
    float top = min((peak * (a * peak + b)) / (peak * (c * peak + d) + e), 1.0);
    vec3 hue_kept = x * (top / max(peak, 1e-6));
    float p4 = peak * peak * peak * peak;
    vec3 display = mix(aces_fit(x), hue_kept, p4 / (p4 + TONE_HUE_MID4));
    float white = TONE_WHITE_SHARE * smoothstep(TONE_WHITE_FROM, TONE_WHITE_FULL, peak);
    return mix(display, vec3(top), white);
}

vec3 srgb_encode(vec3 c) {
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}

vec4 target_colour(vec3 radiance) {
    if (DISPLAY_TARGET == 0) {
        return vec4(radiance, 1.0);
    }
    vec3 display = tone_map(max(radiance * frame.sky_light.w, vec3(0.0)));
    return vec4(DISPLAY_TARGET == 2 ? srgb_encode(display) : display, 1.0);
}

// A value shown as it is, without exposure or tone map (debug views whose numbers matter: the
// foam's reflectance in --view foam reads back exactly, to 8-bit sRGB rounding).
vec4 target_value(vec3 value) {
    vec3 v = clamp(value, 0.0, 1.0);
    return vec4(DISPLAY_TARGET == 2 ? srgb_encode(v) : v, 1.0);
}
