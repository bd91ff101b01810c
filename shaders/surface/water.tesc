#version 460
// Ocean patch LOD and culling. Each edge's level is its screen-space length over the target
// edge length (frame.lod.y px), from the edge's own two corners only, so the two patches
// sharing an edge pick the same level (no cracks). Corners are relative to the grid centre. Patches whose bounds, enlarged by the
// largest displacement (frame.lod.z), lie outside the view frustum get level 0 (discarded).
#include "common/frame.glsl"
#include "common/water.glsl"

layout(vertices = 4) out;
layout(location = 0) in vec2 in_xz[];
layout(location = 0) out vec2 out_xz[];

const float MAX_LEVEL = 63.0;

float edge_level(vec2 a, vec2 b) {
    vec3 mid = vec3(0.5 * (a.x + b.x), water_level(), 0.5 * (a.y + b.y)) - water_eye();
    float dist = max(length(mid), 1e-3);
    float px = distance(a, b) * frame.lod.x / dist;
    return clamp(px / frame.lod.y, 1.0, MAX_LEVEL);
}

bool outside_frustum() {
    float m = frame.lod.z;
    vec2 lo = min(min(in_xz[0], in_xz[1]), min(in_xz[2], in_xz[3])) - m;
    vec2 hi = max(max(in_xz[0], in_xz[1]), max(in_xz[2], in_xz[3])) + m;
    vec3 eye = water_eye();
    // Count, per clip plane, the box corners outside it; all 8 outside one plane: culled.
    int out_l = 0, out_r = 0, out_b = 0, out_t = 0, out_n = 0;
    for (int i = 0; i < 8; ++i) {
        vec3 p = vec3((i & 1) == 0 ? lo.x : hi.x,
                      water_level() + ((i & 2) == 0 ? -m : m),
                      (i & 4) == 0 ? lo.y : hi.y);
        vec4 c = frame.views[0].view_proj * vec4(p - eye, 1.0);
        out_l += c.x < -c.w ? 1 : 0;
        out_r += c.x > c.w ? 1 : 0;
        out_b += c.y < -c.w ? 1 : 0;
        out_t += c.y > c.w ? 1 : 0;
        out_n += c.z > c.w ? 1 : 0; // reversed-Z: in front of the near plane is z <= w
    }
    return out_l == 8 || out_r == 8 || out_b == 8 || out_t == 8 || out_n == 8;
}

void main() {
    out_xz[gl_InvocationID] = in_xz[gl_InvocationID];
    if (gl_InvocationID == 0) {
        if (outside_frustum()) {
            gl_TessLevelOuter[0] = 0.0;
            gl_TessLevelOuter[1] = 0.0;
            gl_TessLevelOuter[2] = 0.0;
            gl_TessLevelOuter[3] = 0.0;
            gl_TessLevelInner[0] = 0.0;
            gl_TessLevelInner[1] = 0.0;
        } else {
            // Quad domain edges: outer 0 is u = 0 (corners 0-3), 1 is v = 0 (0-1),
            // 2 is u = 1 (1-2), 3 is v = 1 (3-2).
            float e0 = edge_level(in_xz[0], in_xz[3]);
            float e1 = edge_level(in_xz[0], in_xz[1]);
            float e2 = edge_level(in_xz[1], in_xz[2]);
            float e3 = edge_level(in_xz[3], in_xz[2]);
            gl_TessLevelOuter[0] = e0;
            gl_TessLevelOuter[1] = e1;
            gl_TessLevelOuter[2] = e2;
            gl_TessLevelOuter[3] = e3;
            gl_TessLevelInner[0] = max(e1, e3);
            gl_TessLevelInner[1] = max(e0, e2);
        }
    }
}
