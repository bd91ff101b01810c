#version 460
// Ocean vertices of the tessellated water: the point of the patch (bilinear in its corners),
// displaced and shaded as every water vertex is (common/water_vertex.glsl, shared with the
// clipmap's water_clipmap.vert).
#include "common/frame.glsl"
#include "common/water.glsl"
#include "common/terrain.glsl"
#include "common/shore.glsl"
#include "common/water_vertex.glsl"

layout(quads, fractional_odd_spacing, ccw) in;
layout(location = 0) in vec2 in_xz[];

// The patch, for `--view triangles`: its first corner's bits (gl_PrimitiveID restarts at each
// instance, and the patches are drawn a row an instance).
uint patch_id() {
    return floatBitsToUint(in_xz[0].x) * 0x27D4EB2Du ^ floatBitsToUint(in_xz[0].y);
}

void main() {
    vec2 uv = gl_TessCoord.xy;
    emit_water_vertex(lerp2(lerp2(in_xz[0], in_xz[1], uv.x),
                            lerp2(in_xz[3], in_xz[2], uv.x), uv.y),
                      patch_id(), vec2(0.0));
}
