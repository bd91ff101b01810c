#version 460
// Ocean surface shading (seed 001 §3.3–3.6, seed 003, seed 004):
// - normal from the simulation's slopes (summed over cascades, each fading out with distance);
// - reflection and refraction textures at this pixel's screen position, offset by a scrolling
//   DU/DV map (seed 001 eq. 4–5) plus the normal's slope; both offsets fade with distance;
// - water depth along the view ray from the refraction depth texture, Beer-Lambert colour;
// - Fresnel weight between reflection and refraction (`--fresnel`: Schlick, exact (seed 004),
//   or seed 001 eq. 6 r = cos θ^0.5);
// - the sun's glitter (a Beckmann lobe of the slopes the pixel does not resolve), foam from the
//   simulation and the surf where the waves break on the shallows (common/shore.glsl), haze
//   toward the horizon.
// Every texture here has one mip level, so lookups are textureLod(…, 0): the same result as
// texture() (minification and magnification filters are both linear) without the per-quad
// derivatives and LOD a CPU driver computes for it. The cascade loop's bound is the
// specialization constant of common/water.glsl.
#include "common/frame.glsl"
#include "common/water.glsl"
#include "common/display.glsl"
#include "common/terrain.glsl"
#include "common/shore.glsl"
#include "common/underwater.glsl"
#include "common/shadow.glsl"
#include "common/caustics.glsl"
#include "common/glitter.glsl"
#include "common/gusts.glsl"

layout(location = 0) in vec3 in_rel_pos;
layout(location = 1) in vec2 in_xz;
layout(location = 2) in vec3 in_displacement;
layout(location = 3) in vec2 in_shore; // water.tese: the water's depth (m) and K_s
layout(location = 4) in float in_sun_through; // water_vertex.glsl: the clouds' share of the sun
layout(location = 5) flat in vec3 in_sky_zenith; // and the frame's sky radiance at the zenith
layout(location = 6) in vec4 in_surf; // water_vertex.glsl: the bores' phase, share, gradient
layout(location = 7) in vec2 in_patches; // water_vertex.glsl: a slick's share, a gust's g here
layout(location = 8) in vec3 in_horizon; // water_vertex.glsl: the sky at the horizon behind P
layout(location = 9) in vec3 in_edge_sky; // and the sky past the reflection's edge
layout(location = 10) flat in uint in_tile; // water_vertex.glsl: the tile or patch
layout(location = 11) in vec2 in_lattice; // and the point on its lattice of cells
layout(location = 0) out vec4 out_colour;

// Which side the main view sees the surface from (src/render/passes/water.rs, `WaterSide`):
// 0 above, 1 below (the pipeline that draws it from under the water), 2 either, pixel by
// pixel, where the surface crosses the near plane (the picture splits at the waterline).
layout(constant_id = 2) const int UNDERWATER_VIEW = 0;
// Whether this pipeline draws the debug views (`--view displacement`, `normals`, `foam`,
// `wireframe`: src/render/passes/water.rs, `WaterPass::draw`); the final picture's pipelines
// leave their branches out (lavapipe ran them at every pixel: 0.6 ms a frame at `low`).
layout(constant_id = 3) const bool DEBUG_VIEWS = false;

// Layer 0: the reflection as drawn; layer l: blurred over 2^l rows in its top H / 2^l rows
// (Recorder::halve_down_layers); common/reflection.glsl looks it up.
// Alpha: the share of objects (the sky draws 0 there, the terrain and objects 1).
layout(set = 1, binding = 0) uniform sampler2DArray reflection_colour;
layout(set = 1, binding = 1) uniform sampler2D refraction_colour;
layout(set = 1, binding = 2) uniform sampler2D refraction_depth;
layout(set = 1, binding = 3) uniform sampler2D dudv_map;
// The sky behind the objects; alpha: their share times their log2 distance.
layout(set = 1, binding = 4) uniform sampler2DArray reflection_sky;
#include "common/reflection.glsl"

// WATER_COLOUR (c_o: deep water, seen through nothing) and ABSORPTION_PER_M (red absorbed
// first) come from src/shared.rs.
const float F0 = 0.02;               // ((n - 1) / (n + 1))^2
const float DUDV_STRENGTH = 0.012;   // screen-space offset at full strength
const float SLOPE_STRENGTH = 0.05;   // screen-space offset per unit slope
const float PI = 3.14159265;
// The diffuse reflectance of a thick layer of clean foam (its bubbles absorb almost nothing in
// the visible, so a thick layer is near white; 0.85, our choice), scaled by the lace's 0.4–1.
const float FOAM_ALBEDO = 0.85;
// Height of the foam's relief (m), as a height field the lace's 0–1 scales: the residual
// layer's bubbles and lace a few centimetres thick; the breaking layer's froth, a crest
// tumbling over itself, in heaps of tens of centimetres. Both our choice: the froth's
// 0.4 m gives a moderate sea's opaque whitecaps, lit by a low sun, the variation of their
// own light the foam test asks (tests/foam.rs: 0.17, up from 0.15 with 0.15 m everywhere).
const float FOAM_RELIEF_M = 0.15;
const float FROTH_RELIEF_M = 0.4;

