// Included by surface/water.frag after the `schlick`, `smith_g1` and `henyey_greenstein` it
// uses (and common/glitter.glsl's `slope_covariance`).

// Light through the crests: a thin crest between the eye and the sun glows turquoise (the
// signature of Sea of Thieves and Atlas, Grenier 2019). Sunlight enters the back of the crest,
// scatters in it and leaves through the face toward the eye. Through a flat surface that
// cannot happen: the sun's refracted ray and the eye's both dive about 40° into the water, so
// they meet at about 80° where the water's forward-peaked phase function has almost nothing;
// only a crest, high (`h` over the local Hs `hs`) and sharp (`compression`, Σ (1 − J)), is
// thin enough for the light to cross it. The crest is taken as Stokes' sharpest, a 120° wedge
// (faces sloping 30°, one toward the eye, one away): the sunlight enters the far face (its
// Fresnel transmission; the refracted beam wider, its irradiance × cos θi / cos θt), refracts,
// and is scattered into the eye's ray as the near face refracts it, by the phase function at
// the angle between the two in the water. Both rays bend toward the faces' normals, so for a
// level view toward a sun ahead that angle is 39° with the sun on the horizon, 44° at 10°, 57°
// at 30°; taken between the rays in the air, the lobe peaked as the view neared a low sun, and
// the crests toward a setting sun painted the sea lime (tests/sky.rs measures it). What
// crosses is the sunlight times the water's transmission over the path, e^(−c·d): red absorbed
// first, so turquoise against the deep water's blue (yellow-green under an orange sun); the
// path shortens as the crest thins (CREST_PATH_M down to half of it). The phase function is
// Henyey–Greenstein with g = 0.7, broader than the water's own (g ≈ 0.92 is usually fitted to
// Petzold's measured ocean phase function): the term stands in for the light a crest's
// surface, bubbles and repeated scattering spread out, so its strength CREST_GLOW (70 times the
// water's 0.04/m scattering) is our choice, set so a backlit moderate sea's crests are 1.24
// times as bright as its troughs at equal normal, in radiance (tests/sky.rs).
const float CREST_PATH_M = 4.0;
const float CREST_PHASE_G = 0.7;
const float CREST_GLOW = 2.8;        // per metre of path
const float CREST_HEIGHT = 0.3;      // of the local Hs: fully high from there up
const float CREST_COMPRESSION = 0.3; // Σ (1 − J): fully sharp from there up
const float CREST_FACE_SLOPE = 0.577; // tan 30°: the faces of Stokes' sharpest crest (120°)
const vec2 CREST_FACE = vec2(0.5, 0.866); // sin, cos 30°: the faces' normals
// `sea_slopes`: the sea's mean-square slope and its anisotropy (`slope_covariance`'s), for the
// waves that stand between the crest and a low sun: Smith's (1967) shadowing of a Gaussian
// surface, for a point at height h the chance F(h)^Λ that the sun reaches it (F the heights'
// distribution, σ_η = Hs/4; Λ from the mean-square slope toward the sun, as `smith_g1`'s).
// It matters as the sun sets only: for a crest 0.3 Hs high on the moderate sea (Cox & Munk's
// 0.027 crosswind to 0.039 upwind at 12.3 m/s), 0.99 at 10°, 0.88–0.91 at 3°, 0.61–0.67 at 1°.
vec3 crest_light(vec3 v, vec3 l, vec3 sunlight, float h, float hs, float compression,
                 vec3 sea_slopes) {
    // The eye's ray must cross the crest sideways: one dipping more steeply than its faces
    // (30° at the most) enters its top and goes on into the wave's body. The fade to there
    // stands in for the crests' spread of steepness.
    float dip = v.y / max(length(v.xz), 1e-3);
    float across = 1.0 - smoothstep(0.0, CREST_FACE_SLOPE, dip);
    float thin = smoothstep(0.0, CREST_HEIGHT, h / max(hs, 0.05))
               * smoothstep(0.0, CREST_COMPRESSION, compression) * across;
    float d = CREST_PATH_M * (1.0 - 0.5 * thin);
    vec3 extinction = ABSORPTION_PER_M + UNDERWATER_SCATTERING_PER_M;
    vec2 away = length(v.xz) > 1e-5 ? -normalize(v.xz) : vec2(1.0, 0.0);
    vec3 front = vec3(-CREST_FACE.x * away, CREST_FACE.y).xzy;
    vec3 back = vec3(CREST_FACE.x * away, CREST_FACE.y).xzy;
    float cos_in = max(dot(l, back), 0.0);
    vec3 into = refract(-l, back, 1.0 / N_WATER);
    vec3 toward_eye = -refract(-v, front, 1.0 / N_WATER);
    float entering = cos_in * (1.0 - schlick(cos_in)) / max(-dot(into, back), 0.1);
    float lobe = henyey_greenstein(dot(into, toward_eye), CREST_PHASE_G);
    vec2 to_sun = length(l.xz) > 1e-5 ? normalize(l.xz) : away;
    float toward = slope_covariance(sea_slopes.x, sea_slopes.yz, to_sun).x;
    float lambda = 1.0 / smith_g1(max(l.y, 1e-3), max(toward, 1e-4)) - 1.0;
    // Φ(x) ≈ 1 / (1 + e^(−1.702 x)), the logistic fit to the normal distribution (error < 0.01);
    // x clamped so the exponential cannot overflow (pow(0, 0) is undefined) by the shore, where
    // h and the local Hs are taken at different places.
    float x = clamp(4.0 * h / max(hs, 0.05), -8.0, 8.0);
    float lit = pow(1.0 / (1.0 + exp(-1.702 * x)), max(lambda, 0.0));
    return thin * lit * sunlight * entering * CREST_GLOW * lobe * d * exp(-extinction * d);
}
