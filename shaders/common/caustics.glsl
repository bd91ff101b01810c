// Caustics (issue 34): the sun's light on a point under the water, gathered and spread by the
// simulated waves above it (no texture). The sun's ray refracted at the surface point x, where
// the slope is s(x) = ∇h (the normal images' xy), reaches the depth d at
//     X(x) = x + d·q(s(x)),
// q the refracted ray's horizontal run per metre of descent (Snell's law). The light through
// a small patch of surface lands on the patch's image, so the irradiance there is the level
// sea's times the area ratio of the refracted grid,
//     1 / |det ∂X/∂x| = 1 / |det(I + d·Q·H)|,   Q = ∂q/∂s,  H = ∂s/∂x (the height's Hessian).
// A point p of the floor takes the ratio at the surface point whose ray lands on it, x = p −
// d·q(s(x)), approximated by one fixed-point step from the level sea's answer (the steps
// contract only until the rays first cross, |d·Q·H| < 1; past that focus p gathers light from
// several x and this takes one). So the ratio is sampled nearly uniformly over the surface,
// where the focusing patches weigh more than on the floor, and its mean over the floor is not
// 1: 1.97 on the calm shelf 16 m down. It is divided by that mean (caustic_mean), measured on
// the GPU over the sea as it is (shaders/underwater/caustic_means.frag) for the floor's depth
// and the pixel's footprint, so the caustics move the sun's light and do not make it.
//
// Left out: the surface's height and horizontal displacement (the ray starts at the rest
// position, at the mean level: centimetres on a calm sea) and the change of the surface's
// transmission with its slope.
//
// Needs common/frame.glsl and common/water.glsl (CASCADES, N_WATER, ocean_texture) before it.
// The sun's disc is 2·0.00465 rad across in the air (common/sky.glsl), 1/1.333 of it under the
// water near the vertical: a point d deep gets its light over an angle 0.007 wide, so a bundle
// of rays b across (the width the Hessian below is taken over) never narrows below d·0.007 m,
// and its area ratio has the floor d·0.007 / b. Deep floors get soft caustics, shallow ones
// sharp lines, as in a pool.
const float CAUSTIC_SUN_SPREAD = 0.007;
// The brightest a caustic gets, where the floor above does not bound it (the sun's image at
// a focus, blurred by the pixel).
const float CAUSTIC_MAX = 12.0;
// A wave of curvature κ focuses the sun about 1/((1 − 1/n)·κ) = 4/κ m down (a thin lens in
// water). Some focal lengths deeper the rays from many surface points cross at every point of
// the floor and the sun's disc blurs their images together: that wave's own pattern washes
// out, and the longer waves, which focus deeper, draw the network. So each cascade's
// curvature enters at most CAUSTIC_FOCI times its RMS focal depth, F = d·(1 − 1/n)·κ_rms,
// κ_rms = √(Σk⁴E) (frame.curvature_variance): a low-pass that keeps the cascade's longer
// waves, which focus deeper. With the normal images' mip levels (SLOPE_MIPS: medium, high)
// the slopes come from the level whose box is F / CAUSTIC_FOCI texels wide (at least one) and
// the Hessian from central differences ±1 texel of it; without them (low) the Hessian is
// taken by central differences ±F / CAUSTIC_FOCI texels of level 0 and, since those let the
// shorter waves through aliased, scaled by min(1, CAUSTIC_FOCI / F). Our choice (1.0): the
// network's lines are the first foci of the waves that focus near the floor. Without it the
// shortest waves, far past their foci, broke the floor into a speckle of dark rims around
// bright blobs (one branch of many crossing rays, taken at random).
const float CAUSTIC_FOCI = 1.0;
// Slope step of Q's central differences.
const float CAUSTIC_DS = 0.02;

// The refracted sun's horizontal run per metre of descent below a surface of slope s (the sun
// toward l, l.y > 0).
vec2 caustic_run(vec2 s, vec3 l) {
    vec3 n = normalize(vec3(-s.x, 1.0, -s.y));
    vec3 t = refract(-l, n, 1.0 / N_WATER);
    return t.xz / max(-t.y, 1e-3);
}

// The slopes at `uv` from mip level `lod` (trilinear) where the normal images have levels, from
// level 0 (bilinear) where they do not.
vec2 caustic_slope(vec3 uv, float lod) {
    return (SLOPE_MIPS ? ocean_texture_lod(ocean_normals, uv, lod)
                       : ocean_texture(ocean_normals, uv)).xy;
}

