#version 460
// Ocean vertices of the clipmap water (src/render/clipmap.rs, CDLOD after Strugar 2009): instance
// i is tile i of this frame's list, a square of Q² cells at its level's cell size (Q =
// tiles.grid.x); vertex v is lattice point (v mod (Q+1), v / (Q+1)) of it (an index buffer makes the
// triangles). Each vertex morphs toward the next coarser level's lattice as its distance from
// the camera goes from the level's morph start to its range: its odd world lattice
// coordinates slide onto the even neighbour below, so at the far end of a level its mesh is the next level's and
// tiles of two levels meet without cracks. Then it is displaced and shaded as every water
// vertex is (common/water_vertex.glsl, shared with the tessellated water.tese).
#include "common/frame.glsl"
#include "common/water.glsl"
#include "common/terrain.glsl"
#include "common/shore.glsl"
#include "common/water_vertex.glsl"

layout(set = 2, binding = 0, std430) readonly buffer Tiles {
    // x: cells per tile side (clipmap::Layout::quarter, this frame's; the draw binds the index
    // buffer of that size).
    uvec4 grid;
    // Per level: x the morph's start (m), y 1 / (its end - start); clipmap::MAX_LEVELS levels.
    vec4 morph[24];
    // Per tile: xy its corner relative to the grid centre (m), z its cell side (m), w its level
    // plus 64 and 128 where its corner's world lattice index is odd along x and z
    // (clipmap::Tile::packed_level).
    vec4 tile[];
} tiles;

void main() {
    vec4 t = tiles.tile[gl_InstanceIndex];
    uint v = uint(gl_VertexIndex);
    uint side = tiles.grid.x + 1u;
    uvec2 ij = uvec2(v % side, v / side);
    // Exact in f32: corners and cells are multiples of a power of two, a few km at most.
    vec2 xz = t.xy + vec2(ij) * t.z;
    vec3 eye = water_eye();
    float dist = length(vec3(xz.x - eye.x, water_level() - eye.y, xz.y - eye.z));
    uint packed = uint(t.w);
    vec2 m = tiles.morph[packed & 63u].xy;
    float k = clamp((dist - m.x) * m.y, 0.0, 1.0);
    // Odd by world index: the tile's own index plus its corner's parity.
    uvec2 odd = (ij + uvec2(packed >> 6u, packed >> 7u)) & 1u;
    emit_water_vertex(xz - vec2(odd) * (t.z * k), uint(gl_InstanceIndex), vec2(ij));
}
