// The sky: sunlight scattered by the Earth's air and aerosols (Rayleigh and Mie), seen
// through a layer of clouds, or the grey of an overcast. sky/sky_cube.frag renders it into the
// sky cube when the sun or the cloud cover changes; every pass looks the cube up (reflections,
// the haze toward the horizon, the ambient light of terrain and foam), so they all agree. The
// sun's light on the water and the island is the same sunlight, dimmed by the air it crosses
// (src/render/atmosphere.rs computes it on the CPU for the frame uniforms; `sun_transmittance`
// below is its twin). The sun's disc is not in the cube (its texels drew a blocky 13 px disc):
// the sky pass draws it per pixel (`sun_disc`). Radiance is linear HDR, in units of the sun's
// irradiance (the cube's `irradiance`); common/display.glsl tone-maps it in the main view.
//
// The scattering integral, phase functions and the atmosphere's constants (src/shared.rs) are
// those of Bruneton & Neyret (2008, "Precomputed atmospheric scattering") and Hillaire (2020,
// "A scalable and production ready sky and atmosphere rendering technique"), evaluated here by
// marching the ray instead of from their lookup tables: the cube is rendered once per sun.
#include "shared.glsl"
#include "clouds.glsl"

const float SKY_PI = 3.14159265;
// The sun's mean apparent diameter is 0.533° (Allen's Astrophysical Quantities, 4th ed., §14.1):
// angular radius 0.00465 rad.
const float SUN_ANGULAR_RADIUS = 0.00465;
// Linear limb darkening I(μ)/I(1) = 1 − u(1 − μ), μ the cosine of the angle from the disc's normal
// to the line of sight, u ≈ 0.6 in the visible (Allen's Astrophysical Quantities, §14.7).
const float SUN_LIMB_U = 0.6;
// An overcast (8 oktas) lets through a quarter of a clear sky's global irradiance: G/G_clear =
// 1 − 0.75 (N/8)^3.4 (Kasten & Czeplak 1980), all of it diffuse.
const float OVERCAST_GLOBAL = 0.25;

// Air, aerosol and ozone densities (relative to their sea-level or peak value) at altitude h.
vec3 air_density(float h) {
    return vec3(exp(-h / RAYLEIGH_SCALE_HEIGHT_M), exp(-h / MIE_SCALE_HEIGHT_M),
                max(1.0 - abs(h - OZONE_PEAK_M) / OZONE_HALF_WIDTH_M, 0.0));
}

vec3 extinction(vec3 density) {
    return RAYLEIGH_SCATTERING * density.x + MIE_EXTINCTION * density.y
         + OZONE_ABSORPTION * density.z;
}

// Distance from radius r along a ray of zenith cosine mu to the top of the atmosphere.
float distance_to_top(float r, float mu) {
    float disc = r * r * (mu * mu - 1.0) + ATMOSPHERE_TOP_M * ATMOSPHERE_TOP_M;
    return max(-r * mu + sqrt(max(disc, 0.0)), 0.0);
}

// The sunlight left at radius r toward a sun of zenith cosine mu_s (optical depth marched
// over 8 segments); none once the Earth hides the sun.
vec3 sun_transmittance(float r, float mu_s) {
    float below = r * r * (mu_s * mu_s - 1.0) + EARTH_RADIUS_M * EARTH_RADIUS_M;
    if (mu_s < 0.0 && below >= 0.0) {
        return vec3(0.0);
    }
    float len = distance_to_top(r, mu_s);
    vec3 depth = vec3(0.0);
    const int STEPS = 8;
    for (int i = 0; i < STEPS; ++i) {
        float t = len * (float(i) + 0.5) / float(STEPS);
        float h = sqrt(r * r + t * t + 2.0 * r * mu_s * t) - EARTH_RADIUS_M;
        depth += extinction(air_density(h));
    }
    return exp(-depth * len / float(STEPS));
}

// The light scattered more than once, Ψ_ms(h, μs) of Hillaire (2020) for a sun of unit
// irradiance (src/render/multiple_scattering.rs computes the table once and describes it):
// its texel centres span the altitude as √(h / height) and the sun's zenith cosine μs.
// Whoever includes this file with SKY_MULTIPLE_SCATTERING defined declares the table,
// `sky_multiple_scattering` (sky/sky_cube.frag); without it the sky is single scattering.
vec3 multiple_scattering(float h, float mu_s) {
#ifdef SKY_MULTIPLE_SCATTERING
    float side = float(textureSize(sky_multiple_scattering, 0).x);
    float u = sqrt(clamp(h / (ATMOSPHERE_TOP_M - EARTH_RADIUS_M), 0.0, 1.0));
    float v = clamp(mu_s * 0.5 + 0.5, 0.0, 1.0);
    vec2 uv = (0.5 + vec2(u, v) * (side - 1.0)) / side;
    return texture(sky_multiple_scattering, uv).rgb;
#else
    return vec3(0.0);
#endif
}

