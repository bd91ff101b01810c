// The view from under the water (when the camera is below the surface at its x, z: frame
// .underwater, src/render/uniforms.rs). Light crossing the water is absorbed (ABSORPTION_PER_M,
// red first) and scattered (UNDERWATER_SCATTERING_PER_M); what the water scatters toward the eye
// (`water_inscatter`) is its own colour, the deep colour seen from above (WATER_COLOUR under the
// sky's light), brighter toward the surface, darker toward the deep and with depth.
// Include after common/frame.glsl.

// Scattering by the water and its particles (1/m, grey): with the absorption, blue light
// fades to 1/e in about 10 m, a clear coastal sea's visibility.
const float UNDERWATER_SCATTERING_PER_M = 0.04;

bool camera_underwater() { return frame.underwater.x > 0.5; }

// The water's own light along a ray going `dir` from the eye, over an endless path.
vec3 water_inscatter(vec3 dir) {
    float up = dir.y * 0.5 + 0.5;
    vec3 light = WATER_COLOUR * frame.sky_light.rgb * mix(0.4, 3.0, up * up);
    // Daylight dims with the eye's depth (diffuse attenuation ≈ absorption).
    return light * exp(-frame.underwater.y * ABSORPTION_PER_M);
}

// `colour` seen `dist` metres away through the water along `dir`.
vec3 underwater_fog(vec3 colour, vec3 dir, float dist) {
    vec3 extinction = ABSORPTION_PER_M + UNDERWATER_SCATTERING_PER_M;
    return mix(water_inscatter(dir), colour, exp(-dist * extinction));
}

// The share of the sun's light the level sea lets in (1 − Schlick's Fresnel at the sun's
// incidence in the air; F0 = 0.02, water's).
float sun_transmission(vec3 l) {
    float m = 1.0 - clamp(l.y, 0.0, 1.0);
    float m2 = m * m;
    return 1.0 - (0.02 + 0.98 * m2 * m2 * m);
}
