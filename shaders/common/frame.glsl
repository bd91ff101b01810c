// Per-frame uniforms shared by every scene pass (set 0, binding 0), filled by
// src/render/uniforms.rs (`FrameUniforms`, std140). Rendering is camera-relative: vertex positions
// are world positions minus the view's eye, so view_proj holds no translation.
struct View {
    mat4 view_proj;      // eye-relative world position -> clip space (reversed-Z, infinite far)
    mat4 inv_view_proj;  // clip space -> eye-relative position (used to build view rays)
    vec4 eye;            // xyz: world position positions are relative to
    vec4 clip_plane;     // world plane: dot(plane, vec4(world, 1)) < 0 is clipped (seed 001 eq. 2)
};

#include "shared.glsl"
#include "clouds.glsl"

layout(set = 0, binding = 0, std140) uniform FrameUniforms {
    View views[3];       // 0: camera, 1: reflection (mirrored about the water), 2: refraction
    uvec4 modes;         // x: debug view (VIEW_*); y: Fresnel model (FRESNEL_*); z: 1 = bounded
                         // ocean window (Gerstner); w: 1 = solid test background
    vec4 sun_dir;        // xyz: unit vector toward the sun; w: the share of its light the
                         // clouds let through to the sea on average (src/render/clouds.rs)
    vec4 viewport;       // xy: main target size (px); zw: 1 / size
    vec4 patch_m;        // side of each ocean cascade's patch (m), cascades 0..3
    vec4 lod;            // x: focal length (px); y: target edge (px); z: max displacement (m)
    vec4 terrain;        // xy: island centre (m); z: sea floor depth (m); w: island radius (m)
    vec4 objects[4];     // (x, z, radius, top height) of the objects in the water; 0 height = none;
                         // 0 is the buoy (top height: above its waterline, see `buoy`)
    vec4 background;     // xyz: the solid test background (modes.w = 1)
    // Camera-relative water (WaterFrame in src/render/uniforms.rs): the water's vertices are
    // measured from a centre near the camera; what depends on absolute position is reduced on
    // the CPU in f64, so precision holds however far from the origin and however late.
    vec4 water;          // xy: camera xz relative to the water grid centre (m); z: water level (m);
                         // w: the camera's near plane (m; depth = near / view distance)
    vec4 cascade_uv[2];  // ocean image coordinates of the grid centre (plus half a texel: texel i
                         // holds the node at i·L/N): cascade c in [c/2].xy / .zw
    vec4 dudv_origin;    // DU/DV tile coordinates of the grid centre (mod 1): xy sample 1, zw sample 2
    vec4 dudv;           // x: tiles per metre; y: sample 2's scale; z: scroll phase (turns)
    vec4 buoy;           // the floating buoy (object 0): xyz its unit axis; w: its heave (m)
    vec4 shore;          // the waves over the shallows (common/shore.glsl): x the sea's Hs (m),
                         // y its mean angular frequency ω̄ (rad/s), z c_g(ω̄) at the depth it is
                         // simulated for (m/s); w the surf's clock (common/shore.glsl)
    vec4 open_sea;       // past the island's slope (SHELF_FOOT_R): x the floor's depth (m,
                         // common/terrain.glsl); y the shoaling coefficient there
    vec4 light;          // x: radiance of the sun's disc above the air, which the sky pass
                         // draws (0 with --skybox, whose faces hold their own sun); y: the sea's
                         // mean-square slope (Cox & Munk 1954); z: the sun's irradiance above
                         // the air
    vec4 slope_variance; // mean-square slope of cascade c's waves (Σ k²E), c = 0..3
    vec4 curvature_variance; // mean square of the Laplacian of cascade c's height (Σ k⁴E)
    vec4 slope_anisotropy[2]; // cascade c's slopes by direction: [0] Σ(k_x² − k_z²)E,
                         // [1] Σ k_x k_z E (`slope_along`)
    vec4 sea_slopes;     // xy: the same for the whole sea (FFT: Cox & Munk's upwind excess
                         // along the wind; Gerstner: the waves' own); z: their growth per
                         // unit of a gust's g over them (common/gusts.glsl)
    vec4 sun_light;      // rgb: the sun's irradiance at the sea through the clear air (before
                         // the clouds: `sun_through_at` takes what they let through); w: the
                         // cloud cover the sun's light passes (0 with --skybox: no layer)
    vec4 sky_light;      // rgb: the irradiance on the sea over the default day's; w: the
                         // display's exposure (the eye's adaptation to the light)
    vec4 underwater;     // x: 1 when the camera's near plane is all under the water; y: the
                         // camera's depth (m, >= 0); z: 1 with the caustics (--caustics on);
                         // w: the share of the sun the clouds above the camera let through
    vec4 waterline;      // the surface at the camera: xy its slope; z its height over the eye
                         // (m); w: 1 when it crosses the near plane (the picture splits)
    vec4 foam_levels[FOAM_MAX_LEVELS]; // the foam near the camera, level l: xy its image
                         // coordinates of the water grid's centre, z per metre; w the number
                         // of levels (0: the lattice's foam only)
    vec4 wake;           // --boat (src/ocean/wake.rs): xy the wake image's coordinates of the
                         // water grid's centre, z per metre; w 1 with a boat
    vec4 slicks;         // natural slicks (src/render/slicks.rs): x their mean-square slope;
                         // yz its excess along the wind (as sea_slopes); w the noise's
                         // threshold (SLICK_NONE: none)
    vec4 slick_space;    // x: their drift along the wind (noise cells); y: the amplitude left
                         // of the short waves in one; zw: the wind (unit)
    vec4 slick_cascades; // cascade c's slopes in a slick over its slopes out of one
    vec4 gusts;          // wind gusts (src/render/gusts.rs): x their drift along the wind
                         // (noise cells); y their strength σ_u/U10 (0: none); z the sea's
                         // mean-square slope's growth per unit of g; w 1 over the sea's mean
                         // whitecap ratio
    vec4 slope_mips[SLOPE_LEVELS]; // what mip level l of the normal images leaves of cascade
                         // c's slopes, [l][c] (src/ocean/moments.rs `slope_mip_gains`)
} frame;

