// What the sea reflects from above (surface/water.frag): the reflection texture, blurred by the
// slopes the pixel does not resolve and leaning toward the sky the visible facets face, the sky
// past the texture's edge (the vertices'), and the sky in place of the objects that stand nearer
// than the sea point. Needs common/frame.glsl (VIEW, frame, sky_lookup, view_ray) and
// common/glitter.glsl (mean_visible_slope, normal_tail) included before it, the samplers
// `reflection_colour` (layer 0: the reflection as drawn; layer l: blurred over 2^l rows in its top
// H / 2^l rows, Recorder::halve_down_layers; alpha: the share of objects) and `reflection_sky`
// (the sky its objects hide; alpha: that share times log2 of their distance), layered and blurred
// alike (src/render/passes/reflection_distance.rs), declared before it (no include guards), and
// runs in a fragment shader drawing the surface (gl_FragCoord.z: its depth).

// The reflection's `image` (colour or sky) at `uv` (of the view) from layer `layer`,
// whose top max(⌊h / 2^layer⌋, 1) rows of the `h` hold it (the rows below are not written: the
// lookup stays half a row inside).
vec4 blurred_layer(sampler2DArray image, vec2 uv, float layer, float h) {
    float rows = max(floor(h / exp2(layer)), 1.0);
    float y = clamp(uv.y * rows, 0.5, rows - 0.5) / h;
    return textureLod(image, vec3(uv.x, y, layer), 0.0);
}

// The reflection's `image` at `uv` blurred by the fractional layer `layer`: its two nearest
// layers mixed (`size`: the image's texels and layers; the last layer blurs no further).
vec4 blurred(sampler2DArray image, vec2 uv, float layer, vec3 size) {
    float below = floor(layer);
    float above = min(below + 1.0, size.z - 1.0);
    return mix(blurred_layer(image, uv, below, size.y), blurred_layer(image, uv, above, size.y),
               layer - below);
}

// Of the objects `distances` (the reflection's, blurred as its colour at the same place and
// layers: their share α and α·u, u = log2(distance / near)) say the lookup mixed in, the share
// standing nearer than the surface point drawn (gl_FragCoord.z: its depth, near / distance).
// The surface and the reflection's mirrored camera share a projection, so an object's distance
// there is its mirror image's in this view: it stands nearer than the surface point where that
// distance is the smaller (along the same ray the mirror image stands beyond the object). The
// objects of a kernel are taken at their mean u: all nearer or all beyond, but for a ramp
// NEARER_RAMP wide in u around the surface point's (±7 % in distance), so that the cut does not
// alias where the surface's distance crosses theirs.
const float NEARER_RAMP = 0.2;
float nearer_objects(vec2 distances) {
    float mean_u = distances.y / distances.x;
    float surface_u = -log2(gl_FragCoord.z);
    return clamp(0.5 + (surface_u - mean_u) / NEARER_RAMP, 0.0, 1.0);
}

