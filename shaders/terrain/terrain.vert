#version 460
// Terrain: a grid of TERRAIN_QUADS² quads around the island (an indexed draw over its
// lattice), displaced by terrain_height (common/terrain.glsl); normals by central differences.
// The lattice is even over the island and its shelf and stretches to the horizon at its edges
// (terrain_warp), so the sea floor has no edge. Drawn in every view; the clip plane of
// the view (reflection: above the water, refraction: below) cuts it (seed 001 eq. 1–2), and
// so does a plane VISIBLE_DEPTH_M under the water.
// Outputs: eye-relative position, world position, normal.
#include "common/frame.glsl"
#include "common/terrain.glsl"

// Grid quads per side: specialized by TerrainPass (--terrain-grid, src/render/passes/terrain.rs;
// constants 0 and 1 are common/water.glsl's, which terrain.frag includes for the caustics).
layout(constant_id = 3) const int TERRAIN_QUADS = 160;
const float TERRAIN_EXTENT = 2.4;    // island radii per unit of lattice coordinate at the centre
const float TERRAIN_FAR_M = 20000.0; // the lattice's half-side (m): the water grid's FAR_M

// Lattice coordinate u in [-1, 1] -> island radii from the centre: TERRAIN_EXTENT·u, plus a
// u^15 term that is under 3 % of it for |u| ≤ 0.6 (1.4 radii: the island and its shores) and
// reaches TERRAIN_FAR_M at |u| = 1 (for the default island the slope down to the open sea lies
// at |u| = 0.7–0.8).
float terrain_warp(float u) {
    float a = abs(u);
    float far_r = TERRAIN_FAR_M / frame.terrain.w;
    return sign(u) * (TERRAIN_EXTENT * a + (far_r - TERRAIN_EXTENT) * pow(a, 15.0));
}

layout(location = 0) out vec3 out_rel_pos;
layout(location = 1) out vec3 out_world;
layout(location = 2) out vec3 out_normal;
layout(location = 3) flat out int out_object; // terrain.frag's object index; -1: terrain
// The share of the sun's light the clouds above the vertex let through (frame.glsl's
// `sun_through_at`).
layout(location = 4) out float out_sun_through;

void main() {
    // Indexed draw: gl_VertexIndex is a point of the (TERRAIN_QUADS + 1)² lattice, row by row.
    uint side = uint(TERRAIN_QUADS) + 1u;
    uvec2 cell = uvec2(uint(gl_VertexIndex) % side, uint(gl_VertexIndex) / side);
    vec2 u = vec2(cell) / float(TERRAIN_QUADS) * 2.0 - 1.0;
    vec2 xz = frame.terrain.xy + vec2(terrain_warp(u.x), terrain_warp(u.y)) * frame.terrain.w;
    float y = terrain_height(xz);
    float e = frame.terrain.w * TERRAIN_EXTENT / float(TERRAIN_QUADS);
    float hx = terrain_height(xz + vec2(e, 0.0)) - terrain_height(xz - vec2(e, 0.0));
    float hz = terrain_height(xz + vec2(0.0, e)) - terrain_height(xz - vec2(0.0, e));
    out_normal = normalize(vec3(-hx, 2.0 * e, -hz));
    vec3 world = vec3(xz.x, y, xz.y);
    out_world = world;
    out_sun_through = sun_through_at(world);
    out_object = -1;
    out_rel_pos = world - VIEW.eye.xyz;
    gl_ClipDistance[0] = dot(VIEW.clip_plane, vec4(world, 1.0));
    // Nothing deeper than VISIBLE_DEPTH_M is drawn: no light comes back from there.
    gl_ClipDistance[1] = y - water_level() + VISIBLE_DEPTH_M;
    gl_Position = VIEW.view_proj * vec4(out_rel_pos, 1.0);
}
