// The procedural island: a shelf `frame.terrain.z` metres deep rising to a peak of PEAK_M at
// `frame.terrain.xy`, with a Gaussian profile of radius `frame.terrain.w` roughened by a few
// octaves of rotated sine ridges (deterministic, no textures). Past SHELF_EDGE_R island radii
// the floor slopes down to the open sea's (`frame.open_sea.x` deep) at SHELF_FOOT_R, flat (the
// ridges faded out) from there to the horizon. Mirrored on the CPU by `terrain_height` in
// src/render/scene.rs (tests use it to place cameras).
#include "shared.glsl" // PEAK_M, SHELF_EDGE_R, SHELF_FOOT_R (src/shared.rs)

// Whether `xz` lies within the slope's foot: beyond it the floor is flat at frame.open_sea.x.
bool near_island(vec2 xz) {
    vec2 d = (xz - frame.terrain.xy) / frame.terrain.w;
    return dot(d, d) < SHELF_FOOT_R * SHELF_FOOT_R;
}

float terrain_height(vec2 xz) {
    vec2 d = (xz - frame.terrain.xy) / frame.terrain.w;
    float r2 = dot(d, d);
    float island = exp(-r2 * 1.6);
    float slope = smoothstep(SHELF_EDGE_R, SHELF_FOOT_R, sqrt(r2));
    // Ridges: a fixed set of directions and frequencies (per island radius).
    float n = 0.0;
    n += 0.50 * sin(dot(d, vec2(3.1, 1.7)) + 0.4);
    n += 0.25 * sin(dot(d, vec2(-4.3, 6.1)) + 1.3);
    n += 0.12 * sin(dot(d, vec2(11.7, -7.9)) + 2.1);
    n += 0.06 * sin(dot(d, vec2(-19.3, -23.1)) + 0.7);
    float shelf = frame.terrain.z;
    float depth = mix(shelf, frame.open_sea.x, slope);
    return -depth + (shelf + PEAK_M) * island * (1.0 + 0.45 * n)
        + 1.5 * n * (1.0 - island) * (1.0 - slope);
}

// Surface colour of the terrain at a height and slope (1 = flat): sea-floor sand, beach, grass,
// rock on steep faces.
vec3 terrain_albedo(float y, float flatness) {
    vec3 sand = vec3(0.62, 0.55, 0.40);
    vec3 wet = vec3(0.42, 0.38, 0.28);
    vec3 grass = vec3(0.20, 0.33, 0.12);
    vec3 rock = vec3(0.36, 0.33, 0.30);
    vec3 c = y < -1.0 ? wet : sand;
    c = mix(c, grass, smoothstep(3.0, 7.0, y));
    return mix(rock, c, smoothstep(0.55, 0.8, flatness));
}
