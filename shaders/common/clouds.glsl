// The broken clouds' layer, CLOUD_BASE_M up (src/shared.rs): their shape, which the sky draws
// (common/sky.glsl, into the sky cube) and the sun's light on the sea, the island and the
// objects passes through (common/frame.glsl's `sun_light_at`: their shadows). The layer is
// anchored in the world: its point above (x, z) has the shape at (x, z) / CLOUD_SCALE_M. The
// cube is one picture for every eye, drawn from the origin; a camera far from it sees the
// same clouds overhead while their shadows stay where they fall.
// Included by frame.glsl and sky.glsl, both in one shader for the sky pass: hence the guard.
#ifndef CLOUDS_GLSL
#define CLOUDS_GLSL
#include "shared.glsl"
// CLOUD_SCALE_M (src/shared.rs): the horizontal scale of the noise's first octave's cells.

// Value noise in [0, 1] and its fractal sum (5 octaves), for the clouds' shapes.
float sky_hash(vec2 p) {
    vec3 q = fract(vec3(p.xyx) * 0.1031);
    q += dot(q, q.yzx + 33.33);
    return fract((q.x + q.y) * q.z);
}
float sky_noise(vec2 q) {
    vec2 i = floor(q);
    vec2 f = q - i;
    vec2 u = f * f * (3.0 - 2.0 * f);
    return mix(mix(sky_hash(i), sky_hash(i + vec2(1.0, 0.0)), u.x),
               mix(sky_hash(i + vec2(0.0, 1.0)), sky_hash(i + 1.0), u.x), u.y);
}
float cloud_shape(vec2 q) {
    float sum = 0.0;
    float amplitude = 0.5;
    for (int i = 0; i < 5; ++i) {
        sum += amplitude * sky_noise(q);
        q = mat2(1.6, 1.2, -1.2, 1.6) * q + 7.3;
        amplitude *= 0.5;
    }
    return sum / 0.96875;
}

// The noise in a space stretched along the wind (its unit vector `wind`, xz): cells `cells_m`
// (m) along it and across it, carried `drift` cells downwind, at `offset` (cells) from the
// clouds' place in it, at the world point xz (m): the natural slicks' and the gusts' patterns
// (common/slicks.glsl, gusts.glsl; `clouds::wind_shape` on the CPU).
float wind_shape(vec2 xz, vec2 wind, vec2 cells_m, float drift, vec2 offset) {
    vec2 q = vec2(dot(xz, wind) / cells_m.x - drift, dot(xz, vec2(-wind.y, wind.x)) / cells_m.y);
    return cloud_shape(q + offset);
}

// The share of the light the broken clouds stop at the layer's point `xz_m` (world, m), for
// `cover` (0–1) of the sky clouded, on a ray that travelled `dist` m from the sea to it: past
// ~20 km the cube cannot resolve their texture and only the mean cover is left (the sky's
// choice; the sun's light takes the same, so a low sun's light dims as its sky does).
float cloud_alpha(vec2 xz_m, float dist, float cover) {
    float shape = cloud_shape(xz_m / CLOUD_SCALE_M);
    float local = smoothstep(1.0 - cover, 1.0 - cover + 0.3, shape);
    float far = smoothstep(15e3, 60e3, dist);
    return mix(local, cover, far) * min(cover * 8.0, 1.0);
}

// The share of the sun's light the clouds let through to the world point `p` (m), the sun
// toward `sun`, `cover` of the sky clouded: the broken clouds' where the ray toward the sun
// meets their layer, and none under an overcast (from 7/8 of cover on they close into it).
float cloud_through(vec3 p, vec3 sun, float cover) {
    float dist = max(CLOUD_BASE_M - p.y, 0.0) / max(sun.y, 1e-3);
    float closed = smoothstep(0.85, 1.0, cover);
    return (1.0 - cloud_alpha(p.xz + sun.xz * dist, dist, cover)) * (1.0 - closed);
}
#endif
