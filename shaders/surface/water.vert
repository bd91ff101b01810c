#version 460
// Ocean surface as a displaced grid (the tessellated tiles come with the rendering issue): a
// camera-centred grid whose spacing grows with distance (|u|^3 warp: 0.1 m cells under the camera,
// reaching 20 km), displaced by the sum of every cascade's displacement image at the vertex's
// world position. Positions are camera-relative (frame.glsl).
// Outputs: camera-relative position, undisplaced world xz (for the normal lookup).
#include "common/frame.glsl"

layout(location = 0) out vec3 out_rel_pos;
layout(location = 1) out vec2 out_world_xz;

const uint GRID = 192;           // quads per side
const float FAR_M = 20000.0;
const uvec2 CORNERS[6] = uvec2[](uvec2(0, 0), uvec2(1, 1), uvec2(1, 0), uvec2(0, 0), uvec2(0, 1), uvec2(1, 1));

vec3 ocean_displacement_at(vec2 world_xz, float dist) {
    vec3 d = vec3(0.0);
    int cascades = int(frame.ocean.x);
    for (int c = 0; c < cascades; ++c) {
        float weight;
        vec3 uv = ocean_uv(world_xz, c, dist, weight);
        d += weight * textureLod(ocean_displacement, uv, 0.0).xyz;
    }
    return d;
}

void main() {
    uint quad = uint(gl_VertexIndex) / 6u;
    uvec2 cell = uvec2(quad % GRID, quad / GRID) + CORNERS[uint(gl_VertexIndex) % 6u];
    vec2 u = vec2(cell) / float(GRID) * 2.0 - 1.0;
    vec2 offset = sign(u) * abs(u) * abs(u) * abs(u) * FAR_M;
    vec2 world_xz = frame.camera_pos.xz + offset;
    vec3 d = ocean_displacement_at(world_xz, length(offset));
    vec3 rel = vec3(offset.x + d.x, d.y - frame.camera_pos.y, offset.y + d.z);
    out_rel_pos = rel;
    out_world_xz = world_xz;
    gl_Position = frame.view_proj * vec4(rel, 1.0);
}
