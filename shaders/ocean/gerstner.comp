#version 460
// Gerstner waves, analytic (seed 000 §2; steepness Q per wave from seed 004), written into the
// same images as the FFT ocean (layer 0), so the renderer does not care which model made them.
// The grid point (α, β) = origin + (n, m) L / N moves to
//   x = α − Σ Q (kx/k) a sin θ,  z = β − Σ Q (kz/k) a sin θ,  y = Σ a cos θ,
//   θ = kx α + kz β − ω t − φ,  ω = √(g k), g = 9.8 (seed 000's constant),
// with the normal n = ∂r/∂β × ∂r/∂α (seed 000 writes ∂r/∂α × ∂r/∂β in left-handed (x, z, y)).
// Outputs: displacement (x − α, y, z − β, 0); normals (slopes −n.x/n.y, −n.z/n.y, the Jacobian of
// the horizontal map, foam as in assemble.comp from that Jacobian, the previous frame's read at
// the same world texel: the window moved `shift` texels since). Mirrors src/ocean/gerstner.rs
// `evaluate`.
layout(local_size_x = 8, local_size_y = 8) in;

struct Wave {
    vec4 wave;  // kx, kz (rad/m), amplitude (m), θ at the window origin this frame (rad)
    vec4 extra; // steepness Q, ω (rad/s), k (rad/m), unused
};
layout(std430, set = 0, binding = 0) readonly buffer Waves { Wave waves[]; };
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2DArray displacement;
layout(set = 0, binding = 2, rgba32f) uniform writeonly image2DArray normals;
layout(set = 0, binding = 3, rgba32f) uniform readonly image2DArray previous_normals;
layout(push_constant) uniform Params {
    float window_m;
    float dt_s;
    float foam_threshold;
    float foam_decay_s;
    float foam_gain;
    uint n;
    uint count;
    int shift_x; // whole texels the window moved since the previous frame
    int shift_z;
} params;

void main() {
    uvec3 id = gl_GlobalInvocationID;
    if (id.x >= params.n || id.y >= params.n) {
        return;
    }
    // Offset from the window origin; θ at the origin (kx ox + kz oz − ωt − φ, reduced mod 2π in
    // f64 on the CPU each frame) keeps the float phase precise anywhere in the world.
    vec2 local = vec2(id.xy) * (params.window_m / float(params.n));
    vec3 d = vec3(0.0);
    vec3 ta = vec3(1.0, 0.0, 0.0); // ∂r/∂α
    vec3 tb = vec3(0.0, 0.0, 1.0); // ∂r/∂β
    for (uint i = 0u; i < params.count; ++i) {
        vec4 w = waves[i].wave;
        vec4 e = waves[i].extra;
        if (e.z == 0.0) {
            continue;
        }
        float theta = w.x * local.x + w.y * local.y + w.w;
        float s = sin(theta);
        float c = cos(theta);
        float qa = e.x * w.z / e.z;
        d.x -= w.x * qa * s;
        d.z -= w.y * qa * s;
        d.y += w.z * c;
        ta -= vec3(w.x * w.x * qa * c, w.x * w.z * s, w.x * w.y * qa * c);
        tb -= vec3(w.x * w.y * qa * c, w.y * w.z * s, w.y * w.y * qa * c);
    }
    vec3 nrm = cross(tb, ta);
    float ny = max(nrm.y, 1e-6);
    float jacobian = ta.x * tb.z - tb.x * ta.z;
    ivec3 texel = ivec3(id.xy, 0);
    ivec2 previous = texel.xy + ivec2(params.shift_x, params.shift_z);
    float kept = 0.0;
    if (all(greaterThanEqual(previous, ivec2(0))) && all(lessThan(previous, ivec2(params.n)))) {
        kept = imageLoad(previous_normals, ivec3(previous, 0)).w * exp(-params.dt_s / params.foam_decay_s);
    }
    float source = clamp((params.foam_threshold - jacobian) * params.foam_gain, 0.0, 1.0);
    float foam = max(kept, source);
    imageStore(displacement, texel, vec4(d, 0.0));
    imageStore(normals, texel, vec4(-nrm.x / ny, -nrm.z / ny, jacobian, foam));
}
