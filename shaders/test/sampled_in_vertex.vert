#version 460
// For tests/derived_barriers.rs only: a vertex shader that samples an image, the case the
// issue-31 review found (a texture read before the fragment stage). A full-screen triangle
// whose depth is the texture's red channel, so the read cannot be optimized away.
layout(set = 0, binding = 0) uniform sampler2D height;

void main() {
    vec2 uv = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
    float h = textureLod(height, vec2(0.5), 0.0).r;
    gl_Position = vec4(uv * 2.0 - 1.0, clamp(h, 0.0, 1.0), 1.0);
}
