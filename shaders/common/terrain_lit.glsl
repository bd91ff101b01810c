// Terrain and objects, lit by the sun (Lambert) and the sky (the sky cube), with the same
// distance haze as the water. Under the water the light is dimmed and tinted by the water it
// crossed (depth below the surface), so the refraction texture already shows a shallow bottom
// turning blue with depth; with TERRAIN_CAUSTICS defined (terrain/terrain_caustics.frag: the
// refraction view, and the main view from under the water) the waves focus the sun on it.
// terrain/terrain.frag, without them, reads nothing the simulation wrote: the reflection view
// draws it before the simulation's images are ready (src/render/frame.rs).
#include "common/frame.glsl"
#include "common/terrain.glsl"
#include "common/shore.glsl"
#include "common/display.glsl"
#include "common/underwater.glsl"
#include "common/shadow.glsl"
#include "common/terrain_material.glsl"
#ifdef TERRAIN_CAUSTICS
#include "common/water.glsl"
#include "common/caustics.glsl"
#endif

// The island's and the pillars' materials (common/terrain_material.glsl); off in the refraction
// view (src/render/passes/terrain.rs), which sees the sea floor, even without them, and paid
// 0.7 ms a frame for them at --quality low on lavapipe (which runs untaken branches).
layout(constant_id = 2) const bool TERRAIN_MATERIALS = true;
// Whether the pipeline draws pixels seen from under the water: the main view's when the camera
// is below the surface or at it (src/render/passes/terrain.rs picks the pipeline by the
// camera's side, as the water does); the reflection, the refraction and the main view from
// above never do (the reflection's and the refraction's terrain paid about 1 ms a frame for
// the untaken branch at --quality low on lavapipe).
layout(constant_id = 5) const bool TERRAIN_UNDERWATER = true;

layout(location = 0) in vec3 in_rel_pos;
layout(location = 1) in vec3 in_world;
layout(location = 2) in vec3 in_normal;
layout(location = 3) flat in int in_object;
layout(location = 4) in float in_sun_through; // the clouds' share of the sun (their shadows)
layout(location = 0) out vec4 out_colour;

// Wet sand over dry: water in the pores and a film on the grains send more of the light that
// enters the sand back into it, where it is absorbed (Lekner & Dorf 1988, "Why some things are
// darker when wet"); 0.68, the ratio of terrain.glsl's wet and dry sand (our choice).
const float WET_SAND = 0.68;

// The beach where the swash reaches (shore_swash of common/shore.glsl), over `colour`, the
// lit terrain (`light` the light on it, n its normal, v toward the eye). Below the set's
// largest run-up (Stockdon's R₂) the sand is damp; below what the last waves reached it is
// soaked: darker still, with a film that mirrors the sky (Schlick's Fresnel of water). Under
// the sheet: a few centimetres of water over the soaked sand, foam along its edge while it
// runs up (a band 0.6–2 m wide), lace behind the edge (fading over 3 m) as it drains.
vec3 beach(vec3 colour, vec3 light, vec3 n, vec3 v) {
    float y = in_world.y;
    float slope = clamp(sqrt(max(1.0 - n.y * n.y, 0.0)) / max(n.y, 0.05), 0.02, 0.5);
    float runup = shore_runup_m(frame.shore.x, max(frame.shore.y, 1e-3), slope);
    vec3 swash = shore_swash(in_world.xz, slope);
    float damp = 1.0 - smoothstep(0.85 * runup, 1.05 * runup, y);
    float soaked = 1.0 - smoothstep(swash.y - 0.03, swash.y + 0.03, y);
    colour *= mix(1.0, WET_SAND, max(0.5 * damp, soaked));
    float f = 0.02 + 0.98 * pow(1.0 - clamp(dot(n, v), 0.0, 1.0), 5.0);
    vec3 sky = f * sky_lookup(reflect(-v, n));
    colour += 0.5 * soaked * sky;
    // The sheet: its depth grows with the height below its edge (to 5 cm).
    float under = swash.x - y;
    float sheet = smoothstep(-0.005, 0.005, under);
    float depth = clamp(0.5 * under, 0.0, 0.05);
    vec3 water = colour * exp(-depth * ABSORPTION_PER_M) * (1.0 - f) + sky;
    float edge = under / slope; // metres from the edge, down the beach
    // The lace changes with each wave, at each point of the shore when its wave arrives.
    uint wave = uint(int(floor(frame.shore.w + shore_offset(in_world.xz))));
    float lace = 0.6 * shore_noise(in_world.xz, 0.5, wave) + 0.4 * shore_noise(in_world.xz, 0.17, wave);
    float foam = (1.0 - smoothstep(0.0, mix(0.6, 2.0, swash.z), edge)) * mix(0.6, 1.0, swash.z);
    foam = max(foam, 0.5 * exp(-edge / 3.0) * smoothstep(0.5, 0.75, lace)) * mix(0.7, 1.0, lace);
    vec3 white = 0.85 * light;
    return mix(colour, mix(water, white, clamp(foam, 0.0, 1.0)), sheet);
}

