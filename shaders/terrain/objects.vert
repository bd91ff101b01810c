#version 460
// Objects in the water: one instance per `frame.objects` entry, each a capped cylinder
// (SEGMENTS around; 6 side + 3 cap vertices per segment). Absent objects (height 0) collapse to
// a degenerate point.
// - Objects 1–3, stone pillars: from the sea floor to their top height, upright.
// - Object 0, the buoy (src/ocean/buoy.rs; painted in stripes by terrain.frag): floating, from
//   BUOY_DRAFT_M below its waterline to `top height` above it, its axis frame.buoy.xyz (the
//   fitted surface normal), its waterline centre at (x, frame.buoy.w, z).
#include "common/frame.glsl"

layout(location = 0) out vec3 out_rel_pos;
layout(location = 1) out vec3 out_world;
layout(location = 2) out vec3 out_normal;
layout(location = 3) flat out int out_object;
// The share of the sun's light the clouds above the vertex let through (frame.glsl's
// `sun_through_at`).
layout(location = 4) out float out_sun_through;

const uint SEGMENTS = 20u;
const float TAU = 6.28318530718;

void main() {
    vec4 obj = frame.objects[gl_InstanceIndex];
    bool buoy = gl_InstanceIndex == 0;
    uint v = uint(gl_VertexIndex);
    uint seg = v / 9u;
    uint k = v % 9u;
    // In the object's own frame: y along its axis, from `bottom` to `top`.
    float bottom = buoy ? -BUOY_DRAFT_M : -frame.terrain.z - 2.0;
    vec3 local;
    vec3 normal;
    if (k < 6u) {
        // Side quad of segment `seg`: two triangles.
        const uvec2 SIDE[6] = uvec2[](uvec2(0, 0), uvec2(1, 0), uvec2(1, 1), uvec2(0, 0), uvec2(1, 1), uvec2(0, 1));
        uvec2 c = SIDE[k];
        float a = float(seg + c.x) / float(SEGMENTS) * TAU;
        vec2 dir = vec2(cos(a), sin(a));
        local = vec3(dir.x * obj.z, c.y == 1u ? obj.w : bottom, dir.y * obj.z);
        normal = vec3(dir.x, 0.0, dir.y);
    } else {
        // Top cap: a fan triangle (centre, two rim points).
        float a = float(seg + (k == 8u ? 1u : 0u)) / float(SEGMENTS) * TAU;
        float r = k == 6u ? 0.0 : obj.z;
        local = vec3(cos(a) * r, obj.w, sin(a) * r);
        normal = vec3(0.0, 1.0, 0.0);
    }
    mat3 rotation = buoy ? buoy_to_world() : mat3(1.0);
    vec3 origin = vec3(obj.x, buoy ? frame.buoy.w : 0.0, obj.y);
    vec3 world = origin + rotation * local;
    normal = rotation * normal;
    if (obj.w <= 0.0) {
        world = vec3(obj.x, bottom, obj.y);
    }
    out_normal = normal;
    out_world = world;
    out_sun_through = sun_through_at(world);
    out_object = gl_InstanceIndex;
    out_rel_pos = world - VIEW.eye.xyz;
    gl_ClipDistance[0] = dot(VIEW.clip_plane, vec4(world, 1.0));
    gl_Position = VIEW.view_proj * vec4(out_rel_pos, 1.0);
}
