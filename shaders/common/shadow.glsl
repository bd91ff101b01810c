// The sun's shadows (issue 34): how much of the sun's disc a point sees past the island, the
// pillars and the buoy. The casters are all analytic (the island is terrain_height, the objects
// are the cylinders of terrain/objects.vert), so the shadow is a ray cast toward the sun in the
// fragment shader rather than a shadow map: no map to render, no resolution to run out of over
// the island's 2 km, no acne from a depth bias, and the same answer in every pass (the main
// view, the reflection, the refraction, and from under the water). Every pass that lights with
// the sun multiplies the sun's light by it: the terrain and the objects (terrain.frag), the
// water's sun terms (water.frag), the floor the surface mirrors from below (water.frag's
// `mirrored_floor`) and the light shafts (shaders/underwater/shafts.frag). `frame.light.w` is
// 0 with `--shadows off`.
//
// The sun is a disc SUN_ANGULAR_RADIUS across (common/sky.glsl); seen from a point, an edge
// that clears the line to the sun's centre by an angle a hides the share 0.5 − a / (2·radius)
// of it (a linear ramp across the disc, near enough to the exact circular segment for a
// penumbra a few pixels wide): penumbrae grow with the distance to the caster, as they do.
// The island's edge is found by marching the ray (TERRAIN_SHADOW_STEPS samples where it
// crosses the island), its step too coarse for the sun's own penumbra there, so the ramp is
// widened to the angle one step subtends at that distance (blurrier, not banded).
// Needs common/frame.glsl, common/terrain.glsl and common/underwater.glsl (refracted_sun) included
// before it (no include guards).

// Whether the pipeline casts shadows at all (`--shadows`, fixed for the run: the water's and
// the terrain's pipelines are specialized by it, src/render/passes). `frame.light.w == 0`
// alone returned early but did not save the work on Mesa 22.3's lavapipe, which runs both
// sides of a branch: the casts cost about 10 ms a frame at --quality low with the shadows off
// (water 8.8, refraction 0.9, scene 0.5 ms).
layout(constant_id = 4) const bool SHADOWS = true;

const int TERRAIN_SHADOW_STEPS = 32;
// The sun's angular radius, SUN_ANGULAR_RADIUS of common/sky.glsl (Allen: 0.533° across).
const float SUN_SHADOW_RADIUS = 0.00465;
// The island rises above the level sea within r_land of its radius, where terrain_height's
// hill with the ridges' largest +45 % meets the shelf's depth s: (s + PEAK_M)·1.45·e^(−1.6 r²)
// = s (1.02 radii for the 18 m shelf, 1.27 for 6 m); the march covers SHADOW_ISLAND_MARGIN
// radii more, so the drowned slope below a point in the shallows can shade it too.
const float SHADOW_ISLAND_MARGIN = 0.25;
// The objects' shape, as terrain/objects.vert draws them.
const float SHADOW_PILLAR_FOOT_M = 2.0; // below the sea floor

// The share of the sun's disc visible past a margin of `a` radians (< 0: the centre hidden),
// the disc seen `radius` across.
float disc_share(float a, float radius) {
    return clamp(0.5 + a / (2.0 * radius), 0.0, 1.0);
}

// The ray p + t·l (t > 0) against a capped cylinder along y (in its own frame) of radius r
// from `bottom` to `top`: the share of the sun left, by the largest of three margins (each an
// angle seen from p, < 0 when the ray is blocked that way): how far the ray passes outside
// the circle (its closest approach in xz less r, over the distance there), how far over the
// top it is where it enters the circle, and how far under the bottom where it leaves it (the
// ray rises toward the sun: lowest at the entry, highest at the exit).
float cylinder_share(vec3 p, vec3 l, float r, float bottom, float top, float sun_radius) {
    vec2 d = l.xz;
    float a = dot(d, d);
    if (a < 1e-8) {
        // Straight up: under the top or not.
        return length(p.xz) < r && p.y < top ? 0.0 : 1.0;
    }
    // Closest approach of the ray's xz to the axis (l is a unit vector: t is the distance).
    float tc = -dot(p.xz, d) / a;
    if (tc <= 0.0) {
        return 1.0; // the cylinder lies behind the point
    }
    float closest = length(p.xz + tc * d);
    float side = (closest - r) / tc;
    // The chord through the circle, in t (0 where the ray misses it).
    float half_chord = sqrt(max(r * r - closest * closest, 0.0) / a);
    float t_in = max(tc - half_chord, 1e-3);
    float t_out = tc + half_chord;
    // Heights across the ray: times cos of the sun's elevation, √a.
    float over = (p.y + t_in * l.y - top) * sqrt(a) / t_in;
    float under = (bottom - p.y - t_out * l.y) * sqrt(a) / t_out;
    return disc_share(max(side, max(over, under)), sun_radius);
}

