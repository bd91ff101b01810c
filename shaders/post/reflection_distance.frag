#version 460
// The reflection's distances and the sky its objects hide (src/render/passes/
// reflection_distance.rs), per texel of the reflection's layer 0, into the reflection sky: the
// sky along the texel's ray of the mirrored view, as the reflection's sky pass draws it where
// nothing stands (its mirror image of the sun's disc left out there too), but everywhere; as
// alpha, the share of objects α (1 where something was drawn, 0 for the sky at the cleared
// depth 0) times u = log2(distance / near) = −log2(depth) (reversed Z: depth = near / distance).
// Blurred down its layers as the reflection's colour is, whose alpha is α (the sky draws 0
// there), the two alphas are the share of objects under a lookup's kernel and that share times
// their mean u, and the sky is what stands behind them (common/reflection.glsl). Texel for
// texel: both images are the reflection's size.
#include "common/frame.glsl"

layout(set = 1, binding = 0) uniform sampler2D reflection_depth;

layout(location = 1) in vec2 in_ndc;
layout(location = 0) out vec4 out_sky;

void main() {
    float depth = texelFetch(reflection_depth, ivec2(gl_FragCoord.xy), 0).r;
    out_sky = vec4(sky_lookup(view_ray(in_ndc)), depth > 0.0 ? -log2(depth) : 0.0);
}
