#version 460
// Light shafts (common/caustics.glsl): for the main camera's ray through each texel of a small
// image (src/render/passes/shafts.rs), the caustics' mean area ratio along it over the first
// quarter, half, three quarters and all of SHAFT_REACH_M, which the scene's shaders under the
// water take up to their own distance (`sun_shafts`). Drawn only with the camera under the
// water (or half in it) and the caustics on. The casters' shadows darken them (SHAFT_SHADOWS;
// `--shadows`: src/render/passes/shafts.rs specializes common/shadow.glsl's SHADOWS).
#include "common/frame.glsl"
#include "common/underwater.glsl"
#include "common/water.glsl"
#include "common/terrain.glsl"
#include "common/shadow.glsl"
#define SHAFT_SHADOWS
#include "common/caustics.glsl"

layout(location = 1) in vec2 in_ndc;
layout(location = 0) out vec4 out_means;

void main() {
    out_means = shaft_means(view_ray(in_ndc), pixel_jitter());
}