void main() {
    vec3 n = normalize(in_normal);
    vec3 sun = frame.sun_dir.xyz;
    float dist = length(in_rel_pos);
    // A pixel's footprint on the ground along the view, where it is longest (the detail's
    // noise fades by it: by the footprint across, grazing views streaked along the view).
    float facing = abs(dot(n, in_rel_pos)) / dist;
    float footprint_m = dist / (frame.lod.x * max(facing, 0.05));
    vec3 albedo;
    float occlusion = 1.0;
    if (in_object >= 4) {
        // The floating bodies (terrain/bodies.vert): a weathered wooden crate, a white boat,
        // a yellow buoy.
        const vec3 BODY_ALBEDO[3] = vec3[](vec3(0.42, 0.27, 0.13), vec3(0.80, 0.80, 0.78),
                                           vec3(0.85, 0.62, 0.06));
        albedo = BODY_ALBEDO[min(in_object - 4, 2)];
    } else if (in_object >= 0) {
        if (in_object == 0) {
            // Buoy: red and white bands 0.7 m high along its axis from its waterline (it floats:
            // objects.vert), so the bands move with it.
            vec3 waterline = vec3(frame.objects[0].x, frame.buoy.w, frame.objects[0].y);
            float along = dot(in_world - waterline, frame.buoy.xyz);
            albedo = fract(along / 1.4) < 0.5 ? vec3(0.75, 0.08, 0.05) : vec3(0.85);
        } else if (TERRAIN_MATERIALS) {
            albedo = pillar_albedo(in_world, frame.objects[in_object].xy, footprint_m);
        } else {
            albedo = vec3(0.45, 0.42, 0.38);
        }
    } else if (TERRAIN_MATERIALS) {
        island_surface(in_world, n, footprint_m, albedo, n, occlusion);
    } else {
        albedo = terrain_albedo(in_world.y, n.y);
    }
    // Lambertian under the sun through the air and clouds, and the sky (common/frame.glsl).
    // Under the water the sun comes down refracted (steeper), less what the surface reflects,
    // and focused by the waves (common/caustics.glsl); over the first half metre the two
    // blend, so the waterline's swash has no seam.
    float below = max(water_level() - in_world.y, 0.0);
    float drowned = smoothstep(0.0, 0.5, below);
    float lambert = max(dot(n, sun), 0.0);
    if (below > 0.0) {
        float under = max(dot(n, refracted_sun(sun)), 0.0) * sun_transmission(sun);
        lambert = mix(lambert, under, drowned);
    }
    // The sun's shadows (common/shadow.glsl); a point of the ground casts from the analytic
    // surface, half a metre up (the drawn lattice sags below it between its vertices).
    vec3 caster = in_world;
    if (in_object < 0) {
        caster.y = max(caster.y, terrain_height(caster.xz)) + 0.5;
    }
    float shadow = lambert > 0.0 ? sun_shadow(caster, in_object) : 1.0;
    float sun_share = lambert * shadow;
    // The light without the caustics: their local mean (they move light, common/caustics.glsl),
    // what the water's forward scattering leaves of them far from an eye under the water.
    float sun_mean = sun_share;
#ifdef TERRAIN_CAUSTICS
    // The refraction view, or the main view from under the water (above it, the main view's
    // drowned terrain lies under the water's surface); not with --caustics off.
    bool seen_drowned = (pass.view != 0u || (TERRAIN_UNDERWATER && pixel_underwater()))
                        && frame.underwater.z > 0.5;
    if (below > 0.0 && sun_share > 0.0 && seen_drowned) {
        // The point relative to the water grid's centre (camera-relative, as the water's).
        vec2 xz = in_rel_pos.xz + VIEW.eye.xz - frame.views[0].eye.xz + frame.water.xy;
        float pixel_m = dist / (frame.lod.x * sqrt(max(facing, 0.01)));
        sun_share *= mix(1.0, caustic(xz, below, dist, pixel_m), drowned);
    }
#endif
    vec3 ambient = sky_ambient(n) * occlusion;
    vec3 sun_light = frame.sun_light.rgb * in_sun_through;
    vec3 light = sun_light * sun_share / 3.14159265 + ambient;
    vec3 colour = albedo * light;
    vec3 blurred = albedo * (sun_light * sun_mean / 3.14159265 + ambient);
    // The swash's reach: R₂ is at most 1.1·(0.35·0.5 + ½·√(0.563·0.25 + 0.004))·√(H₀L₀) =
    // 0.402·√(H₀L₀) on the steepest beach beach() allows (a branch: most pixels skip it).
    float omega = max(frame.shore.y, 1e-3);
    float reach = 0.41 * sqrt(frame.shore.x * SHORE_TAU * SHORE_G / (omega * omega));
    if (in_object < 0 && in_world.y > -0.2 && in_world.y < reach) {
        colour = beach(colour, light, n, -in_rel_pos / dist);
        blurred = colour; // within 0.2 m of the surface: no caustics to blur
    }
    // Below the water: light attenuated on its way down (Beer-Lambert, depth below the surface).
    vec3 down = exp(-below * ABSORPTION_PER_M);
    colour *= down;
    if (TERRAIN_UNDERWATER && pass.view == 0u && pixel_underwater()) {
        vec3 dir = in_rel_pos / dist;
        vec3 seen = underwater_fog(colour, blurred * down, dir, dist);
#ifdef TERRAIN_CAUSTICS
        // (terrain.frag's pipelines never see from under the water: TERRAIN_UNDERWATER off.)
        seen += sun_shafts(dir, dist);
#endif
        out_colour = target_colour(seen);
        return;
    }
    vec3 horizon = sky_lookup(normalize(vec3(in_rel_pos.x, 0.0, in_rel_pos.z) + vec3(0.0, 0.02, 0.0)));
    vec3 haze = aerial_haze(dist);
    out_colour = target_colour(mix(colour, horizon, haze));
}