// The summed normal, its slopes scaled as the shallows scale the waves (`scale`), and the
// whitecap field (layer 0's foam: the whole surface's, see src/ocean/foam.rs), faded with the
// largest cascade. `resolved`: the covariance of the slopes those faded, scaled cascades carry
// along the view and across it (`slope_covariance`'s order), each cascade's by its waves'
// directions (the wind's waves are steeper along the wind than across it).
// A cascade's slopes also fade where the pixel's footprint on the water passes its shortest
// wavelength (gone at twice that), before they alias into shimmer: its band ends at 6 waves
// per next patch (L_{c+1}/6 = L_c/26, spectrum.rs's cascades), the last one at its Nyquist
// limit (2 texels). The footprint is longer along the view than across it (`footprint`: x
// along, y across, m; `along`: the view's direction over the water), 1/sin e times at an
// elevation e: the slopes along the view fade by the one, those across by the other (an
// anisotropic filter, as LEAN mapping's per-axis variances; Bruneton, Neyret & Holzschuch 2010
// filter along and across the view alike). With one footprint for both (their geometric
// mean), grazing views kept slopes along the view that their pixels cannot hold, and the sea
// a few hundred metres out broke into one-pixel filaments. What fades out joins the glitter's
// unresolved slopes, per direction.
// `compression`: how much the waves whose crests the light can cross squeeze the water
// together here, Σ w_c (1 − J_c) (J_c each cascade's Jacobian, 0 on a flat sea): cascade 1
// (waves of 3.5–15 m at the default 400 m patch, crests a few metres thick) in full, cascade
// 0 (15–400 m) at half, the smaller ones not at all (their ripples hold too little water to
// glow, and their compression drew the glow as a sparkling net).
vec4 ocean_normal_foam(vec2 xz, float dist, vec2 footprint, vec2 along, float scale,
                       out vec3 resolved, out float compression) {
    vec2 across = vec2(-along.y, along.x);
    vec2 slope = vec2(0.0);
    compression = 0.0;
    float foam = 0.0;
    resolved = vec3(0.0);
    float texels = float(textureSize(ocean_normals, 0).x);
    for (int c = 0; c < CASCADES; ++c) {
        float weight;
        vec3 uv = ocean_uv(xz, c, dist, weight);
        // In a natural slick (common/slicks.glsl) the film damps the cascade's short waves.
        float slick = mix(1.0, frame.slick_cascades[c], in_patches.x);
        // `w`: how much of the slopes looked up is drawn, along the view and across it;
        // `kept`: the root-mean-square share of the cascade's slopes that is.
        // `s_along`, `s`: the slopes looked up for along the view and across it.
        vec2 w, kept;
        vec4 s_along, s;
        if (SLOPE_MIPS) {
            // The levels that blur as much as the pixel does, along the view and across it:
            // the slopes along the view from the one, those across it from the other.
            vec2 lod = max(log2(footprint * texels / frame.patch_m[c]) - SLOPE_LOD_BIAS, 0.0);
            s_along = ocean_texture_lod(ocean_normals, uv, lod.x);
            s = ocean_texture_lod(ocean_normals, uv, lod.y);
            w = weight * slick * clamp(float(SLOPE_LEVELS) - lod, 0.0, 1.0);
            kept = w * vec2(mip_gain(frame.slope_mips, c, lod.x),
                             mip_gain(frame.slope_mips, c, lod.y));
        } else {
            s = ocean_texture(ocean_normals, uv);
            s_along = s;
            w = weight * clamp(2.0 - footprint / cascade_shortest_m(c, texels), 0.0, 1.0) * slick;
            kept = w;
        }
        slope += w.x * dot(s_along.xy, along) * along + w.y * dot(s.xy, across) * across;
        foam += c == 0 ? weight * s.w : 0.0;
        vec2 a = vec2(frame.slope_anisotropy[0][c], frame.slope_anisotropy[1][c]);
        resolved += vec3(kept * kept, kept.x * kept.y)
                    * slope_covariance(frame.slope_variance[c], a, along);
        compression += (c == 0 ? 0.5 : (c == 1 ? 1.0 : 0.0)) * weight * (1.0 - s.z);
    }
    slope += wake_at(xz).yz;
    slope *= scale;
    resolved *= scale * scale;
    return vec4(normalize(vec3(-slope.x, 1.0, -slope.y)), foam);
}

float fresnel(float cos_theta); // below

// Schlick's approximation to the Fresnel reflectance at incidence cos θ = c: F0 + (1 − F0)(1 − c)⁵
// (powers by multiplication: pow() is an exp2 of a log2).
float schlick(float c) {
    float m = 1.0 - c;
    float m2 = m * m;
    return F0 + (1.0 - F0) * m2 * m2 * m;
}

// Smith's masking for the Beckmann distribution, at a direction whose cosine to the normal is
// `c`, from the mean-square slope σ² of the facets in that direction's plane (Walter et al.
// 2007's rational fit, eq. 27, with their α² = 2σ²).
float smith_g1(float c, float sigma2) {
    float a = c / sqrt(2.0 * sigma2 * max(1.0 - c * c, 1e-6));
    return a < 1.6 ? (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a) : 1.0;
}