// The surface's slope at `x` (relative to the water grid's centre) and its Hessian ∂s/∂x, each
// cascade low-passed as CAUSTIC_FOCI says (the slope: the mean of the four samples its
// central differences take) and, where a pixel (`pixel_m` across, `dist` from the eye) cannot
// resolve its shortest waves, low-passed to the pixel (mip levels) or faded (level 0) as
// water.frag does its slopes: there its caustics would alias, so they average to the level
// sea's 1. `bundle_m`: the narrowest difference taken.
void caustic_surface(vec2 x, float depth, float dist, float pixel_m, out vec2 s, out mat2 hess,
                     out float bundle_m) {
    float texels = float(textureSize(ocean_normals, 0).x);
    s = vec2(0.0);
    hess = mat2(0.0);
    bundle_m = 1e9;
    for (int c = 0; c < CASCADES; ++c) {
        float weight;
        vec3 uv = ocean_uv(x, c, dist, weight);
        float patch_m = frame.patch_m[c];
        float foci = depth * (1.0 - 1.0 / N_WATER) * sqrt(frame.curvature_variance[c]);
        float widen = max(1.0, foci / CAUSTIC_FOCI);
        // `resolved`: how much of the cascade enters.
        float resolved;
        float lod = 0.0;
        if (SLOPE_MIPS) {
            // The level that box-filters the cascade to the waves focusing at most
            // CAUSTIC_FOCI deep, or to the pixel's footprint where that is coarser (water.frag's
            // level for it): a low-pass, where level 0's stencil only spread its samples and
            // the waves past its cutoff came through aliased. Past the last level the cascade
            // fades as water.frag's slopes do.
            lod = max(log2(widen),
                      log2(max(pixel_m, 1e-6) * texels / patch_m) - SLOPE_LOD_BIAS);
            widen = exp2(lod);
            resolved = weight * clamp(float(SLOPE_LEVELS) - lod, 0.0, 1.0);
        } else {
            resolved = weight * clamp(2.0 - pixel_m / cascade_shortest_m(c, texels), 0.0, 1.0)
                       * min(1.0, CAUSTIC_FOCI / max(foci, 1e-6));
        }
        vec2 step_uv = vec2(widen / texels, 0.0);
        vec2 sx0 = caustic_slope(uv - step_uv.xyy, lod);
        vec2 sx1 = caustic_slope(uv + step_uv.xyy, lod);
        vec2 sz0 = caustic_slope(uv - step_uv.yxy, lod);
        vec2 sz1 = caustic_slope(uv + step_uv.yxy, lod);
        float step_m = widen * patch_m / texels;
        s += resolved * 0.25 * (sx0 + sx1 + sz0 + sz1);
        hess += resolved / (2.0 * step_m) * mat2(sx1 - sx0, sz1 - sz0);
        bundle_m = resolved > 0.01 ? min(bundle_m, 2.0 * step_m) : bundle_m;
    }
}

// The area ratio 1 / |det(I + d·Q·H)| at depth `depth` under a surface point of slope `s` and
// Hessian `hess` (caustic_surface), the sun's disc and CAUSTIC_MAX bounding it.
float caustic_area_ratio(vec2 s, mat2 hess, float bundle_m, float depth) {
    vec3 l = frame.sun_dir.xyz;
    vec2 dx = vec2(CAUSTIC_DS, 0.0);
    vec2 dz = vec2(0.0, CAUSTIC_DS);
    mat2 dq = mat2(caustic_run(s + dx, l) - caustic_run(s - dx, l),
                   caustic_run(s + dz, l) - caustic_run(s - dz, l))
              / (2.0 * CAUSTIC_DS);
    float det = abs(determinant(mat2(1.0) + depth * dq * hess));
    float spread = depth * CAUSTIC_SUN_SPREAD / bundle_m;
    return 1.0 / max(det, max(spread, 1.0 / CAUSTIC_MAX));
}

// The area ratio at the surface point whose refracted ray lands on the floor at `xz`
// (relative to the water grid's centre), `depth` m under the mean level, found from the level
// sea's answer by `steps` − 1 fixed-point steps (with the same low-passed slopes, so a step
// does not scatter neighbouring pixels). `dist`: its distance from the eye; `pixel_m`: the
// floor's footprint in a pixel there. Its mean over the floor is not 1 (see the top).
float caustic_raw(vec2 xz, float depth, float dist, float pixel_m, int steps) {
    vec3 l = frame.sun_dir.xyz;
    vec2 s = vec2(0.0);
    mat2 hess;
    float bundle_m;
    for (int i = 0; i < steps; ++i) {
        caustic_surface(xz - depth * caustic_run(s, l), depth, dist, pixel_m, s, hess, bundle_m);
    }
    return caustic_area_ratio(s, hess, bundle_m, depth);
}

