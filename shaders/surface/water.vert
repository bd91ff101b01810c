#version 460
// Flat water plane at y = 0: one camera-centred quad (two triangles, no vertex buffer) reaching
// far past the horizon haze. Positions are camera-relative (frame.glsl).
// Outputs: camera-relative position and world xz (for the ripple normals).
#include "common/frame.glsl"

layout(location = 0) out vec3 out_rel_pos;
layout(location = 1) out vec2 out_world_xz;

const float HALF_EXTENT_M = 40000.0;
const vec2 CORNERS[6] = vec2[](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1));

void main() {
    vec2 c = CORNERS[gl_VertexIndex] * HALF_EXTENT_M;
    vec3 rel = vec3(c.x, -frame.camera_pos.y, c.y);
    out_rel_pos = rel;
    out_world_xz = frame.camera_pos.xz + c;
    gl_Position = frame.view_proj * vec4(rel, 1.0);
}
