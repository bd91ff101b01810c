#version 460
// The wake's step in space (src/ocean/wake.rs), after the inverse FFT: the texels the grid's
// move brought in are zeroed (the spectrum's phase shifts the grid periodically, so they hold
// the far edge's water, not this water), the boat's hull presses
// on the water (φ −= Δt p/ρ, linearized Bernoulli), and the absorbing layer at the grid's edge
// damps h and φ by e^{−σΔt}, σ growing as the square of the depth into the layer, so the wake
// leaves the periodic grid instead of coming back in at the other side.
layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, set = 0, binding = 0) buffer State { vec2 z[]; };
layout(push_constant) uniform Params {
    vec2 boat;           // the boat's centre from texel (0, 0) (m)
    vec2 course;         // its unit course (x, z)
    ivec2 shift;         // the grid's move this step (texels): texel i held texel i + shift
    float dt;            // step (s)
    float pressure;      // p0/ρ under the hull's centre (m²/s²); 0: no boat
    float sigma_length;  // the pressure patch's σ along the course (m)
    float sigma_beam;    // and across it (m)
    float spacing;       // texel (m)
    float sponge_rate;   // σ at the very edge (1/s)
    uint sponge_texels;  // width of the layer
    uint n;
    uint reset;          // 1: zero the state instead (the first step of a run)
} params;

void main() {
    uint n = params.n;
    uvec2 id = gl_GlobalInvocationID.xy;
    if (id.x >= n || id.y >= n) {
        return;
    }
    uint at = id.y * n + id.x;
    if (params.reset != 0u) {
        z[at] = vec2(0.0);
        return;
    }
    ivec2 from = ivec2(id) + params.shift;
    bool inside = all(greaterThanEqual(from, ivec2(0))) && all(lessThan(from, ivec2(n)));
    vec2 v = inside ? z[at] : vec2(0.0);
    vec2 d = vec2(id) * params.spacing - params.boat;
    float along = dot(d, params.course) / params.sigma_length;
    float across = (d.y * params.course.x - d.x * params.course.y) / params.sigma_beam;
    v.y -= params.dt * params.pressure * exp(-0.5 * (along * along + across * across));
    uint edge = min(min(id.x, id.y), min(n - 1u - id.x, n - 1u - id.y));
    float depth = edge < params.sponge_texels
        ? float(params.sponge_texels - edge) / float(params.sponge_texels)
        : 0.0;
    z[at] = v * exp(-params.sponge_rate * depth * depth * params.dt);
}
