#version 460
// The floating bodies (`--bodies`, src/ocean/bodies.rs), one instance each, lit by
// terrain.frag as the objects are (object ids 4 + shape: 4 a crate, 5 a boat, 6 a buoy).
// Instance i is bodies[3i..3i+3] (`Body::instance`): its shape's centre and shape, its
// orientation quaternion (x, y, z, w), its size. Shapes in their own frame (x along, y up):
// - 0, a box of that size (36 vertices);
// - 1, a small boat: a block over the rear two thirds and a wedge bow tapering to a stem over
//   the front third in plan (54);
// - 2, a buoy: an upright 12-sided prism of radius size.x and height size.y (144).
// The bodies come sorted by shape, one draw of its own vertex count each (src/render/passes/
// terrain.rs); vertices past a shape's own would collapse to a degenerate point.
#include "common/frame.glsl"

layout(std140, set = 0, binding = 6) uniform Bodies { vec4 bodies[3 * MAX_BODIES]; };

layout(location = 0) out vec3 out_rel_pos;
layout(location = 1) out vec3 out_world;
layout(location = 2) out vec3 out_normal;
layout(location = 3) flat out int out_object;
// The share of the sun's light the clouds above the vertex let through (frame.glsl's
// `sun_through_at`).
layout(location = 4) out float out_sun_through;

const uint SEGMENTS = 12u;
const float TAU = 6.28318530718;
// A quad's two triangles, as (u, v) corners.
const uvec2 QUAD[6] = uvec2[](uvec2(0, 0), uvec2(1, 0), uvec2(1, 1), uvec2(0, 0), uvec2(1, 1), uvec2(0, 1));

// v rotated by the unit quaternion q.
vec3 rotate(vec4 q, vec3 v) { return v + 2.0 * cross(q.xyz, cross(q.xyz, v) + q.w * v); }

// Vertex v (< 36) of the box from lo to hi: face v / 6 (−x, +x, −y, +y, −z, +z).
void box_vertex(uint v, vec3 lo, vec3 hi, out vec3 p, out vec3 n) {
    uint face = v / 6u;
    uint axis = face / 2u;
    float s = face % 2u == 0u ? -1.0 : 1.0;
    uvec2 c = QUAD[v % 6u];
    vec3 unit;
    unit[axis] = s;
    unit[(axis + 1u) % 3u] = c.x == 1u ? 1.0 : -1.0;
    unit[(axis + 2u) % 3u] = c.y == 1u ? 1.0 : -1.0;
    p = mix(lo, hi, unit * 0.5 + 0.5);
    n = vec3(0.0);
    n[axis] = s;
}

void main() {
    int i = gl_InstanceIndex;
    vec4 place = bodies[3 * i];
    vec4 q = bodies[3 * i + 1];
    vec3 size = bodies[3 * i + 2].xyz;
    uint shape = uint(place.w);
    uint v = uint(gl_VertexIndex);
    vec3 p = vec3(0.0);
    vec3 n = vec3(0.0, 1.0, 0.0);
    bool used = true;
    if (shape == 2u) {
        uint seg = v / 12u;
        uint k = v % 12u;
        float r = size.x;
        float h = size.y / 2.0;
        if (k < 6u) {
            uvec2 c = QUAD[k];
            float a = float(seg + c.x) / float(SEGMENTS) * TAU;
            vec2 dir = vec2(cos(a), sin(a));
            p = vec3(dir.x * r, c.y == 1u ? h : -h, dir.y * r);
            n = vec3(dir.x, 0.0, dir.y);
        } else {
            // The caps: fans of (centre, rim, next rim point), top then bottom.
            float y = k < 9u ? h : -h;
            uint j = (k - 6u) % 3u;
            float a = float(seg + (j == 2u ? 1u : 0u)) / float(SEGMENTS) * TAU;
            p = vec3(j == 0u ? vec2(0.0) : vec2(cos(a), sin(a)) * r, y).xzy;
            n = vec3(0.0, sign(y), 0.0);
        }
    } else if (v < 36u) {
        vec3 hi = size / 2.0;
        if (shape == 1u) {
            hi.x = size.x / 6.0; // the boat's block ends where its bow begins
        }
        box_vertex(v, -size / 2.0, hi, p, n);
    } else if (shape == 1u && v < 54u) {
        float l = size.x;
        float d = size.y / 2.0;
        float b = size.z / 2.0;
        uint w = v - 36u;
        if (w < 12u) {
            // The bow's sides, from the block's front corners to the stem.
            float s = w < 6u ? -1.0 : 1.0;
            uvec2 c = QUAD[w % 6u];
            p = vec3(c.x == 0u ? l / 6.0 : l / 2.0, c.y == 1u ? d : -d, c.x == 0u ? s * b : 0.0);
            n = normalize(vec3(b, 0.0, s * l / 3.0));
        } else {
            // Its deck and bottom.
            uint t = w - 12u;
            float y = t < 3u ? d : -d;
            uint k = t % 3u;
            p = k == 0u ? vec3(l / 6.0, y, -b) : k == 1u ? vec3(l / 6.0, y, b) : vec3(l / 2.0, y, 0.0);
            n = vec3(0.0, sign(y), 0.0);
        }
    } else {
        used = false;
    }
    vec3 world = place.xyz + rotate(q, p);
    if (!used) {
        world = place.xyz;
    }
    out_normal = rotate(q, n);
    out_world = world;
    out_sun_through = sun_through_at(world);
    out_object = 4 + int(shape);
    out_rel_pos = world - VIEW.eye.xyz;
    gl_ClipDistance[0] = dot(VIEW.clip_plane, vec4(world, 1.0));
    gl_Position = VIEW.view_proj * vec4(out_rel_pos, 1.0);
}
