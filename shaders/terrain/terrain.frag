#version 460
// Terrain and objects, lit by the sun (Lambert) and the sky (the sky cube), with the same
// distance haze as the water. Under the water the light is dimmed and tinted by the water it
// crossed (depth below the surface), so the refraction texture already shows a shallow bottom
// turning blue with depth.
#include "common/frame.glsl"
#include "common/terrain.glsl"
#include "common/display.glsl"
#include "common/underwater.glsl"

layout(location = 0) in vec3 in_rel_pos;
layout(location = 1) in vec3 in_world;
layout(location = 2) in vec3 in_normal;
layout(location = 3) flat in int in_object;
layout(location = 0) out vec4 out_colour;

void main() {
    vec3 n = normalize(in_normal);
    vec3 sun = frame.sun_dir.xyz;
    vec3 albedo;
    if (in_object >= 0) {
        if (in_object == 0) {
            // Buoy: red and white bands 0.7 m high along its axis from its waterline (it floats:
            // objects.vert), so the bands move with it.
            vec3 waterline = vec3(frame.objects[0].x, frame.buoy.w, frame.objects[0].y);
            float along = dot(in_world - waterline, frame.buoy.xyz);
            albedo = fract(along / 1.4) < 0.5 ? vec3(0.75, 0.08, 0.05) : vec3(0.85);
        } else {
            albedo = vec3(0.45, 0.42, 0.38);
        }
    } else {
        albedo = terrain_albedo(in_world.y, n.y);
    }
    // Lambertian under the sun through the air and clouds, and the sky (common/frame.glsl).
    float lambert = max(dot(n, sun), 0.0);
    vec3 colour = albedo * (sun_light() * lambert / 3.14159265 + sky_ambient(n));
    // Below the water: light attenuated on its way down (Beer-Lambert, depth below the surface).
    float below = max(water_level() - in_world.y, 0.0);
    colour *= exp(-below * ABSORPTION_PER_M);
    float dist = length(in_rel_pos);
    if (camera_underwater() && pass.view == 0u) {
        out_colour = target_colour(underwater_fog(colour, in_rel_pos / dist, dist));
        return;
    }
    vec3 horizon = sky_lookup(normalize(vec3(in_rel_pos.x, 0.0, in_rel_pos.z) + vec3(0.0, 0.02, 0.0)));
    float haze = 1.0 - exp(-dist / 9000.0);
    out_colour = target_colour(mix(colour, horizon, haze));
}