// Which view a draw renders (ViewIndex in src/render/uniforms.rs).
layout(push_constant) uniform Pass { uint view; } pass;

#define VIEW frame.views[pass.view]

// Debug views (`--view`, ViewMode in src/render/mod.rs) the scene shaders react to: VIEW_*
// of src/shared.rs.
uint debug_view() { return frame.modes.x; }
// The water level (m).
float water_level() { return frame.water.z; }

// The ocean simulation's images of this frame's slot, one layer per cascade (GENERAL layout,
// repeat sampler): (dx, h, dz, 0) and (-n.x/n.y, -n.z/n.y, Jacobian, foam) of the exact normal.
layout(set = 0, binding = 1) uniform sampler2DArray ocean_displacement;
layout(set = 0, binding = 2) uniform sampler2DArray ocean_normals;
// The sky cubemap (rendered when the sun changes, or loaded with --skybox).
layout(set = 0, binding = 3) uniform samplerCube sky_cube;
// The foam near the camera (src/ocean/simulation/foam_sim.rs), one layer per level: (whitecap
// foam, residual foam, 0, 0) at rest positions.
layout(set = 0, binding = 4) uniform sampler2DArray foam_field;
// The boat's wake on its grid near the camera (src/ocean/simulation/wake_sim.rs): (h, ∂h/∂x,
// ∂h/∂z, foam) (clamp sampler; 1×1 without a boat), read by `wake_at` (common/water.glsl).
layout(set = 0, binding = 7) uniform sampler2DArray wake_field;
// The caustics' area ratio's measured means over the floor, by depth and pixel footprint
// (src/render/passes/caustic_means.rs; common/caustics.glsl `caustic_mean`): r with one
// fixed-point step, g with none (linear, clamp sampler).
layout(set = 0, binding = 8) uniform sampler2D caustic_means;