// The sun's reflection off the slopes a pixel does not resolve (Bruneton, Neyret & Holzschuch
// 2010): the facets around the drawn normal n have Gaussian (Beckmann) slopes of covariance m
// along the view (the direction `along` over the water) and across it (`beckmann_lobe`, common/
// glitter.glsl), so the radiance toward v is E·F(v·h)·D(h)·G/(4 n·v), each direction's masking
// from the mean square in its plane, uᵀMu for its azimuth u.
float sun_glitter(vec3 n, vec3 v, vec3 l, vec2 along, vec3 m) {
    vec3 h = normalize(v + l);
    float nv = max(dot(n, v), 1e-4);
    float nl = max(dot(n, l), 0.0);
    float d = beckmann_lobe(n, h, along, m);
    // The sun's azimuth in the view's frame: its plane's mean square.
    vec2 l_flat = l.xz / max(length(l.xz), 1e-6);
    vec2 u = vec2(dot(l_flat, along), dot(l_flat, vec2(-along.y, along.x)));
    float sigma2_l = u.x * u.x * m.x + u.y * u.y * m.y + 2.0 * u.x * u.y * m.z;
    float g = smith_g1(nv, m.x) * smith_g1(max(nl, 1e-4), sigma2_l) * step(1e-4, nl);
    return fresnel(clamp(dot(v, h), 0.0, 1.0)) * d * g / (4.0 * nv);
}

// Value noise in [0, 1] on a lattice that repeats every `cells` cells (hash of the lattice
// corners, smooth interpolation).
float hash12(vec2 p) {
    vec3 q = fract(vec3(p.xyx) * 0.1031);
    q += dot(q, q.yzx + 33.33);
    return fract((q.x + q.y) * q.z);
}
// A lattice index (a whole number) wrapped into [0, cells): half a cell off the boundaries, so a
// division rounded either way gives the same whole number (mod() on floats may not).
vec2 wrap_cell(vec2 i, float cells) { return i - cells * floor((i + 0.5) / cells); }

float periodic_noise(vec2 q, float cells) {
    vec2 i = floor(q);
    vec2 f = q - i;
    vec2 u = f * f * (3.0 - 2.0 * f);
    vec2 a = wrap_cell(i, cells);
    vec2 b = wrap_cell(i + 1.0, cells);
    return mix(mix(hash12(a), hash12(vec2(b.x, a.y)), u.x),
               mix(hash12(vec2(a.x, b.y)), hash12(b), u.x), u.y);
}

// The whitecaps' foam field F at the rest position xz (m from the water grid's centre): the
// lattice's `lattice` (layer 0 of the normal images), or the residual foam near the camera
// where it is denser (src/ocean/simulation/foam_sim.rs: left by the whitecaps, drifting
// downwind, gathered into windrows), from its finest level, each level fading into the next
// over its outer tenth. (The simulation's own whitecap field, at 0.25 m, feeds the residual
// foam but is not drawn yet: resolved so finely its whitecaps are thin crest lines, a third of
// the lattice's opaque foam at the moderate sea, and the shading's thresholds are tuned to the
// lattice's.)
float foam_at(vec2 xz, float lattice) {
    int count = int(frame.foam_levels[0].w);
    float residual = 0.0;
    for (int l = count - 1; l >= 0; --l) {
        vec4 level = frame.foam_levels[l];
        vec2 uv = level.xy + xz * level.z;
        vec2 q = abs(uv - 0.5);
        float inside = 1.0 - smoothstep(0.4, 0.49, max(q.x, q.y));
        residual = mix(residual, textureLod(foam_field, vec3(uv, float(l)), 0.0).y, inside);
    }
    return max(lattice, residual);
}

// One octave of foam texture at about `per_m` cells per metre over the largest cascade's patch
// (`uv` its image coordinates): a whole number of cells per patch, so the texture repeats with
// the waves and stays put on the water however far the camera goes.
float foam_octave(vec2 uv, float per_m, float seed) {
    float cells = max(1.0, round(frame.patch_m.x * per_m));
    return periodic_noise(uv * cells + seed, cells);
}

// Distance from q to the nearest wall of a cellular (Worley) pattern, one jittered point per
// lattice cell, repeating every `cells` cells: F2 − F1 of the distances to the two nearest points.
float cell_walls(vec2 q, float cells) {
    vec2 i = floor(q);
    vec2 f = q - i;
    float d1 = 8.0;
    float d2 = 8.0;
    for (int y = -1; y <= 1; ++y) {
        for (int x = -1; x <= 1; ++x) {
            vec2 c = vec2(x, y);
            vec2 cell = wrap_cell(i + c, cells);
            vec2 p = c + vec2(hash12(cell), hash12(cell + 57.0)) - f;
            float d = dot(p, p);
            d2 = min(d2, max(d, d1));
            d1 = min(d1, d);
        }
    }
    return sqrt(d2) - sqrt(d1);
}