// The light scattered toward the eye (SKY_EYE_ALTITUDE_M up) along `dir`, for a sun of unit
// irradiance along `sun`: once, ∫ T(eye, p) [β_R ρ_R P_R(ν) + β_M ρ_M P_M(ν)] T_sun(p) dt,
// and more often, ∫ T(eye, p) (β_R ρ_R + β_M ρ_M) Ψ_ms dt (Hillaire 2020, eq. 11). Samples
// crowd toward the eye (t ∝ u²), where the air is dense. Below the horizon the sea hides the
// sky: the horizon's light stands in (the water's own colour is drawn over it).
vec3 clear_sky(vec3 dir, vec3 sun) {
    float r = EARTH_RADIUS_M + SKY_EYE_ALTITUDE_M;
    vec3 d = normalize(vec3(dir.x, max(dir.y, 0.0), dir.z));
    float len = distance_to_top(r, d.y);
    float nu = dot(d, sun);
    float phase_r = 3.0 / (16.0 * SKY_PI) * (1.0 + nu * nu);
    float g2 = MIE_G * MIE_G;
    float phase_m = 3.0 / (8.0 * SKY_PI) * (1.0 - g2) * (1.0 + nu * nu)
                  / ((2.0 + g2) * pow(1.0 + g2 - 2.0 * MIE_G * nu, 1.5));
    vec3 depth = vec3(0.0);
    vec3 rayleigh = vec3(0.0);
    vec3 mie = vec3(0.0);
    vec3 multiple = vec3(0.0);
    const int STEPS = 16;
    for (int i = 0; i < STEPS; ++i) {
        float u0 = float(i) / float(STEPS);
        float u1 = float(i + 1) / float(STEPS);
        float dt = len * (u1 * u1 - u0 * u0);
        float t = len * 0.5 * (u0 * u0 + u1 * u1);
        vec3 p = vec3(0.0, r, 0.0) + t * d;
        float rp = length(p);
        vec3 density = air_density(rp - EARTH_RADIUS_M);
        vec3 ext = extinction(density);
        vec3 seen = exp(-(depth + 0.5 * ext * dt));
        float mu_s = dot(p, sun) / rp;
        vec3 light = seen * sun_transmittance(rp, mu_s);
        rayleigh += light * density.x * dt;
        mie += light * density.y * dt;
        vec3 scattering = RAYLEIGH_SCATTERING * density.x + MIE_SCATTERING * density.y;
        multiple += seen * scattering * multiple_scattering(rp - EARTH_RADIUS_M, mu_s) * dt;
        depth += ext * dt;
    }
    return rayleigh * RAYLEIGH_SCATTERING * phase_r + mie * MIE_SCATTERING * phase_m + multiple;
}

// The sky along `dir` with `cover` (0–1) of it clouded, for a sun of irradiance `irradiance`
// toward `sun`: rgb the radiance, a the share of the sun's light the clouds let through along
// `dir` (the sun's disc and the direct light on the scene are multiplied by it at `sun`).
// `sunlight` (the sun's irradiance at the sea) and `zenith` (the clear sky's radiance there)
// are the same for every direction: src/render/atmosphere.rs computes them once per sky.
// Broken clouds are a layer CLOUD_BASE_M up, lit by the sun through the air and by the sky;
// from 7/8 of cover on, they close into an overcast whose radiance follows the CIE standard
// overcast sky, L(θ) = L_z (1 + 2 sin θ)/3 (Moon & Spencer 1942), with its horizontal
// irradiance (7π/9) L_z a quarter of the clear sky's global irradiance (OVERCAST_GLOBAL).
vec4 sky_radiance(vec3 dir, vec3 sun, float cover, float irradiance, vec3 sunlight, vec3 zenith) {
    vec3 clear = clear_sky(dir, sun) * irradiance;
    // The clear sky's global irradiance on the sea: the sun's and (about) the sky's.
    vec3 global = sunlight * max(sun.y, 0.0) + SKY_PI * zenith;
    vec3 grey = vec3(dot(global, vec3(0.2126, 0.7152, 0.0722)));
    vec3 overcast_zenith = OVERCAST_GLOBAL * mix(grey, global, 0.1) * 9.0 / (7.0 * SKY_PI);
    float elevation = max(dir.y, 0.0);
    vec3 overcast = overcast_zenith * (1.0 + 2.0 * elevation) / 3.0;

    // Broken clouds: where the ray meets the layer, a coverage from the shape's noise.
    // The layer is common/clouds.glsl's, seen from the origin.
    float dist = CLOUD_BASE_M / max(dir.y, 1e-3);
    float alpha = cloud_alpha(dir.xz * dist, dist, cover) * step(0.0, dir.y);
    // Cloud lit from above and through (forward scattering toward the sun), and by the sky.
    float nu = max(dot(dir, sun), 0.0);
    vec3 cloud = sunlight * (0.12 * max(sun.y, 0.0) + 0.1 * pow(nu, 6.0)) + 1.4 * zenith;
    // Air between the eye and a far cloud lays the clear sky over it.
    cloud = mix(cloud, clear, 1.0 - exp(-dist / 40e3));

    float closed = smoothstep(0.85, 1.0, cover);
    float below_horizon = mix(1.0, 0.55, clamp(-dir.y * 6.0, 0.0, 1.0));
    vec3 col = mix(mix(clear, cloud, alpha), overcast, closed) * below_horizon;
    float through = (1.0 - alpha) * (1.0 - closed);
    return vec4(col, through);
}

// The sun's disc along `dir`, relative to its centre's radiance: the share of a pixel
// `pixel_rad` wide (in radians) the disc covers, times the limb darkening where it does. The
// angle from the sun comes from |dir × sun| = sin θ, exact in f32 near θ = 0 (acos of the dot
// product resolves steps of 3.5·10⁻⁴ rad, 8 % of the radius).
float sun_disc(vec3 dir, vec3 sun, float pixel_rad) {
    float theta = dot(dir, sun) > 0.0 ? asin(min(length(cross(dir, sun)), 1.0)) : 3.0;
    float cover = clamp((SUN_ANGULAR_RADIUS - theta) / pixel_rad + 0.5, 0.0, 1.0);
    float r = min(theta / SUN_ANGULAR_RADIUS, 1.0);
    float mu = sqrt(1.0 - r * r);
    return cover * (1.0 - SUN_LIMB_U * (1.0 - mu));
}
