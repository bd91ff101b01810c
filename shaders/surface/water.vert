#version 460
// Ocean patches: instance r draws row r of the patch grid (common/water.glsl); vertex i is
// corner i % 4 of patch i / 4 of the row. No vertex buffers. Output: the corner's undisplaced
// xz relative to the grid's centre (camera-relative; common/water.glsl). (One instance per row: lavapipe drops patches of a draw whose tessellated output
// grows too large, so each instance stays small.)
#include "common/frame.glsl"
#include "common/water.glsl"

layout(location = 0) out vec2 out_xz;

const uvec2 CORNERS[4] = uvec2[](uvec2(0, 0), uvec2(1, 0), uvec2(1, 1), uvec2(0, 1));

void main() {
    uint patch_index = uint(gl_VertexIndex) / 4u;
    uvec2 cell = uvec2(patch_index, uint(gl_InstanceIndex)) + CORNERS[uint(gl_VertexIndex) % 4u];
    vec2 u = vec2(cell) / float(PATCHES) * 2.0 - 1.0;
    out_xz = vec2(warp(u.x), warp(u.y));
}