// Whitecap foam, from the field F (src/ocean/foam.rs: 1 where a crest is breaking, e^(−age/τ)
// after it passed). foam_lace is its texture (0–1) at the rest position whose largest-cascade
// image coordinates are `uv` (so it rides with the water), `pixel_m` the pixel's footprint on
// the water (m); foam_layer turns F and the lace into the layer's reflectance R (how much of the
// water it whitens); foam_light is the light it sends back.
//
// Two layers by age (Sea of Thieves' approach, SIGGRAPH 2018): the breaking layer, where the
// crest broke within about 1.3 s, dense after 0.4 s; the residual layer, a lace (2.5 m rafts, a
// cellular network of bubble walls 0.5 m across, 0.2 m bubbles; whole periods per patch) whose
// thin parts the age eats first, so a whitecap thins into strands and holes and fades as F
// decays (nothing pops). Each scale fades to its mean before it would alias, and the layer then
// takes its average over the lace: far foam is coverage, not specks (Dupuy & Bruneton 2012
// filter foam the same way).
float foam_lace(vec2 uv, float pixel_m, out float detail) {
    float coarse = clamp(1.5 - pixel_m * 0.4, 0.0, 1.0);
    float mid = clamp(1.5 - pixel_m * 4.0, 0.0, 1.0);
    float fine = clamp(1.5 - pixel_m * 5.0, 0.0, 1.0);
    float rafts = mix(0.5, foam_octave(uv, 0.4, 0.0), coarse);
    // The lace: the walls between bubbles about 0.5 m across (a cellular network, its lattice
    // bent by the value noise so no row of cells lines up), thinning away from them; averaged
    // about 0.15.
    float cells = max(1.0, round(frame.patch_m.x * 2.0));
    // Two octaves serve twice: the bend, the walls' width and where they break.
    float a = foam_octave(uv, 0.8, 3.0);
    float b = foam_octave(uv, 1.2, 23.0);
    vec2 bend = vec2(a, b) - 0.5;
    // Walls of varying width, broken here and there: lace, not a crackle glaze.
    float width = mix(0.08, 0.45, a);
    float walls = 1.0 - smoothstep(0.0, width, cell_walls(uv * cells + 1.5 * bend, cells));
    walls *= smoothstep(0.25, 0.65, b);
    float net = mix(0.15, walls, mid);
    float bubbles = mix(0.5, foam_octave(uv, 5.0, 31.0), fine);
    detail = mid;
    return smoothstep(0.15, 0.85, 0.45 * rafts + 0.3 * net + 0.25 * bubbles);
}

// The foam layer's reflectance R for the field F and the lace there; `detail` (1 near, 0 far)
// says how much of the lace's small scales the pixel resolves.
float foam_layer(float field, float lace, float detail) {
    // The breaking layer: F from 0.6 (1.3 s after the crest passed) to 0.85 (0.4 s), its
    // bubbles letting some water show through, solid where the crest breaks now (F > 0.9).
    float solid = smoothstep(0.9, 1.0, field);
    float breaking = smoothstep(0.6, 0.85, field) * mix(0.5 + 0.5 * lace, 1.0, solid);
    // The residual layer: the age erodes the lace from its thin parts (the threshold rises as
    // 1 − F^½: at F = 1 everything above 0 is foam, at F = 0.1 only the top of the strands;
    // a soft edge of ±0.12), and what is left thins with F.
    float keep = smoothstep(-0.12, 0.12, lace - (1.0 - sqrt(field)));
    float residual = 0.6 * field * keep * (0.4 + 0.6 * lace);
    // Where the pixel no longer resolves the lace (its scales faded to their mean), the same
    // layer on average: for lace spread evenly over [0, 1], a share √F of it is kept, with a
    // mean lace of 1 − √F/2 there. Far foam keeps its coverage instead of vanishing.
    float kept = sqrt(field);
    float average = 0.6 * field * kept * (0.4 + 0.6 * (1.0 - 0.5 * kept));
    return max(breaking, mix(average, residual, detail));
}

// The foam layer's reflectance: the whitecaps' (field `foam.x`) under the gusts here
// (common/gusts.glsl), the surf's and the boat's white water (`foam.y`) as the waves make it.
// foam_layer rises with F: without gusts, foam_layer of the greater field, as it was.
float foam_opacity(vec2 foam, float lace, float detail) {
    return max(gust_foam(foam_layer(foam.x, lace, detail), in_patches.y),
               foam_layer(foam.y, lace, detail));
}

// Henyey–Greenstein phase function (per steradian) at the cosine `mu` of the scattering angle.
float henyey_greenstein(float mu, float g) {
    return (1.0 - g * g) / (4.0 * PI * pow(1.0 + g * g - 2.0 * g * mu, 1.5));
}

#include "common/crest_light.glsl"

// The light foam sends toward the eye (v) at normal n, under the sun (direction l, light
// `sunlight`) and the sky: a bright scattering medium, not a flat wall. A thick layer of bubbles
// gives back nearly all the light that enters it, spread about as a Lambert surface (the sun by
// its cosine, the sky over the hemisphere around n); its bubbles also stand out of the surface,
// so they catch the light that grazes it, which a flat Lambert surface would not: half again of
// the sun through a Henyey–Greenstein lobe (g = 0.5: bubbles scatter forward, so foam between
// the eye and a low sun glows) and of the sky along the horizon behind it (`horizon`). White
// under white light, and at sunset as warm and bright as the sky around it. `lace`: thicker
// foam is whiter, its thin lace greyer.
vec3 foam_light(vec3 n, vec3 v, vec3 l, vec3 sunlight, vec3 horizon, float lace) {
    vec3 surface = sunlight * max(dot(n, l), 0.0) / PI + sky_ambient_under(n, in_sky_zenith);
    vec3 sides = sunlight * henyey_greenstein(dot(-l, v), 0.5) + horizon;
    return FOAM_ALBEDO * (0.4 + 0.6 * lace) * (surface + 0.5 * sides);
}