// The reflection seen at the point `rel_pos` (camera-relative, m) of the surface, `height` (m)
// above the still water level, toward the eye along `v`, with the slopes' screen-space offset
// `offset` and the unresolved slopes' mean square `along_ms` in the plane of incidence.
//
// The reflection texture mirrors the scene about the still water level. A point of the
// surface h above that level mirrors it about its own height instead: the image of what
// stands near it lies 2h lower, where the still-water mirror shows (P − 2h ŷ). Looking it
// up there keeps the reflections of the pillars and the buoy on the faces of big waves.
//
// The slopes the pixel does not resolve (Cox & Munk's mean square less what the cascades
// drawn here carry) scatter the reflected ray: a facet tilted by s in the plane of
// incidence turns it by 2s up or down, one tilted across it by 2s·cos θ sideways (θ the
// angle of incidence, near 90° where the sea meets the sky). So the mirror image spreads
// by 2σ·f texels up and down (σ² the unresolved mean square along the view, f the
// reflection's texels per radian): vertical streaks. The reflection's layers blur it over
// 2^l rows (a kernel of standard deviation 2^l / 2 once filtered), so the lookup blends the
// two layers around l = log2(2 · 2σf). The sideways spread is left out (small but near the
// camera).
//
// The facets the eye sees lean toward it (`mean_visible_slope`: s̄), so they reflect higher
// sky: the reflected ray turns up by 2·atan s̄, its mirror image down as far (−v turned
// toward −ŷ; both projected as points at infinity). About the mean plane (tan e): about the
// drawn normal it would follow the drawn slopes the wrong way and alias far out.
// The blur (σ: half a texel of the layer's ⌊H/2^l⌋ rows stretched over H) reaches past the
// texture's bottom edge (higher sky) for a share 1 − Φ(a), a = (H − y)/σ (y in rows): there
// `edge_sky`, the sky along the mirrored ray turned up by the lean (common/water_vertex.glsl,
// per vertex: those rays point high, where the sky changes slowly). Until 2026-12-05 each
// pixel turned the ray on to that share's mean row, y + σφ(a)/(1 − Φ(a)), a degree or so more.
vec3 sea_reflection(vec3 rel_pos, float height, vec2 screen, vec2 offset, vec3 v, float along_ms,
                    vec3 edge_sky) {
    vec4 mirror = VIEW.view_proj * vec4(rel_pos - vec3(0.0, 2.0 * height, 0.0), 1.0);
    vec2 mirror_uv = mirror.w > 0.0 ? mirror.xy / mirror.w * 0.5 + 0.5 : screen;
    vec3 reflection_size = vec3(textureSize(reflection_colour, 0));
    float texels_per_rad = frame.lod.x * reflection_size.y * frame.viewport.w;
    float spread = 2.0 * sqrt(along_ms) * texels_per_rad;
    float layer = clamp(log2(max(2.0 * spread, 1.0)), 0.0, reflection_size.z - 1.0);
    float rise = clamp(v.y, 1e-3, 0.9999);
    float lean_s = mean_visible_slope(rise / sqrt(1.0 - rise * rise), sqrt(along_ms));
    vec3 down = vec3(0.0, -1.0, 0.0) + v.y * v; // −ŷ less its part along −v
    down /= max(length(down), 1e-4);
    // cos and sin of 2·atan s̄, without the trigonometry: (1 − s̄², 2s̄) / (1 + s̄²).
    vec3 turned = (-v * (1.0 - lean_s * lean_s) + down * (2.0 * lean_s)) / (1.0 + lean_s * lean_s);
    vec4 seen = VIEW.view_proj * vec4(-v, 0.0);
    vec4 lean = VIEW.view_proj * vec4(turned, 0.0);
    vec2 lean_uv = lean.w > 1e-4 ? (lean.xy / lean.w - seen.xy / seen.w) * 0.5 : vec2(0.0, 1.0);
    vec2 leaned_uv = mirror_uv + offset + lean_uv;
    vec2 reflect_uv = clamp(leaned_uv, 0.001, 0.999);
    vec4 colour = blurred(reflection_colour, reflect_uv, layer, reflection_size);
    vec3 c_reflect = colour.rgb;
    // What stands nearer than this sea point cannot be in its reflection: the reflected ray
    // leaves toward what lies beyond. The blur and the lean took the far sea's lookup onto the
    // mirror images of near objects (the boat, the buoy): a darker column up to the horizon.
    // Where the kernel holds objects (their share α over 0), the share n of them nearer than
    // the sea point (`nearer_objects`) gives way to the sky behind them: with the objects there
    // of one colour O and the sky S, C = (1 − α)S + αO becomes (1 − α)S + α(1 − n)O + αnS =
    // mix(C, S, n), S from the sky image blurred by the same kernel (3 sky cube lookups over
    // its σ had cost the water 2 ms a frame at `low` on lavapipe; one left a faint column).
    // α is the colour's alpha and α·u the sky's, so the lookups are the ones the mix needs (an
    // image of the distances of its own had cost the water 2 lookups more, 0.4 ms at `low`).
    if (colour.a > 1e-3) {
        vec4 behind = blurred(reflection_sky, reflect_uv, layer, reflection_size);
        c_reflect = mix(c_reflect, behind.rgb, nearer_objects(vec2(colour.a, behind.a)));
    }
    float below = floor(layer);
    float above = min(below + 1.0, reflection_size.z - 1.0);
    vec2 texel = reflection_size.y / max(floor(reflection_size.y / exp2(vec2(below, above))), 1.0);
    float sigma = 0.5 * mix(texel.x, texel.y, layer - below);
    float to_edge = (1.0 - leaned_uv.y) * reflection_size.y / sigma; // a
    // The share past the edge takes the sky the vertices looked up (`edge_sky`): on GPUs a
    // branch here skips most pixels' blocks, but lavapipe ran its cube lookup and turn at
    // every pixel (0.5 ms of the water pass at `low`, 2026-12-05).
    c_reflect = mix(c_reflect, edge_sky, normal_tail(to_edge));
    return c_reflect;
}
