#version 460
// Objects standing in the water: one instance per `frame.objects` entry, each a capped cylinder
// from the sea floor to its top height (SEGMENTS around; 6 side + 3 cap vertices per segment).
// Object 0 is the buoy (painted in stripes by terrain.frag). Absent objects (height 0)
// collapse to a degenerate point.
#include "common/frame.glsl"

layout(location = 0) out vec3 out_rel_pos;
layout(location = 1) out vec3 out_world;
layout(location = 2) out vec3 out_normal;
layout(location = 3) flat out int out_object;

const uint SEGMENTS = 20u;
const float TAU = 6.28318530718;

void main() {
    vec4 obj = frame.objects[gl_InstanceIndex];
    uint v = uint(gl_VertexIndex);
    uint seg = v / 9u;
    uint k = v % 9u;
    float bottom = -frame.terrain.z - 2.0;
    vec3 world;
    vec3 normal;
    if (k < 6u) {
        // Side quad of segment `seg`: two triangles.
        const uvec2 SIDE[6] = uvec2[](uvec2(0, 0), uvec2(1, 0), uvec2(1, 1), uvec2(0, 0), uvec2(1, 1), uvec2(0, 1));
        uvec2 c = SIDE[k];
        float a = float(seg + c.x) / float(SEGMENTS) * TAU;
        vec2 dir = vec2(cos(a), sin(a));
        world = vec3(obj.x + dir.x * obj.z, c.y == 1u ? obj.w : bottom, obj.y + dir.y * obj.z);
        normal = vec3(dir.x, 0.0, dir.y);
    } else {
        // Top cap: a fan triangle (centre, two rim points).
        float a = float(seg + (k == 8u ? 1u : 0u)) / float(SEGMENTS) * TAU;
        float r = k == 6u ? 0.0 : obj.z;
        world = vec3(obj.x + cos(a) * r, obj.w, obj.y + sin(a) * r);
        normal = vec3(0.0, 1.0, 0.0);
    }
    if (obj.w <= 0.0) {
        world = vec3(obj.x, bottom, obj.y);
    }
    out_normal = normal;
    out_world = world;
    out_object = gl_InstanceIndex;
    out_rel_pos = world - VIEW.eye.xyz;
    gl_ClipDistance[0] = dot(VIEW.clip_plane, vec4(world, 1.0));
    gl_Position = VIEW.view_proj * vec4(out_rel_pos, 1.0);
}