// Fraction of light reflected at incidence cos θ (θ between normal and view). Every model in
// a few multiplications and at most one square root: lavapipe runs all three, whichever the
// uniform picks (it evaluates both sides of a branch), twice a pixel (here and in the glitter).
float fresnel(float cos_theta) {
    uint model = frame.modes.y;
    float c = clamp(cos_theta, 1e-4, 1.0);
    if (model == FRESNEL_EXACT) {
        // The exact unpolarised Fresnel equations (seed 004 §2.5) for a dielectric, written
        // without angles (Cook & Torrance 1982, eq. in their appendix; Walter et al. 2007,
        // eq. 22): g = √(n² − 1 + c²), F = ½ (g−c)²/(g+c)² · (1 + (c(g+c) − 1)²/(c(g−c) + 1)²),
        // the same as ½ (sin²(θt−θi)/sin²(θt+θi) + tan²(θt−θi)/tan²(θt+θi)) with Snell's θt.
        float g = sqrt(N_WATER * N_WATER - 1.0 + c * c);
        float a = (g - c) / (g + c);
        float b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
        return clamp(0.5 * a * a * (1.0 + b * b), 0.0, 1.0);
    }
    if (model == FRESNEL_POWER) {
        // Seed 001 eq. 6: r_refract = θ^r with r = 0.5, θ taken as cos θ = N·V (the angle itself
        // would make straight-down views fully reflective).
        return 1.0 - sqrt(c);
    }
    // Schlick's approximation.
    return schlick(c);
}

// The share of the sky a rough sea reflects toward the eye at cos θ = c of its drawn normal,
// whose unresolved slopes have a standard deviation σ_V along the view (Bruneton, Neyret &
// Holzschuch 2010, §4: the Fresnel factor averaged over the visible facets of a Gaussian slope
// distribution, their fit F̄ ≈ (1 − c)^(5·exp(−2.69 σ_V)) / (1 + 22.7 σ_V^1.5)), written as
// Schlick's F0 + (1 − F0)·F̄ so a smooth sea (σ_V → 0) gets Schlick back. At grazing views the
// facets the eye sees lean toward it, so a rough sea reflects well below the mirror's Fresnel
// and the sea under the horizon is darker than the sky above it. The other models (`--fresnel`
// exact or power, the seeds' own) stay as they are, for comparison.
float sea_fresnel(float c, float sigma_v) {
    if (frame.modes.y != FRESNEL_SCHLICK) {
        return fresnel(c);
    }
    float m = 1.0 - clamp(c, 0.0, 1.0);
    float mean = pow(m, 5.0 * exp(-2.69 * sigma_v)) / (1.0 + 22.7 * sigma_v * sqrt(sigma_v));
    return F0 + (1.0 - F0) * mean;
}

