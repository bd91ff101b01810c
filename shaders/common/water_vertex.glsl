// The water's vertex, the same for both geometries (surface/water.tese, tessellated patches;
// surface/water_clipmap.vert, the clipmap's tiles): the point xz of the sea plane (relative to
// the grid centre, common/water.glsl) displaced by every cascade's displacement image (repeat
// sampler, textureLod 0), scaled by what the depth of the terrain under the point makes of the
// waves (common/shore.glsl). Outputs: eye-relative position, undisplaced xz relative to the grid
// centre (normal lookups), the displacement (debug view, surf), the depth and shoaling
// coefficient (water.frag finishes the shore), how much of the point lies in a natural slick
// and how gusty the wind is there.
// Needs common/frame.glsl, water.glsl, terrain.glsl and shore.glsl included before it.
#include "slicks.glsl"
#include "gusts.glsl"
#include "glitter.glsl"

layout(location = 0) out vec3 out_rel_pos;
layout(location = 1) out vec2 out_xz;
layout(location = 2) out vec3 out_displacement;
layout(location = 3) out vec2 out_shore; // the water's depth (m) and K_s here
// The share of the sun's light the clouds above the vertex let through (frame.glsl's
// `sun_through_at`: the clouds' shadows), and the frame's sky at the zenith (the same at every
// vertex; cube lookups and the clouds' noise here cost a fraction of what they cost per pixel).
layout(location = 4) out float out_sun_through;
layout(location = 5) flat out vec3 out_sky_zenith;
// The surf's bores (common/shore.glsl): x their phase θ (waves), y their share of the sea
// (0–1), zw θ's gradient over the water (waves per metre, toward deeper water).
layout(location = 6) out vec4 out_surf;
// x: how much of the point lies in a natural slick (common/slicks.glsl); y: the local wind's
// excess g over the mean (common/gusts.glsl). Both are patches hundreds of metres wide, so the
// vertices resolve them.
layout(location = 7) out vec2 out_patches;
// The sky at the horizon behind the point, as the eye sees it (toward the point's azimuth, just
// over the horizon): it hazes the far sea and lights the foam from behind. It changes slowly
// with the azimuth, so the pixels take it between the vertices (a cube lookup a pixel had cost
// the water pass 0.5 ms a frame at `low` on lavapipe).
layout(location = 8) out vec3 out_horizon;
// The sky the reflection shows past its texture's bottom edge (common/reflection.glsl): along
// the ray the point mirrors toward the eye, turned up by twice the mean slope toward the eye of
// the facets the eye sees (`mean_visible_slope`) for Cox & Munk's mean square along the view.
// The pixels take off the slopes the cascades draw there; here they are left in, so near the
// camera the ray turns a little higher. Those rays point high, where the sky changes slowly, so
// the pixels take it between the vertices (a cube lookup and the turn's trigonometry a pixel
// had cost the water pass 0.5 ms a frame at `low` on lavapipe).
layout(location = 9) out vec3 out_edge_sky;
// Which triangle a pixel belongs to, for `--view triangles` (water.frag's VIEW_TRIANGLES): the
// tile or patch (flat), and the point's coordinates on its lattice of cells (interpolated: the
// pixel's cell is their floor, its triangle the side of the cell's diagonal). The tessellated
// patches give none (the tessellator's triangles lie on no lattice): the view colours patches.
layout(location = 10) flat out uint out_tile;
layout(location = 11) out vec2 out_lattice;

// `out_edge_sky` for the point at `rel` (eye-relative, m) in a slick of share `slick`, under
// the local wind's excess `gust`.
vec3 edge_sky(vec3 rel, float slick, float gust) {
    vec3 v = -rel / max(length(rel), 1e-6); // toward the eye
    float flat_len = length(v.xz);
    vec2 along = flat_len > 1e-5 ? -v.xz / flat_len : vec2(1.0, 0.0);
    vec3 clean = gust_slopes(gust);
    float along_ms = slope_covariance(mix(clean.x, frame.slicks.x, slick),
                                      mix(clean.yz, frame.slicks.yz, slick), along).x;
    float rise = clamp(v.y, 1e-3, 0.9999);
    float lean = mean_visible_slope(rise / sqrt(1.0 - rise * rise), sqrt(max(along_ms, 1e-3)));
    float turn = min(2.0 * atan(lean), acos(clamp(v.y, 0.0, 1.0)));
    vec3 down = vec3(0.0, -1.0, 0.0) + v.y * v; // −ŷ less its part along −v
    down /= max(length(down), 1e-4);
    vec3 ray = -v * cos(turn) + down * sin(turn);
    return sky_lookup(ray * vec3(1.0, -1.0, 1.0));
}

// The vertex at `xz` (grid-relative, m), point `lattice` of tile or patch `tile`.
void emit_water_vertex(vec2 xz, uint tile, vec2 lattice) {
    out_tile = tile;
    out_lattice = lattice;
    vec3 eye = water_eye();
    vec2 offset = xz - eye.xz;
    // The camera's world xz plus the offset: the terrain is placed in world coordinates.
    vec2 world_xz = frame.views[0].eye.xz + offset;
    // Past the island's slope the floor is flat: its depth and K_s come with the frame.
    float depth = frame.open_sea.x;
    float ks = frame.open_sea.y;
    vec4 surf = vec4(0.0);
    if (near_island(world_xz)) {
        depth = water_level() - terrain_height(world_xz);
        ks = shore_shoaling(depth);
        surf = shore_surf(world_xz, depth, shore_waves_at(ks, depth).y, frame.shore.w);
    }
    vec3 waves = shore_waves_at(ks, depth);
    vec3 d = waves.x * ocean_displacement_at(xz, length(offset));
    // Where the waves have broken, a share surf.y of the sea is bores, as high as the sea
    // there (SURF_BORE); the shares add in quadrature, so the local Hs holds. Their face no
    // sharper than the triangles hold: about frame.lod.y pixels apart.
    float spacing_m = frame.lod.y * length(vec3(offset.x, water_level() - eye.y, offset.y))
                      / frame.lod.x;
    float bore = SURF_BORE * waves.z * shore_bore(surf.x, shore_front(surf.zw, spacing_m)).x;
    d = d * sqrt(1.0 - surf.y * surf.y) + vec3(0.0, surf.y * bore, 0.0);
    vec3 rel = vec3(offset.x + d.x, water_level() + d.y - eye.y, offset.y + d.z);
    out_rel_pos = rel;
    out_xz = xz;
    out_displacement = d;
    // Interpolated to the pixels (the surf, water.frag): dry land counts as just dry, so
    // the waterline between a vertex on a hill and one at sea lies near the shore's.
    out_shore = vec2(max(depth, -1.0), ks);
    out_surf = surf;
    out_sun_through = sun_through_at(frame.views[0].eye.xyz + rel);
    out_patches = vec2(slick_at(world_xz), gust_at(world_xz));
    out_sky_zenith = sky_lookup(vec3(0.0, 1.0, 0.0));
    vec2 away = rel.xz / max(length(rel), 1e-6); // −v.xz, v toward the eye
    out_horizon = sky_lookup(normalize(vec3(away.x, 0.002, away.y)));
    out_edge_sky = edge_sky(rel, out_patches.x, out_patches.y);
    gl_Position = frame.views[0].view_proj * vec4(rel, 1.0);
}
