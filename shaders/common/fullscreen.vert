#version 460
// Fullscreen triangle without vertex buffers: three vertices cover the viewport.
// Outputs: uv in [0,1] (y down, Vulkan convention) and ndc for ray reconstruction.
layout(location = 0) out vec2 out_uv;
layout(location = 1) out vec2 out_ndc;

void main() {
    vec2 uv = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
    out_uv = uv;
    out_ndc = uv * 2.0 - 1.0;
    gl_Position = vec4(out_ndc, 0.0, 1.0); // reversed-Z: depth 0 is the far plane
}
