// The view from under the water (when the camera's near plane is below the surface, or the
// pixel's point on it where the surface crosses it: frame.underwater, frame.waterline,
// src/render/uniforms.rs). Light crossing the water is absorbed (ABSORPTION_PER_M,
// red first) and scattered (UNDERWATER_SCATTERING_PER_M); what the water scatters toward the eye
// (`water_inscatter`) is its own colour, the deep colour seen from above (WATER_COLOUR under the
// sky's light), brighter toward the surface, darker toward the deep and with depth.
// Include after common/frame.glsl.

// Scattering by the water and its particles (1/m, grey): with the absorption, blue light
// fades to 1/e in about 10 m, a clear coastal sea's visibility.
const float UNDERWATER_SCATTERING_PER_M = 0.04;

bool camera_underwater() { return frame.underwater.x > 0.5; }

// Whether the main view's pixel sees from under the water: the camera's near plane's side, or,
// where the surface crosses the near plane (frame.waterline.w), the side of the pixel's point
// on it against the surface's tangent plane at the camera, so the picture splits along the
// waterline. Fragment shaders of the main view only.
bool pixel_underwater() {
    if (frame.waterline.w < 0.5) {
        return camera_underwater();
    }
    vec2 ndc = gl_FragCoord.xy * frame.viewport.zw * 2.0 - 1.0;
    vec4 p = frame.views[0].inv_view_proj * vec4(ndc, 1.0, 1.0); // reversed-Z: near at 1
    vec3 q = p.xyz / p.w;
    return q.y < frame.waterline.z + dot(frame.waterline.xy, q.xz);
}

// Scattering in sea water goes mostly forward: in Petzold's (1972) clear-ocean measurements
// (Bahamas, 530 nm) about 70 % of the scattering coefficient lies within 10° of the beam and 36 %
// within 1°. Along a path to an extended surface (the floor, the underside of the waves) that
// light stays near the line of sight: it blurs the surface's detail instead of dimming its
// mean. So its detail fades with the beam attenuation a + b and its mean with a + 0.3 b.
const float UNDERWATER_FORWARD_SHARE = 0.7;

// The water's own light along a ray going `dir` from the eye, over an endless path.
vec3 water_inscatter(vec3 dir) {
    float up = dir.y * 0.5 + 0.5;
    vec3 light = WATER_COLOUR * frame.sky_light.rgb * mix(0.4, 3.0, up * up);
    // Daylight dims with the eye's depth (diffuse attenuation ≈ absorption).
    return light * exp(-frame.underwater.y * ABSORPTION_PER_M);
}

// A surface seen `dist` metres away through the water along `dir`: `colour` as it is and
// `blurred` its local mean (without the detail forward scattering spreads over about 10°: the
// caustics). The unscattered light keeps the detail, the forward-scattered adds the mean, the
// water's own light fills what is lost.
vec3 underwater_fog(vec3 colour, vec3 blurred, vec3 dir, float dist) {
    vec3 direct = exp(-dist * (ABSORPTION_PER_M + UNDERWATER_SCATTERING_PER_M));
    vec3 kept = exp(-dist * (ABSORPTION_PER_M
                             + (1.0 - UNDERWATER_FORWARD_SHARE) * UNDERWATER_SCATTERING_PER_M));
    return colour * direct + blurred * (kept - direct) + water_inscatter(dir) * (1.0 - kept);
}

// The sun's direction under the water: refracted at a level surface (Snell, n = 1.333).
vec3 refracted_sun(vec3 l) {
    float sin_t = length(l.xz) / 1.333;
    vec2 toward = length(l.xz) > 1e-4 ? normalize(l.xz) : vec2(0.0);
    return vec3(toward.x * sin_t, sqrt(1.0 - sin_t * sin_t), toward.y * sin_t);
}

// The share of the sun's light the level sea lets in (1 − Schlick's Fresnel at the sun's
// incidence in the air; F0 = 0.02, water's).
float sun_transmission(vec3 l) {
    float m = 1.0 - clamp(l.y, 0.0, 1.0);
    float m2 = m * m;
    return 1.0 - (0.02 + 0.98 * m2 * m2 * m);
}

