#version 460
// Terrain: a grid of TERRAIN_QUADS² quads around the island (an indexed draw over its lattice), displaced by terrain_height
// (common/terrain.glsl); normals by central differences. Drawn in every view; the clip plane of
// the view (reflection: above the water, refraction: below) cuts it (seed 001 eq. 1–2).
// Outputs: eye-relative position, world position, normal.
#include "common/frame.glsl"
#include "common/terrain.glsl"

layout(location = 0) out vec3 out_rel_pos;
layout(location = 1) out vec3 out_world;
layout(location = 2) out vec3 out_normal;
layout(location = 3) flat out int out_object; // terrain.frag's object index; -1: terrain

void main() {
    // Indexed draw: gl_VertexIndex is a point of the (TERRAIN_QUADS + 1)² lattice, row by row.
    uint side = uint(TERRAIN_QUADS) + 1u;
    uvec2 cell = uvec2(uint(gl_VertexIndex) % side, uint(gl_VertexIndex) / side);
    vec2 u = vec2(cell) / float(TERRAIN_QUADS) * 2.0 - 1.0;
    float half_side = frame.terrain.w * TERRAIN_EXTENT;
    vec2 xz = frame.terrain.xy + u * half_side;
    float y = terrain_height(xz);
    float e = half_side / float(TERRAIN_QUADS);
    float hx = terrain_height(xz + vec2(e, 0.0)) - terrain_height(xz - vec2(e, 0.0));
    float hz = terrain_height(xz + vec2(0.0, e)) - terrain_height(xz - vec2(0.0, e));
    out_normal = normalize(vec3(-hx, 2.0 * e, -hz));
    vec3 world = vec3(xz.x, y, xz.y);
    out_world = world;
    out_object = -1;
    out_rel_pos = world - VIEW.eye.xyz;
    gl_ClipDistance[0] = dot(VIEW.clip_plane, vec4(world, 1.0));
    gl_Position = VIEW.view_proj * vec4(out_rel_pos, 1.0);
}
