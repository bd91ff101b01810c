#version 460
// Anti-aliasing pass, first draw (`--aa fxaa`): copies the main colour into the anti-aliased
// target and marks the pixels FXAA will change, those whose local contrast reaches its edge
// thresholds (common/fxaa.glsl), with depth 0 (the rest 1). The second draw (post/fxaa.frag)
// is depth-tested against the mark, so the rasterizer skips its shader where no pixel is on an
// edge: lavapipe runs every pixel of a 4x4 block through the whole shader, branch or not.
#include "common/fxaa.glsl"

layout(location = 0) out vec4 out_colour;

void main() {
    ivec2 size = textureSize(display_colour, 0);
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec3 centre = texelFetch(display_colour, p, 0).rgb;
    out_colour = vec4(centre, 1.0);
    // The mark: 0 on an edge, 1 elsewhere; fxaa.frag, drawn at depth 0 with GREATER_OR_EQUAL,
    // runs where it is 0 (the scene's reversed-Z direction: NVIDIA's Z-cull keeps one).
    gl_FragDepth = on_edge(contrast(cross_at(p, size, centre))) ? 0.0 : 1.0;
}