// The water's phase function: Henyey–Greenstein with g = 0.924, the mean cosine of Petzold's
// average-particle phase function (Mobley, Ocean Optics Web Book, "The Henyey-Greenstein phase
// function"): most of the sun's scattered light goes on within a few degrees of its beam, so
// the water glows around the sun's direction and hardly at all away from it.
const float UNDERWATER_PHASE_G = 0.924;

// The sun's light the water scatters toward the eye from the stretch s0..s1 m along `dir`
// (from the eye): single scattering b·p(θ) of the refracted sun, whose irradiance is what the
// level sea lets in less the absorption down to each point's depth (as the floor's light,
// common/terrain_lit.glsl), dimmed by a + b on its way to the eye. Over a level sea: the
// caustics' focusing (their area ratio, common/caustics.glsl) multiplies it.
vec3 sun_scatter(vec3 dir, float s0, float s1) {
    vec3 l = frame.sun_dir.xyz;
    if (l.y <= 0.0) {
        return vec3(0.0);
    }
    float g = UNDERWATER_PHASE_G;
    float phase = (1.0 - g * g)
                  / (4.0 * 3.14159265 * pow(1.0 + g * g - 2.0 * g * dot(refracted_sun(l), dir), 1.5));
    // Per metre along the ray: the way to the eye, and the depth the sun's light crosses.
    vec3 decay = ABSORPTION_PER_M * (1.0 - dir.y) + UNDERWATER_SCATTERING_PER_M;
    // frame.underwater.w: what the clouds above the eye let through (the same for the whole
    // frame: src/render/uniforms.rs computes it with src/render/clouds.rs).
    vec3 light = frame.sun_light.rgb * frame.underwater.w * sun_transmission(l)
                 * exp(-frame.underwater.y * ABSORPTION_PER_M);
    return UNDERWATER_SCATTERING_PER_M * phase * light * (exp(-decay * s0) - exp(-decay * s1)) / decay;
}

// A per-pixel offset in 0..1 that neighbours do not share (Jimenez 2014's interleaved gradient
// noise): where the light shafts take their samples along each stretch of the ray.
float pixel_jitter() {
    return fract(52.9829189 * fract(dot(gl_FragCoord.xy, vec2(0.06711056, 0.00583715))));
}

// The light shafts' image (shaders/underwater/shafts.frag, common/caustics.glsl's
// shaft_means): per texel of the main view, the caustics' mean area ratio along the ray over
// the first quarter, half, three quarters and all of SHAFT_REACH_M.
const float SHAFT_REACH_M = 16.0;
layout(set = 0, binding = 5) uniform sampler2D shaft_image;

// The sun's light the water scatters toward the eye from the `dist` m before the surface a
// fragment of the main view shows, with the caustics' focusing (`shaft_means` at its pixel).
vec3 sun_shafts(vec3 dir, float dist) {
    float reach = min(dist, SHAFT_REACH_M);
    float mean = 1.0;
    if (frame.underwater.z > 0.5) {
        // Four bilinear taps half a texel apart: a 3x3 tent over the march's per-texel jitter.
        vec2 uv = gl_FragCoord.xy * frame.viewport.zw;
        vec2 half_texel = 0.5 / vec2(textureSize(shaft_image, 0));
        vec4 means = 0.25 * (textureLod(shaft_image, uv + half_texel, 0.0)
                             + textureLod(shaft_image, uv - half_texel, 0.0)
                             + textureLod(shaft_image, uv + vec2(half_texel.x, -half_texel.y), 0.0)
                             + textureLod(shaft_image, uv + vec2(-half_texel.x, half_texel.y), 0.0));
        float q = clamp(reach / (0.25 * SHAFT_REACH_M), 1.0, 4.0) - 1.0;
        int k = min(int(q), 2);
        mean = mix(means[k], means[k + 1], q - float(k));
    }
    return mean * sun_scatter(dir, 0.0, reach) + sun_scatter(dir, reach, dist);
}
