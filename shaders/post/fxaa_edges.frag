#version 460
// Anti-aliasing pass, first draw (`--aa fxaa`): copies the main colour into the anti-aliased
// target and marks the pixels FXAA will change, those whose local contrast reaches its edge
// thresholds (common/fxaa.glsl), with depth 1 (the rest 0). The second draw (post/fxaa.frag)
// is depth-tested against the mark, so the rasterizer skips its shader where no pixel is on an
// edge: lavapipe runs every pixel of a 4x4 block through the whole shader, branch or not.
#include "common/fxaa.glsl"

layout(location = 0) out vec4 out_colour;

void main() {
    ivec2 size = textureSize(display_colour, 0);
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec3 centre = texelFetch(display_colour, p, 0).rgb;
    out_colour = vec4(centre, 1.0);
    gl_FragDepth = on_edge(contrast(cross_at(p, size, centre))) ? 1.0 : 0.0;
}