// The share of the sun seen from world point `p` past the pillars and the buoy, their parts
// below the height `cap` (the water's, for a ray under it; else above every top); object
// `skip` (its own surface) is not tested (−1: none).
float objects_share(vec3 p, vec3 l, int skip, float cap) {
    float share = 1.0;
    for (int i = 0; i < 4; ++i) {
        vec4 obj = frame.objects[i];
        if (obj.w <= 0.0 || i == skip) {
            continue;
        }
        if (i == 0) {
            // The buoy: tilted along its axis frame.buoy.xyz about its waterline centre; the
            // ray goes into its frame (the inverse of a rotation is its transpose).
            vec3 centre = vec3(obj.x, frame.buoy.w, obj.y);
            mat3 to_local = transpose(buoy_to_world());
            share = min(share, cylinder_share(to_local * (p - centre), to_local * l, obj.z,
                                              -BUOY_DRAFT_M, min(obj.w, cap - frame.buoy.w),
                                              SUN_SHADOW_RADIUS));
        } else {
            vec3 q = p - vec3(obj.x, 0.0, obj.y);
            share = min(share, cylinder_share(q, l, obj.z, -frame.terrain.z - SHADOW_PILLAR_FOOT_M,
                                              min(obj.w, cap), SUN_SHADOW_RADIUS));
        }
    }
    return share;
}

// The share of the sun seen from world point `p` past the island: the ray marched where it
// crosses the island's circle below its highest possible ground.
float island_share(vec3 p, vec3 l) {
    float shelf = max(frame.terrain.z, 0.5);
    float land_r = sqrt(max(log((shelf + PEAK_M) * 1.45 / shelf) / 1.6, 0.0));
    float radius = (land_r + SHADOW_ISLAND_MARGIN) * frame.terrain.w;
    float highest = (frame.terrain.z + PEAK_M) * 1.45 - frame.terrain.z;
    float t_top = (highest - p.y) / l.y;
    vec2 o = p.xz - frame.terrain.xy;
    vec2 d = l.xz;
    float a = dot(d, d);
    float t0 = 0.0;
    float t1 = t_top;
    if (a > 1e-8) {
        float b = dot(o, d) / a;
        float disc = b * b - (dot(o, o) - radius * radius) / a;
        float root = sqrt(max(disc, 0.0));
        t0 = disc > 0.0 ? max(-b - root, 0.0) : 1.0;
        t1 = disc > 0.0 ? min(-b + root, t_top) : 0.0;
    } else if (dot(o, o) > radius * radius) {
        t1 = 0.0;
    }
    // A point on the ground starts on the analytic surface (the drawn lattice sags below it
    // between its vertices), plus half a metre.
    float step_m = (t1 - t0) / float(TERRAIN_SHADOW_STEPS);
    float share = 1.0;
    // A loop rather than a branch: where no pixel's ray crosses the island, lavapipe leaves it
    // at once (it runs both sides of an if).
    for (int i = 0; i < TERRAIN_SHADOW_STEPS && t1 > t0; ++i) {
        float t = t0 + (float(i) + 0.5) * step_m;
        vec3 q = p + t * l;
        float margin = (q.y - terrain_height(q.xz)) / t;
        share = min(share, disc_share(margin, max(SUN_SHADOW_RADIUS, step_m * l.y / t)));
    }
    return share;
}

// The share of the sun seen from world point `p` (on the object `skip`, −1 for none). Under
// the water the sunlight came down the refracted ray: past the objects' drowned parts to the
// surface, and from there as above it (the island's drowned slopes are left to the Lambert
// term).
float sun_shadow(vec3 p, int skip) {
    vec3 l = frame.sun_dir.xyz;
    if (!SHADOWS || frame.light.w == 0.0 || l.y <= 0.0) {
        return 1.0;
    }
    float share = 1.0;
    float depth = water_level() - p.y;
    if (depth > 0.0) {
        vec3 down = refracted_sun(l);
        share = objects_share(p, down, skip, water_level());
        p += depth / down.y * down;
    }
    return min(share, min(objects_share(p, l, skip, 1e9), island_share(p, l)));
}

// On the water: x the shadow at the surface point `p` (for the sun's glitter, its light
// through the crests and on the foam), y the shadow on the light the water body sends back up.
// That light was scattered at depths of metres, where the sun's refracted rays entered the sea
// nearer the sun than `p`: the shadow is the surface's averaged along the way. Its sources
// lie at depths weighted e^(−2cz) (down and back up; c ≈ 0.07/m between the blue's and the
// green's ABSORPTION_PER_M, a mean depth of 7 m), sampled at the midpoints of that
// exponential's eighths (0.45 to 19.4 m; four samples drew visible steps), each entering the
// sea z·tan θ_t toward the sun (θ_t
// the refracted sun's angle from the vertical, Snell's law with n = 1.333). So a pillar's
// narrow shadow greys the water only faintly, as on a real sea, while the island's, far wider
// than the light's path, darkens it in full (the island's share is taken once, at `p`).
vec2 water_shadow(vec3 p) {
    vec3 l = frame.sun_dir.xyz;
    if (!SHADOWS || frame.light.w == 0.0 || l.y <= 0.0) {
        return vec2(1.0);
    }
    float island = island_share(p, l);
    vec3 down = refracted_sun(l);
    const float DEPTHS_M[8] = float[](0.45, 1.44, 2.57, 3.92, 5.59, 7.69, 10.78, 19.41);
    float body = 0.0;
    for (int i = 0; i < 8; ++i) {
        vec2 entry = p.xz + down.xz * (DEPTHS_M[i] / down.y);
        body += 0.125 * objects_share(vec3(entry.x, p.y, entry.y), l, -1, 1e9);
    }
    return island * vec2(objects_share(p, l, -1, 1e9), body);
}
