// Wind gusts (src/render/gusts.rs, its CPU twin, has the law and the papers): patches of sea
// under a stronger or weaker wind, carried downwind at the mean wind. `gust_at` gives the local
// wind's excess g over the mean at the world point xz (m): the wind there is U10·(1 + g). The
// clouds' fractal noise in a space stretched along the wind (cells GUST_ALONG_M by
// GUST_ACROSS_M), made zero-mean and of unit variance, times the gusts' strength σ_u/U10
// (frame.gusts.y; 0 without gusts). The water's vertices take it (common/water_vertex.glsl);
// water.frag gives the unresolved slopes Cox & Munk's mean square at the local wind and the
// whitecaps Monahan's coverage (`gust_foam`).
// Needs common/frame.glsl (and so clouds.glsl) included before it.
#ifndef GUSTS_GLSL
#define GUSTS_GLSL

// GUST_ALONG_M, GUST_ACROSS_M, GUST_NOISE_OFFSET_X, _Y, GUST_NOISE_MEAN, _STD: src/shared.rs.

float gust_at(vec2 xz) {
    // No branch for "no gusts" (strength 0): see slick_at (common/slicks.glsl) for why.
    float n = wind_shape(xz, frame.slick_space.zw, vec2(GUST_ALONG_M, GUST_ACROSS_M),
                         frame.gusts.x, vec2(GUST_NOISE_OFFSET_X, GUST_NOISE_OFFSET_Y));
    return frame.gusts.y * (n - GUST_NOISE_MEAN) / GUST_NOISE_STD;
}

// The sea's mean-square slope (x) and its excess along the wind (yz, as frame.sea_slopes) at
// the local wind U10·(1 + g): Cox & Munk's clean-surface fits are linear in the wind, so the
// frame's total plus g times its growth (frame.gusts.z), and its excess times 1 + g times the
// excess' growth over the excess (frame.sea_slopes.z), none below none (under 2.4 m/s).
vec3 gust_slopes(float g) {
    return vec3(frame.light.y + g * frame.gusts.z,
                frame.sea_slopes.xy * max(1.0 + g * frame.sea_slopes.z, 0.0));
}

// The foam layer's reflectance R (water.frag's `foam_layer`: the share of the water the foam
// covers, its lace averaged over the pixel far off) under the local wind: Monahan &
// O'Muircheartaigh's (1980) whitecap coverage grows as U^3.41, so the local foam is r times the
// sea's, r = (1 + g)^3.41 over its mean over the sea (frame.gusts.w: the sea's mean coverage
// stays Monahan's at U10, a mean over the gusts). r times as much foam laid at random leaves
// (1 − R)^r of the water uncovered: thin foam scales by r, opaque foam stays opaque. The crests
// that break are the lattice's; a gust lays more foam where they do. Without gusts
// (strength 0) R is returned as it was.
float gust_foam(float opacity, float g) {
    float r = pow(max(1.0 + g, 0.0), WHITECAP_WIND_EXPONENT) * frame.gusts.w;
    return frame.gusts.y == 0.0 ? opacity : 1.0 - pow(1.0 - opacity, r);
}
#endif
