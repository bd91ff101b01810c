#version 460
// Sky pass: every pixel gets the sky cubemap's radiance along its view ray (in the reflection
// view the ray is mirrored, so the reflection shows the sky the water reflects), and in the
// camera's view the sun's disc, anti-aliased over the pixel's angular size (1 / focal length)
// and limb-darkened (common/sky.glsl). The reflection view leaves the disc out: a mirror image
// of it was a second sharp sun in the water, whose sun is the specular term of water.frag. With
// the test background on (modes.w), the main view paints a solid colour found nowhere else.
// In the HDR targets its alpha is 0 (objects: 1).
#include "common/frame.glsl"
#include "common/display.glsl"
#include "common/sky.glsl"
#include "common/underwater.glsl"

// Whether this pipeline draws the main view, the one view that can look from under the water
// (src/render/passes/sky.rs): the reflection's leaves the branch out (lavapipe runs both sides).
layout(constant_id = 0) const bool SKY_UNDERWATER = true;

layout(location = 0) in vec2 in_uv;
layout(location = 1) in vec2 in_ndc;
layout(location = 0) out vec4 out_colour;

void main() {
    if (frame.modes.w == 1u && pass.view == 0u) {
        out_colour = target_colour(frame.background.rgb / frame.sky_light.w);
        return;
    }
    vec3 dir = view_ray(in_ndc);
    if (SKY_UNDERWATER && pass.view == 0u && pixel_underwater()) {
        // Under the water nothing is endless but the water itself, and the sun's light it
        // scatters (the light shafts).
        out_colour = target_colour(water_inscatter(dir) + sun_shafts(dir, 1e4));
        return;
    }
    float disc = pass.view == 0u ? sun_disc(dir, frame.sun_dir.xyz, 1.0 / frame.lod.x) : 0.0;
    // The disc through the air (the sun's light over its irradiance above it) and the clouds
    // (the cube's alpha along the ray).
    vec4 sky = textureLod(sky_cube, dir, 0.0);
    vec3 through_air = frame.sun_light.rgb / frame.light.z;
    out_colour = target_colour(sky.rgb + frame.light.x * through_air * sky.a * disc);
    // In the reflection and the refraction (HDR targets) alpha is the share of objects, 0 for
    // the sky (the terrain's pixels write 1): blurred down the reflection's layers, the share
    // under a lookup's kernel (common/reflection.glsl).
    if (DISPLAY_TARGET == 0) {
        out_colour.a = 0.0;
    }
}