// The ocean image coordinates of cascade c at a point `xz` metres from the water grid's
// centre (repeating for the FFT cascades). `weight` fades a cascade out with distance before its
// waves alias, and a bounded (Gerstner) window toward its edges.
vec3 ocean_uv(vec2 xz, int c, float dist, out float weight) {
    float patch_m = frame.patch_m[c];
    vec4 centres = frame.cascade_uv[c / 2];
    vec2 uv = ((c & 1) == 0 ? centres.xy : centres.zw) + xz / patch_m;
    vec2 q = abs(uv - 0.5);
    // Branch-free (see ocean_displacement_at in common/water.glsl for why).
    weight = mix(clamp(2.0 - dist / (patch_m * 4.0), 0.0, 1.0),
                 1.0 - smoothstep(0.35, 0.5, max(q.x, q.y)), float(frame.modes.z));
    return vec3(uv, c);
}

// World-space direction of the view ray through a pixel, from normalized device coordinates.
vec3 view_ray(vec2 ndc) {
    vec4 p = VIEW.inv_view_proj * vec4(ndc, 0.5, 1.0);
    return normalize(p.xyz / p.w);
}

// Sky radiance along a world direction, from the cubemap (faces as Vulkan addresses them;
// shaders/sky/sky_cube.frag renders them with the inverse mapping).
vec3 sky_lookup(vec3 dir) { return textureLod(sky_cube, dir, 0.0).rgb; }

// The buoy's frame (terrain/objects.vert draws it, common/shadow.glsl casts its shadow): the
// rotation taking +y to its axis u = frame.buoy.xyz (uy > −1), the shortest one (about y × u);
// its columns are the images of x, y and z (Rodrigues' formula with cos = uy, sin·k = y × u).
mat3 buoy_to_world() {
    vec3 u = frame.buoy.xyz;
    float s = 1.0 / (1.0 + u.y);
    return mat3(vec3(1.0 - u.x * u.x * s, -u.x, -u.x * u.z * s),
                u,
                vec3(-u.x * u.z * s, -u.z, 1.0 - u.z * u.z * s));
}

// The share of the sun's light that reaches world point `p` (m) through the broken clouds above
// p toward the sun (common/clouds.glsl), so their shadows lie on the sea and the island where
// the layer the sky draws casts them. Evaluated per vertex (the noise's finest cells are 150 m;
// far out, where the vertices lie farther apart along the view, its finer octaves blur), and
// without the cube. With a --skybox the cover the sun passes (sun_light.w) is 0: all of it.
float sun_through_at(vec3 p) {
    return cloud_through(p, frame.sun_dir.xyz, frame.sun_light.w);
}

// The sun's light on a surface facing it at world point `p` (m): through the air and the clouds.
vec3 sun_light_at(vec3 p) {
    return frame.sun_light.rgb * sun_through_at(p);
}

// The sky's light on a surface whose normal is n (irradiance / π): the sky cube along the normal
// and toward the zenith, a cheap stand-in for the cosine-weighted hemisphere. `zenith`: the
// sky cube toward the zenith, which a shader that has it at hand passes (one cube lookup a
// pixel fewer: 0.45 ms a frame of the water pass at `low` on lavapipe).
vec3 sky_ambient_under(vec3 n, vec3 zenith) {
    return 0.5 * (sky_lookup(normalize(n + vec3(0.0, 1.0, 0.0))) + zenith);
}
vec3 sky_ambient(vec3 n) { return sky_ambient_under(n, sky_lookup(vec3(0.0, 1.0, 0.0))); }

// Aerial perspective over the sea: what `dist` metres of air at sea level let through of what is
// behind them (Koschmieder 1924: L = L_object · T + L_horizon · (1 − T), the sky at the horizon
// standing for the air light of an endless path), T = exp(−β d) with the atmosphere's own
// extinction at sea level (src/shared.rs: Rayleigh scattering and the aerosols' extinction), so
// blue hazes first and the sky above the horizon stays brighter than the sea under it. Returns
// 1 − T, the horizon's share.
vec3 aerial_haze(float dist) {
    return 1.0 - exp(-dist * (RAYLEIGH_SCATTERING + MIE_EXTINCTION));
}
