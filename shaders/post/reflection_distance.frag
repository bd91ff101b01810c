#version 460
// The reflection's distances (src/render/passes/reflection_distance.rs): per texel of the
// reflection's layer 0, the share of objects (1 where something was drawn, 0 for the sky at
// the cleared depth 0) and that share times u = log2(distance / near) = −log2(depth) (reversed
// Z: depth = near / distance). Blurred down its layers with the reflection's colour, the pair
// is the share of objects under a lookup's kernel and that share times their mean u
// (common/reflection.glsl). Texel for texel: both images are the reflection's size.
layout(set = 0, binding = 0) uniform sampler2D reflection_depth;

layout(location = 0) out vec2 out_distance;

void main() {
    float depth = texelFetch(reflection_depth, ivec2(gl_FragCoord.xy), 0).r;
    out_distance = depth > 0.0 ? vec2(1.0, -log2(depth)) : vec2(0.0);
}
