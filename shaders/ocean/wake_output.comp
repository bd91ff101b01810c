#version 460
// The wake for the water and the height queries (src/ocean/wake.rs): per texel of the slot's wake
// image (h, ∂h/∂x, ∂h/∂z, foam), the slopes by central differences (one-sided at the grid's edge,
// inside the absorbing layer where the wake has died out).
//
// The foam: the previous image's, carried over the grid's move, spreading (the turbulence widens
// the trail: D = FOAM_SPREAD_M2_S) and fading as e^(−Δt/τ), and new
// foam where the hull churns the water (its pressure patch, above a walking pace) and where the
// wake's waves are steep enough to break (slopes from 0.3 to 0.45, toward the Stokes limit's
// 0.44 of ka).
layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, set = 0, binding = 0) readonly buffer State { vec2 z[]; };
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2DArray wake;
layout(set = 0, binding = 2, rgba32f) uniform readonly image2DArray previous;
layout(push_constant) uniform Params {
    vec2 boat;          // the boat's centre from texel (0, 0) (m)
    vec2 course;        // its unit course (x, z)
    ivec2 shift;        // texels the grid moved since the previous image
    float spacing;      // texel (m)
    float dt;           // time since the previous image (s)
    float decay_s;      // the foam's e-folding time (s)
    float spread;       // the foam's diffusion over the step, D Δt / spacing² (≤ 1/4)
    float churn;        // the hull's foam where its pressure is full (0: none)
    float sigma_length; // the pressure patch's σ along the course (m)
    float sigma_beam;   // and across it (m)
    uint n;
} params;

// The previous image's foam at texel t (0 off the grid).
float previous_foam(ivec2 t) {
    bool inside = all(greaterThanEqual(t, ivec2(0))) && all(lessThan(t, ivec2(params.n)));
    return inside ? imageLoad(previous, ivec3(t, 0)).w : 0.0;
}

float height(int i, int j) {
    int n = int(params.n);
    return z[clamp(j, 0, n - 1) * n + clamp(i, 0, n - 1)].x;
}

void main() {
    uint n = params.n;
    ivec2 id = ivec2(gl_GlobalInvocationID.xy);
    if (id.x >= int(n) || id.y >= int(n)) {
        return;
    }
    float h = height(id.x, id.y);
    float sx = (height(id.x + 1, id.y) - height(id.x - 1, id.y)) / (2.0 * params.spacing);
    float sz = (height(id.x, id.y + 1) - height(id.x, id.y - 1)) / (2.0 * params.spacing);
    // Carried over the grid's move, spread by the turbulence (an explicit diffusion step) and
    // fading.
    ivec2 from = id + params.shift;
    float centre = previous_foam(from);
    float around = previous_foam(from + ivec2(1, 0)) + previous_foam(from - ivec2(1, 0))
                 + previous_foam(from + ivec2(0, 1)) + previous_foam(from - ivec2(0, 1));
    float foam = (centre + params.spread * (around - 4.0 * centre)) * exp(-params.dt / params.decay_s);
    vec2 d = vec2(id) * params.spacing - params.boat;
    float along = dot(d, params.course) / params.sigma_length;
    float across = (d.y * params.course.x - d.x * params.course.y) / params.sigma_beam;
    float hull = exp(-0.5 * (along * along + across * across));
    foam = max(foam, params.churn * smoothstep(0.2, 0.6, hull));
    foam = max(foam, smoothstep(0.3, 0.45, length(vec2(sx, sz))));
    imageStore(wake, ivec3(id, 0), vec4(h, sx, sz, foam));
}