// The sea floor (the island's terrain) that the surface point `p` (relative to the eye) mirrors
// along the ray `r` going down, seen through the water between: the ray marched in
// MIRROR_STEPS to at most MIRROR_REACH_M (where a + b leaves e^-4 of the blue) and the crossing
// refined by halving; the floor lit as terrain_lit.glsl lights it (the refracted sun focused
// by the caustics and past the casters' shadows, the sky, the light's absorption on the way
// down).
// Where the ray meets no floor: the water's own light.
const int MIRROR_STEPS = 8;
const float MIRROR_REACH_M = 40.0;
const float MIRROR_BLUR = 32.0;
vec3 mirrored_floor(vec3 p, vec3 r) {
    vec3 start = frame.views[0].eye.xyz + p;
    float step_m = MIRROR_REACH_M / float(MIRROR_STEPS);
    float hit = -1.0;
    for (int i = 1; i <= MIRROR_STEPS && hit < 0.0; ++i) {
        vec3 q = start + r * (step_m * float(i));
        if (q.y < terrain_height(q.xz)) {
            float lo = step_m * float(i - 1);
            float hi = step_m * float(i);
            for (int k = 0; k < 4; ++k) {
                float mid = 0.5 * (lo + hi);
                vec3 m = start + r * mid;
                if (m.y < terrain_height(m.xz)) {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            hit = hi;
        }
    }
    if (hit < 0.0) {
        return water_inscatter(r);
    }
    vec3 q = start + r * hit;
    float e = 0.5;
    float h = terrain_height(q.xz);
    vec3 n = normalize(vec3(h - terrain_height(q.xz + vec2(e, 0.0)), e,
                            h - terrain_height(q.xz + vec2(0.0, e))));
    vec3 sun = frame.sun_dir.xyz;
    float lambert = max(dot(n, refracted_sun(sun)), 0.0) * sun_transmission(sun);
    float depth = max(water_level() - q.y, 0.0);
    if (frame.underwater.z > 0.5 && lambert > 0.0) {
        // The caustics (--caustics on), over a pixel's footprint at the mirrored distance,
        // from the level sea's surface point (no fixed-point step: a wavy mirror blurs them).
        float seen_m = length(p) + hit;
        vec2 xz = q.xz - frame.views[0].eye.xz + frame.water.xy;
        lambert *= caustic_ratio(xz, depth, seen_m, seen_m / frame.lod.x, 1);
    }
    // The casters' shadows on it (common/shadow.glsl; with --shadows), cast from half a metre
    // over the ground as for the floor seen directly, and the clouds' above it.
    lambert *= lambert > 0.0 ? sun_shadow(vec3(q.x, max(q.y, h) + 0.5, q.z), -1) : 1.0;
    vec3 light = sun_light_at(q) * lambert / 3.14159265 + sky_ambient_under(n, in_sky_zenith);
    vec3 colour = terrain_albedo(q.y, n.y) * light * exp(-depth * ABSORPTION_PER_M);
    return underwater_fog(colour, colour, r, hit);
}

// The surface seen from under the water (the camera's below it): within Snell's window,
// arcsin(1/1.333) = 48.6° of the normal, the sky refracted through it (Snell, written out),
// less what the surface reflects back down (Schlick's Fresnel at the angle in the air); outside
// it total internal reflection, a mirror of the water below: the sea floor where it lies within
// reach (mirrored_floor). Then the water between, with the
// sun's light it scatters toward the eye (the light shafts, common/caustics.glsl). Only the
// pipelines for a camera under the water or at the waterline (UNDERWATER_VIEW 1, 2) keep
// this: as a branch not taken, lavapipe still paid about 6 ms a frame for it at --quality low.
vec3 from_below(vec3 n, vec3 smooth_n, vec3 v, float dist) {
    vec3 ray = -v; // from the eye up to the surface
    float c = max(dot(ray, n), 0.0); // cosine of the angle in the water
    float s2 = N_WATER * N_WATER * (1.0 - c * c); // sin² of the angle in the air
    float ca = sqrt(max(1.0 - s2, 0.0));
    float f = s2 >= 1.0 ? 1.0 : schlick(ca);
    vec3 through = N_WATER * ray + (ca - N_WATER * c) * n;
    // Inside the window the mirror's few per cent of the floor are left to the water's colour.
    vec3 mirrored = reflect(ray, smooth_n);
    mirrored.y = min(mirrored.y, -0.01);
    vec3 below = f > 0.1 ? mirrored_floor(-v * dist, normalize(mirrored)) : water_inscatter(mirrored);
    vec3 colour = mix(sky_lookup(through), below, f);
    return underwater_fog(colour, colour, ray, dist) + sun_shafts(ray, dist);
}

void main() {
    float dist = length(in_rel_pos);
    vec3 v = -in_rel_pos / dist; // toward the camera
    // The shallows from the depth and K_s between the vertices (a pixel's own terrain height
    // cost lavapipe 0.8 ms a frame at --quality low: it runs both sides of a branch).
    vec3 shore = shore_waves_at(in_shore.y, in_shore.x);
    // The pixel's footprint on the water: dist / focal length across the view, stretched by
    // 1/sin(elevation) along it; `pixel_m` the geometric mean of the two (the foam's lace, the
    // surf's front: patterns of no direction). From under the water (v.y < 0) the filter stays
    // what MIRROR_BLUR was tuned with: 10 pixels' width in every direction.
    float across_m = dist / frame.lod.x;
    float pixel_m = across_m / sqrt(max(v.y, 0.01));
    vec2 footprint = v.y > 0.0 ? vec2(across_m / max(v.y, 0.01), across_m) : vec2(pixel_m);
    // The view's direction over the water, away from the eye (any, looking straight down).
    float flat_len = length(v.xz);
    vec2 along = flat_len > 1e-5 ? -v.xz / flat_len : vec2(1.0, 0.0);
    vec3 resolved;
    float compression;
    vec4 nf = ocean_normal_foam(in_xz, dist, footprint, along, shore.x, resolved, compression);
    // Foam fields: x the whitecaps' (the gusts change them), y the boat's and the surf's.
    vec2 foam = vec2(foam_at(in_xz, nf.w), wake_at(in_xz).w);
    vec3 n = nf.xyz;
    // The surf (common/shore.glsl). Where the waves have broken, a share in_surf.y of the sea
    // is bores: their slope (the sawtooth's, as high as the vertex drew it) replaces that share
    // of the simulated slopes, and their white water covers the face and the roller behind it,
    // more for the set's larger waves. Where the waves break but no bore is drawn (the storm's
    // flat shelf), foam on the simulated crests (in_displacement.y over half the local Hs).
    // A branch: the water away from the island's shallows (almost every pixel, in whole
    // blocks) skips it.
    if (in_surf.y > 0.0 || shore.y > 0.0) {
        vec2 world_xz = frame.views[0].eye.xz + in_xz - frame.water.xy;
        float front = shore_front(in_surf.zw, max(frame.lod.y * dist / frame.lod.x, pixel_m));
        vec2 slopes = -n.xz / max(n.y, 1e-3) * sqrt(1.0 - in_surf.y * in_surf.y)
                      + in_surf.y * SURF_BORE * shore.z * shore_bore(in_surf.x, front).y * in_surf.zw;
        n = normalize(vec3(-slopes.x, 1.0, -slopes.y));
        float wave = floor(in_surf.x + front); // the face ahead belongs to the next wave
        float roller = shore_roller(in_surf.x, front) * shore_strength(world_xz, wave);
        float crest = smoothstep(0.0, 0.6, in_displacement.y / max(0.5 * shore.z, 0.01));
        float bores = in_surf.y / SURF_SHARE;
        foam.y = max(foam.y, max(bores * roller, shore.y * (1.0 - bores) * crest));
    }
    uint view = DEBUG_VIEWS ? debug_view() : VIEW_FINAL;
    if (view == VIEW_DISPLACEMENT) {
        out_colour = target_colour(0.5 + 0.25 * in_displacement.xzy);
        return;
    }
    if (view == VIEW_NORMALS) {
        out_colour = target_colour(n * 0.5 + 0.5);
        return;
    }
    if (view == VIEW_FOAM) {
        // The foam as drawn: its layer's reflectance R (0 none, 1 opaque), grey.
        float unused_weight;
        vec2 uv = ocean_uv(in_xz, 0, dist, unused_weight).xy;
        float detail;
        float lace = foam_lace(uv, pixel_m, detail);
        out_colour = target_value(vec3(foam_opacity(foam, lace, detail)));
        return;
    }
    if (view == VIEW_TRIANGLES) {
        // A colour per triangle: a hash (MurmurHash3's 32-bit finalizer, Appleby 2011) of the
        // tile, the cell its lattice coordinates fall in and the side of the cell's diagonal
        // (passes::lattice_triangles splits a cell along (0,0)–(1,1)); per patch, tessellated.
        vec2 cell = max(floor(in_lattice), 0.0);
        vec2 f = in_lattice - cell;
        uint h = in_tile * 0x9E3779B1u ^ uint(cell.x) * 0x85EBCA77u ^ uint(cell.y) * 0xC2B2AE3Du;
        h ^= uint(f.x > f.y);
        h ^= h >> 16u;
        h *= 0x85EBCA6Bu;
        h ^= h >> 13u;
        h *= 0xC2B2AE35u;
        h ^= h >> 16u;
        out_colour = target_value(vec3(uvec3(h, h >> 8u, h >> 16u) & 255u) / 255.0);
        return;
    }
    if (view == VIEW_WIREFRAME) {
        out_colour = target_colour(vec3(0.9, 0.95, 1.0));
        return;
    }
    vec3 sun = frame.sun_dir.xyz;
    // From under the water: the pipeline for it returns here; at the waterline the pixels that
    // see from below keep going with the rest (a branch per pixel there: the foam's relief
    // below takes screen-space derivatives, which need every pixel of a quad to run them) and
    // take this colour at the end.
    bool from_under = UNDERWATER_VIEW == 1 || (UNDERWATER_VIEW == 2 && pixel_underwater());
    vec3 under_colour = vec3(0.0);
    if (from_under) {
        // The mirror's rays travel on, metres, to the floor, so a slope's error moves their
        // image far: they take the slopes a MIRROR_BLUR times wider footprint resolves (our
        // choice, 32: at 1 the floor's image broke into sparkles pixel by pixel at --quality
        // high, at 8 it still did far off; a pixel sees the mean of its many facets' images).
        vec3 unused_resolved;
        float unused_compression;
        vec3 smooth_n = ocean_normal_foam(in_xz, dist, MIRROR_BLUR * footprint, along, shore.x,
                                          unused_resolved, unused_compression).xyz;
        under_colour = from_below(n, smooth_n, v, dist);
        if (UNDERWATER_VIEW == 1) {
            out_colour = target_colour(under_colour);
            return;
        }
    }

    // Distortion (seed 001 eq. 4-5): DU/DV sampled twice, scrolling in opposite directions
    // (tile coordinates and phase reduced on the CPU: frame.dudv_origin, frame.dudv).
    float t = frame.dudv.z;
    vec2 tile = in_xz * frame.dudv.x;
    vec2 dudv = textureLod(dudv_map, frame.dudv_origin.xy + tile + vec2(t, 0.0), 0.0).rg * 2.0 - 1.0;
    dudv += textureLod(dudv_map, frame.dudv_origin.zw + tile * frame.dudv.y + vec2(-t, t), 0.0).rg * 2.0 - 1.0;
    float fade = clamp(1.0 - dist / 3000.0, 0.0, 1.0) / max(1.0, dist / 40.0);
    // The map stands for the ripples; a natural slick damps them as it damps the short waves.
    dudv *= mix(1.0, frame.slick_space.y, in_patches.x);
    vec2 offset = (dudv * DUDV_STRENGTH + n.xz * SLOPE_STRENGTH) * fade;
    vec2 screen = gl_FragCoord.xy * frame.viewport.zw;

    // The slopes the pixel does not resolve: Cox & Munk's mean square along and across the
    // view (upwind σ_u², crosswind σ_c²: frame.sea_slopes, at the local wind in a gust,
    // common/gusts.glsl; in a natural slick their slick-surface fits, frame.slicks,
    // common/slicks.glsl), less what the cascades drawn here carry in each direction; their
    // covariance (`slope_covariance`'s order), kept a covariance: the mean squares at least
    // 1e-3, the correlation at most 0.95. They blur and lean what the water reflects
    // (common/reflection.glsl), widen the glitter and lower the Fresnel reflectance.
    vec3 clean = gust_slopes(in_patches.y);
    vec3 sea_slopes = vec3(mix(clean.x, frame.slicks.x, in_patches.x),
                           mix(clean.yz, frame.slicks.yz, in_patches.x));
    vec3 unresolved = slope_covariance(sea_slopes.x, sea_slopes.yz, along) - resolved;
    unresolved.xy = max(unresolved.xy, 1e-3);
    float correlated = 0.95 * sqrt(unresolved.x * unresolved.y);
    unresolved.z = clamp(unresolved.z, -correlated, correlated);
    vec3 c_reflect = sea_reflection(in_rel_pos, in_displacement.y, screen, offset, v, unresolved.x,
                                     in_edge_sky);

    // Water thickness along the ray: refraction depth behind the surface minus the surface's.
    float near_m = frame.water.w; // Camera::near_m (depth = near / view distance)
    float water_view = near_m / gl_FragCoord.z;
    vec2 refr_uv = clamp(screen + offset, 0.001, 0.999);
    float floor_ndc = textureLod(refraction_depth, refr_uv, 0.0).r;
    if (near_m / max(floor_ndc, 1e-30) < water_view) {
        // The offset reached something in front of the water: use the undistorted point.
        refr_uv = screen;
        floor_ndc = textureLod(refraction_depth, refr_uv, 0.0).r;
    }
    vec3 c_refract = textureLod(refraction_colour, refr_uv, 0.0).rgb;
    float floor_view = floor_ndc > 0.0 ? near_m / floor_ndc : 1e9;
    float thickness = max(floor_view - water_view, 0.0) * dist / water_view;
    // Seed 001 eq. 7 fades the whole colour toward c_o with depth, which removes reflections
    // over deep water; the depth fade belongs to the refracted light only (Beer-Lambert).
    // The light the deep water scatters back up follows the light that falls on it: the sun's
    // and the sky's irradiance on the sea, relative to the default day's (WATER_COLOUR).
    // In a shadow (common/shadow.glsl: `water_shadow`) the sun's share of that irradiance is
    // gone from the water body (y); the sun's other terms below take `sunlight`, the sun's light
    // past the casters at the surface (x).
    // The clouds move the sun's share too: frame.sky_light is the sea's mean irradiance under
    // this sky (Kasten & Czeplak's cloud factor), whose sun reaches the sea through the
    // clouds' mean share t̄ (frame.sun_dir.w); here a share t of the clear sun's arrives
    // (in_sun_through: past the clouds above the point), so the sun's part is scaled by
    // t / t̄. Over the whole sea the mean stays sky_light; under an overcast there is
    // no sun to scale.
    vec2 shadow = water_shadow(in_rel_pos + VIEW.eye.xyz);
    vec3 sunlight = frame.sun_light.rgb * in_sun_through * shadow.x;
    const vec3 LUMA = vec3(0.2126, 0.7152, 0.0722);
    float clear_sun = max(dot(frame.sun_light.rgb, LUMA), 1e-6);
    float mean_through = frame.sun_dir.w;
    float sun_on_sea = clear_sun * max(sun.y, 0.0) * mean_through;
    float sun_share = sun_on_sea / max(sun_on_sea + PI * dot(in_sky_zenith, LUMA), 1e-6);
    float sun_here = shadow.y * in_sun_through / max(mean_through, 1e-3);
    vec3 deep = WATER_COLOUR * frame.sky_light.rgb * (1.0 - sun_share * (1.0 - sun_here));
    vec3 transmitted = mix(deep, c_refract, exp(-thickness * ABSORPTION_PER_M));
    // The light through the crests (crest_light), scaled as the shallows scale the waves.
    vec3 glow = crest_light(v, sun, sunlight, in_displacement.y, shore.z, compression * shore.x,
                            sea_slopes);
    transmitted += glow;

    float cos_theta = clamp(dot(n, v), 0.0, 1.0);
    // The unresolved slopes' spread along the view.
    float f = sea_fresnel(cos_theta, sqrt(unresolved.x));
    vec3 colour = mix(transmitted, c_reflect, f);

    // Whitecaps: a layer of foam of reflectance R over the water (foam_layer), lit as a
    // scattering medium (foam_light). The horizon's sky behind the pixel (in_horizon) lights it
    // and hazes it.
    // Evaluated at every pixel: lavapipe runs both sides of a branch anyway (a branch on the
    // field with two more lace lookups for the relief cost it 3.7 ms more at `low`), and the
    // relief's screen-space derivatives need every pixel of a quad.
    float unused_weight;
    vec2 uv = ocean_uv(in_xz, 0, dist, unused_weight).xy;
    float detail;
    float lace = foam_lace(uv, pixel_m, detail);
    float opacity = foam_opacity(foam, lace, detail);
    // The foam's own relief: the lace as a height field FOAM_RELIEF_M high, FROTH_RELIEF_M
    // where the crest breaks now or just did (the breaking layer, F from 0.6 to 0.9), its
    // normal from the screen-space derivatives (Mikkelsen 2010's surface gradient).
    vec3 dpx = dFdx(in_rel_pos);
    vec3 dpy = dFdy(in_rel_pos);
    vec3 r1 = cross(dpy, n);
    vec3 r2 = cross(n, dpx);
    float det = dot(dpx, r1);
    vec3 grad = abs(det) > 1e-12 ? (dFdx(lace) * r1 + dFdy(lace) * r2) / det : vec3(0.0);
    float froth = smoothstep(0.6, 0.9, max(foam.x, foam.y));
    vec3 foam_n = normalize(n - mix(FOAM_RELIEF_M, FROTH_RELIEF_M, froth) * grad);
    // Looking straight down there is no horizon behind the foam: the sky above it.
    vec3 behind = mix(in_sky_zenith, in_horizon, clamp(2.0 * length(v.xz), 0.0, 1.0));
    colour = mix(colour, foam_light(foam_n, v, sun, sunlight, behind, lace), opacity);
    // c_h: the sun's glitter from the slopes the normal does not resolve (the sea's mean-square
    // slope, Cox & Munk 1954, less what the cascades drawn here carry), none on the foam.
    float glitter = sun_glitter(n, v, sun, along, unresolved) * (1.0 - opacity);
    colour += sunlight * glitter;

    vec3 haze = aerial_haze(dist);
    if (view == VIEW_CRESTS) { // the debug pipeline sees from above: none from below
        out_colour = target_colour(glow * (1.0 - f) * (1.0 - opacity) * (1.0 - haze)
                                   * step(0.0, v.y));
        return;
    }
    out_colour = target_colour(from_under ? under_colour : mix(colour, in_horizon, haze));
}
