#version 460
// Ocean vertices: the point of the patch (bilinear in its corners), displaced by every
// cascade's displacement image (repeat sampler, textureLod 0). Outputs: eye-relative position,
// undisplaced xz relative to the grid centre (normal lookups), the displacement (debug view).
#include "common/frame.glsl"
#include "common/water.glsl"

layout(quads, fractional_odd_spacing, ccw) in;
layout(location = 0) in vec2 in_xz[];
layout(location = 0) out vec3 out_rel_pos;
layout(location = 1) out vec2 out_xz;
layout(location = 2) out vec3 out_displacement;

void main() {
    vec2 uv = gl_TessCoord.xy;
    vec2 xz = lerp2(lerp2(in_xz[0], in_xz[1], uv.x),
                    lerp2(in_xz[3], in_xz[2], uv.x), uv.y);
    vec3 eye = water_eye();
    vec2 offset = xz - eye.xz;
    vec3 d = ocean_displacement_at(xz, length(offset));
    vec3 rel = vec3(offset.x + d.x, water_level() + d.y - eye.y, offset.y + d.z);
    out_rel_pos = rel;
    out_xz = xz;
    out_displacement = d;
    gl_Position = frame.views[0].view_proj * vec4(rel, 1.0);
}
