// Per-frame uniforms shared by every scene pass (set 0, binding 0).
// Filled by src/render/frame_uniforms.rs (`FrameUniforms`, std140). Rendering is camera-relative:
// vertex positions are world positions minus camera_pos, so view_proj holds no translation.
layout(set = 0, binding = 0, std140) uniform FrameUniforms {
    mat4 view_proj;      // camera-relative world position -> clip space (reversed-Z, infinite far)
    mat4 inv_view_proj;  // clip space -> camera-relative position (used to build view rays)
    vec4 camera_pos;     // xyz: world camera position (m); w: simulation time (s)
    vec4 sun_dir;        // xyz: unit vector toward the sun; w: sun radiance scale
    vec4 viewport;       // xy: target size (px); zw: 1 / size
    vec4 patch_m;        // side of each ocean cascade's patch (m), cascades 0..3
    vec4 ocean;          // x: number of cascades; y: 1 for a bounded window (Gerstner); zw: origin (m)
} frame;

// The ocean simulation's images of this frame's slot, one layer per cascade (GENERAL layout,
// repeat sampler): (dx, h, dz, 0) and (dh/dx, dh/dz, Jacobian, foam).
layout(set = 0, binding = 1) uniform sampler2DArray ocean_displacement;
layout(set = 0, binding = 2) uniform sampler2DArray ocean_normals;

// Where cascade c's images hold world point xz: (xz - origin) / patch, repeating for the FFT
// cascades. `weight` fades a cascade out with distance before its waves alias, and a bounded
// (Gerstner) window toward its edges.
vec3 ocean_uv(vec2 world_xz, int c, float dist, out float weight) {
    float patch_m = frame.patch_m[c];
    vec2 uv = (world_xz - frame.ocean.zw) / patch_m;
    weight = clamp(2.0 - dist / (patch_m * 4.0), 0.0, 1.0);
    if (frame.ocean.y > 0.5) {
        vec2 q = abs(uv - 0.5);
        weight = 1.0 - smoothstep(0.35, 0.5, max(q.x, q.y));
    }
    return vec3(uv, c);
}

// World-space view ray through a pixel, from the fragment's normalized device coordinates.
vec3 view_ray(vec2 ndc) {
    vec4 p = frame.inv_view_proj * vec4(ndc, 0.5, 1.0);
    return normalize(p.xyz / p.w);
}
