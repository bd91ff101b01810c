// The island's surface (issue 34): its materials (terrain.glsl's terrain_albedo: sand, wet
// sand, grass, rock by height and slope) broken up by noise at two scales, with detail
// normals and an occlusion for the sky's light in hollows; and the pillars' concrete, streaked,
// with a band of algae along the waterline. No textures: value noise on a hash.
// Needs common/frame.glsl and common/terrain.glsl.

// pcg2d (Jarzynski & Olano 2020, "Hash Functions for GPU Rendering", JCGT 9(3)): two rounds
// of a linear congruential step, each coordinate mixed into the other, and a xor-shift.
uvec2 pcg2d(uvec2 v) {
    v = v * 1664525u + 1013904223u;
    v.x += v.y * 1664525u;
    v.y += v.x * 1664525u;
    v ^= v >> 16u;
    v.x += v.y * 1664525u;
    v.y += v.x * 1664525u;
    v ^= v >> 16u;
    return v;
}

// A value in [0, 1) per integer lattice point.
float lattice_value(ivec2 p) {
    return float(pcg2d(uvec2(p)).x) * (1.0 / 4294967296.0);
}

// Value noise at `p` (lattice units): x its value in [0, 1], yz its gradient, interpolated
// with the quintic 6t⁵ − 15t⁴ + 10t³ (continuous slopes, so the detail normals have no
// creases along the lattice).
vec3 value_noise(vec2 p) {
    vec2 i = floor(p);
    vec2 f = p - i;
    vec2 u = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
    vec2 du = 30.0 * f * f * (f * (f - 2.0) + 1.0);
    ivec2 c = ivec2(i);
    float a = lattice_value(c);
    float b = lattice_value(c + ivec2(1, 0));
    float d = lattice_value(c + ivec2(0, 1));
    float e = lattice_value(c + ivec2(1, 1));
    float k = a - b - d + e;
    return vec3(a + (b - a) * u.x + (d - a) * u.y + k * u.x * u.y,
                du * vec2(b - a + k * u.y, d - a + k * u.x));
}

// Fractal sum of `octaves` of value noise, the first `wavelength_m` long, each next one 2.03
// times shorter and half as strong, each faded out as a pixel `pixel_m` across stops
// resolving it (gone at two pixels a wavelength): x the sum in about [−1, 1], yz its gradient
// per metre. The octaves after the first one gone are not evaluated (all shorter, all gone):
// the far island's pixels skip most of them.
vec3 noise_fbm(vec2 xz, float wavelength_m, int octaves, float pixel_m) {
    vec3 sum = vec3(0.0);
    float amplitude = 0.5;
    float length_m = wavelength_m;
    for (int o = 0; o < octaves; ++o) {
        float seen = clamp(length_m / (2.0 * pixel_m) - 1.0, 0.0, 1.0);
        if (seen <= 0.0) {
            break;
        }
        vec3 n = value_noise(xz / length_m + vec2(17.3, 5.1) * float(o));
        sum += amplitude * seen * vec3(2.0 * n.x - 1.0, 2.0 * n.yz / length_m);
        amplitude *= 0.5;
        length_m /= 2.03;
    }
    return sum;
}