// The texel of the measured means (caustic_means, frame set binding 8) for a floor `depth` m
// under the mean level seen in pixels `pixel_m` across: two texels an octave of depth, one an
// octave of footprint (src/shared.rs).
vec2 caustic_mean_texel(float depth, float pixel_m) {
    return vec2(2.0 * log2(max(depth, 1e-6) / CAUSTIC_MEAN_DEPTH0_M),
                log2(max(pixel_m, 1e-6) / CAUSTIC_MEAN_PIXEL0_M));
}

#ifndef CAUSTIC_MEANS_PASS
// The mean of caustic_raw over the floor at this depth and footprint (r: one fixed-point step;
// g: none), interpolated between the measured texels (and clamped to the table's edges).
float caustic_mean(float depth, float pixel_m, int steps) {
    vec2 size = vec2(CAUSTIC_MEAN_DEPTHS, CAUSTIC_MEAN_PIXELS);
    vec2 uv = (caustic_mean_texel(depth, pixel_m) + 0.5) / size;
    vec2 means = textureLod(caustic_means, uv, 0.0).rg;
    return max(steps > 1 ? means.r : means.g, 1e-3);
}

// The sun's irradiance on the floor at `xz`, over the level sea's: caustic_raw over its mean.
float caustic_ratio(vec2 xz, float depth, float dist, float pixel_m, int steps) {
    return caustic_raw(xz, depth, dist, pixel_m, steps) / caustic_mean(depth, pixel_m, steps);
}

// The floor's: one fixed-point step.
float caustic(vec2 xz, float depth, float dist, float pixel_m) {
    return caustic_ratio(xz, depth, dist, pixel_m, 2);
}

// Light shafts: the sun's single scattering along the ray from an eye under the water
// (common/underwater.glsl's sun_scatter) with the caustics' focusing at each point: the
// shafts are the caustic network's bright lines drawn out along the refracted sun.
// shaders/underwater/shafts.frag marches the main camera's rays at a fixed low resolution
// (src/render/passes/shafts.rs) before the scene is drawn, through the first SHAFT_REACH_M
// metres in SHAFT_STEPS stretches, each taking the area ratio at a point `jitter` (0..1, per
// texel) along it, and keeps the ratio's mean, weighted by the light each stretch sends the eye,
// over the first quarter, half, three quarters and all of that reach (`shaft_means`). The scene
// shaders take the mean up to their own distance (`sun_shafts`). Past the reach the water has
// dimmed the light to e^-(a+b)·SHAFT_REACH_M (a fifth of the blue) and a level sea's is
// enough. A sample stands for its stretch, whose extent across the sun's rays (its length
// times the sine of its angle to them) is its footprint: the ratio is low-passed to that, so
// along the sun the shafts keep the caustics' detail and across it they do not alias. The ratio
// comes from the level sea's surface point (no fixed-point step: soft shafts need less than
// the floor) and is capped at SHAFT_MAX_RATIO, a sharp focus being a thin sheet the stretch
// mostly misses (our choice: without it single samples speckle). With SHAFT_SHADOWS defined
// (shaders/underwater/shafts.frag, which includes common/shadow.glsl) each sample also takes
// the share of the sun the casters leave its point (`sun_shadow`: the refracted sun's way up
// past the pillars and the buoy, then the island): the shadows of the objects and the island
// cut dark slabs out of the shafts, as they do in the water around a pier.
const int SHAFT_STEPS = 12;
const float SHAFT_MAX_RATIO = 3.0;

vec4 shaft_means(vec3 dir, float jitter) {
    float stretch = SHAFT_REACH_M / float(SHAFT_STEPS);
    float along = dot(dir, refracted_sun(frame.sun_dir.xyz));
    float across = stretch * sqrt(max(1.0 - along * along, 0.0));
    vec4 means = vec4(1.0);
    float light = 0.0;
    float gathered = 0.0;
    for (int i = 0; i < SHAFT_STEPS; ++i) {
        float s0 = stretch * float(i);
        float s = s0 + stretch * jitter;
        float depth = frame.underwater.y - s * dir.y;
        // The green's share (the channel the eye weighs most).
        float w = sun_scatter(dir, s0, s0 + stretch).g;
        float ratio = 1.0;
        if (depth > 0.0) {
            float pixel_m = max(across, s / frame.lod.x);
            ratio = min(caustic_ratio(frame.water.xy + s * dir.xz, depth, s, pixel_m, 1),
                        SHAFT_MAX_RATIO);
#ifdef SHAFT_SHADOWS
            ratio *= sun_shadow(frame.views[0].eye.xyz + s * dir, -1);
#endif
        }
        light += ratio * w;
        gathered += w;
        if ((i + 1) % (SHAFT_STEPS / 4) == 0) {
            means[(i + 1) / (SHAFT_STEPS / 4) - 1] = gathered > 0.0 ? light / gathered : 1.0;
        }
    }
    return means;
}
#endif
