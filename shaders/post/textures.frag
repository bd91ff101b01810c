#version 460
// Texture debug views (`--view reflection|refraction|dudv`): the reflection or refraction
// texture over the whole main target, or the DU/DV map tiled 4x (du in red, dv in green, as
// linear values). Drawn after the scene with shaders/common/fullscreen.vert; the textures are
// the water pass's set.
#include "common/frame.glsl"
#include "common/display.glsl"

layout(location = 0) in vec2 in_uv;
layout(location = 0) out vec4 out_colour;

layout(set = 1, binding = 0) uniform sampler2DArray reflection_colour; // layer 0: as drawn
layout(set = 1, binding = 1) uniform sampler2D refraction_colour;
layout(set = 1, binding = 3) uniform sampler2D dudv_map;

void main() {
    uint view = debug_view();
    if (view == VIEW_REFLECTION) {
        out_colour = target_colour(textureLod(reflection_colour, vec3(in_uv, 0.0), 0.0).rgb);
    } else if (view == VIEW_REFRACTION) {
        out_colour = target_colour(textureLod(refraction_colour, in_uv, 0.0).rgb);
    } else {
        out_colour = vec4(textureLod(dudv_map, in_uv * 4.0, 0.0).rg, 0.0, 1.0);
    }
}