// The island at world point `p` with the lattice's normal `n`, seen by a pixel `pixel_m`
// across: `albedo`, the lit `normal` (the detail's bumps on it) and `occlusion`, the share of
// the sky a hollow still sees.
//   Patches (a 60 m noise): grass from green to dry, rock breaking through where the slope
//   or the height lets it, the grass line and the beach's edge wandering.
//   Detail (a 4 m noise, four octaves): clumps of grass, sand that varies, rock in strata
//   with cracks; its height (a few centimetres on sand and grass, 0.4 m on rock) bends the
//   normal.
//   Occlusion: how far the ground 8 m around lies above the point (the island's own height
//   function), a hollow 2 m deep seeing half the sky.
//   The sea floor (1 m down and deeper) stays even, without detail or occlusion: its pattern
//   is the caustics'.
void island_surface(vec3 p, vec3 n, float pixel_m, out vec3 albedo, out vec3 normal,
                    out float occlusion) {
    normal = n;
    occlusion = 1.0;
    if (p.y < -1.5) {
        // The sea floor: even (as below, where `drowned` is 1), and most of the refraction
        // view's pixels (the noise there cost lavapipe 1 ms a frame at low).
        albedo = terrain_albedo(p.y, n.y);
        return;
    }
    vec3 patches = noise_fbm(p.xz, 60.0, 3, pixel_m);
    vec3 detail = noise_fbm(p.xz, 4.0, 4, pixel_m);
    float flat_n = n.y;
    // Rock where the slope is steep or the peak high, the bounds wandering with the patches.
    float rock = 1.0 - smoothstep(0.62, 0.80, flat_n + 0.08 * patches.x + 0.04 * detail.x);
    rock = max(rock, smoothstep(36.0, 42.0, p.y + 6.0 * patches.x));
    float grass = smoothstep(2.5, 5.5, p.y + 2.5 * patches.x) * (1.0 - rock);
    float beach = (1.0 - grass) * (1.0 - rock);
    vec3 base = terrain_albedo(p.y + 2.0 * patches.x, 1.0);
    vec3 green = mix(vec3(0.17, 0.31, 0.10), vec3(0.33, 0.34, 0.15), smoothstep(-0.2, 0.5, patches.x));
    green *= 0.85 + 0.35 * detail.x;
    // Strata: light and dark bands a few metres high, bent by the patches; cracks darker.
    float strata = 0.5 + 0.5 * sin(p.y * 2.1 + 5.0 * patches.x);
    vec3 stone = mix(vec3(0.27, 0.25, 0.23), vec3(0.44, 0.41, 0.37), strata);
    stone *= 1.0 - 0.45 * smoothstep(0.15, 0.45, -detail.x);
    vec3 sand = base * (0.92 + 0.1 * detail.x);
    float drowned = 1.0 - smoothstep(-1.5, -0.5, p.y);
    albedo = mix(beach * sand + grass * green + rock * stone, terrain_albedo(p.y, n.y), drowned);
    float bump_m = mix(mix(0.03, 0.08, grass), 0.4, rock) * (1.0 - drowned);
    vec2 slope = bump_m * detail.yz;
    normal = normalize(n - vec3(slope.x, 0.0, slope.y) + n * dot(n.xz, slope));
    float around = 0.25 * (terrain_height(p.xz + vec2(8.0, 0.0)) + terrain_height(p.xz - vec2(8.0, 0.0))
                           + terrain_height(p.xz + vec2(0.0, 8.0)) + terrain_height(p.xz - vec2(0.0, 8.0)));
    occlusion = mix(clamp(1.0 - 0.25 * (around - terrain_height(p.xz)), 0.5, 1.0), 1.0, drowned);
}

// A noise on a pillar's side at `r` (from its axis, x z) and height `y` (stretched `stretch`
// times along the axis): two noises on the planes along its axis, each weighted by how
// squarely the side faces it (an angle around the axis would jump where it wraps: a seam).
float pillar_noise(vec2 r, float y, float wavelength_m, int octaves, float pixel_m) {
    float across_x = noise_fbm(vec2(r.y, y), wavelength_m, octaves, pixel_m).x;
    float across_z = noise_fbm(vec2(r.x + 31.0, y), wavelength_m, octaves, pixel_m).x;
    vec2 w = abs(r) / max(abs(r.x) + abs(r.y), 1e-6);
    return w.x * across_x + w.y * across_z;
}

// A pillar's concrete at world point `p`, its axis at `centre` (x, z): grey, streaked along
// its height by the rain (a noise stretched 20 times along the axis); from the water up to
// 1.1–1.5 m, where the waves wash it, a band of dark algae, and above it a metre of concrete
// the spray keeps damp (darker).
vec3 pillar_albedo(vec3 p, vec2 centre, float pixel_m) {
    vec2 r = p.xz - centre;
    float streaks = pillar_noise(r, p.y / 20.0, 1.5, 3, pixel_m);
    vec3 concrete = vec3(0.46, 0.45, 0.42) * (0.82 + 0.3 * streaks);
    float line = 1.3 + 0.3 * pillar_noise(r, 0.0, 2.0, 2, pixel_m);
    float above = p.y - water_level();
    concrete *= mix(0.7, 1.0, smoothstep(line, line + 1.0, above));
    float algae = 1.0 - smoothstep(line - 0.3, line, above);
    return mix(concrete, vec3(0.06, 0.08, 0.05), algae);
}
