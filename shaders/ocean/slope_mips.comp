#version 460
// The normal images' mip levels 1–5 (src/ocean/simulation/slope_mips.rs): each texel the mean
// of the 2x2 texels of the level below, so level l holds the mean of 2^l x 2^l texels of level
// 0 — the slopes, the Jacobian and the foam a pixel covering that much water sees. water.frag
// samples the level the pixel's footprint asks for, along the view and across it, instead of
// fading a cascade's slopes out as a whole once its shortest waves pass the footprint.
// One workgroup reduces a 32x32 block of level 0 through shared memory, down to one texel of
// level 5; the image has at least 32 texels a side (N > 64: `slope_levels`).
layout(local_size_x = 16, local_size_y = 16) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2DArray level0;
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2DArray level1;
layout(set = 0, binding = 2, rgba32f) uniform writeonly image2DArray level2;
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2DArray level3;
layout(set = 0, binding = 4, rgba32f) uniform writeonly image2DArray level4;
layout(set = 0, binding = 5, rgba32f) uniform writeonly image2DArray level5;

shared vec4 block[16][16];

void store(int level, ivec3 p, vec4 v) {
    switch (level) {
    case 2: imageStore(level2, p, v); break;
    case 3: imageStore(level3, p, v); break;
    case 4: imageStore(level4, p, v); break;
    default: imageStore(level5, p, v); break;
    }
}

void main() {
    ivec2 local = ivec2(gl_LocalInvocationID.xy);
    int layer = int(gl_WorkGroupID.z);
    ivec2 q = 2 * ivec2(gl_GlobalInvocationID.xy);
    vec4 mean = 0.25 * (imageLoad(level0, ivec3(q, layer))
                      + imageLoad(level0, ivec3(q + ivec2(1, 0), layer))
                      + imageLoad(level0, ivec3(q + ivec2(0, 1), layer))
                      + imageLoad(level0, ivec3(q + ivec2(1, 1), layer)));
    imageStore(level1, ivec3(gl_GlobalInvocationID.xy, layer), mean);
    block[local.y][local.x] = mean;
    // Level l's 32 >> l texels of this block a side, from level l − 1's in `block`.
    for (int level = 2; level <= 5; ++level) {
        int side = 32 >> level;
        bool inside = all(lessThan(local, ivec2(side)));
        barrier();
        if (inside) {
            ivec2 s = 2 * local;
            mean = 0.25 * (block[s.y][s.x] + block[s.y][s.x + 1]
                         + block[s.y + 1][s.x] + block[s.y + 1][s.x + 1]);
        }
        barrier();
        if (inside) {
            block[local.y][local.x] = mean;
            store(level, ivec3(ivec2(gl_WorkGroupID.xy) * side + local, layer), mean);
        }
    }
}
