//! The clipmap water's tiles: which parts of the sea plane are drawn at which level of detail
//! this frame. Continuous distance-dependent level of detail, after Strugar 2009 ("Continuous
//! Distance-Dependent Level of Detail for Rendering Heightmaps", JGT 14(4)), on a quadtree
//! fixed to the world:
//! - Level L's cells are `finest_cell_m · 2^L` wide, its nodes `grid` cells wide; a node of
//!   level L+1 is four of level L. A node is drawn at level L where it lies within `range(L)`
//!   of the camera (3D distance to the sea plane at the water level) but not within
//!   `range(L-1)`; a node that straddles `range(L-1)` draws the quarters that lie beyond it
//!   and hands the others to its children (Strugar's `LODSelect`).
//! - Every tile drawn is one such quarter, `grid / 2` cells wide (`Tile`), one instance of
//!   one index buffer (`QUARTER` in shaders/surface/water_clipmap.vert).
//! - The vertex shader morphs each vertex of level L toward level L+1's lattice (its odd
//!   lattice points slide onto their even neighbours) as its distance d goes from
//!   `morph_start(L)` to `morph_end(L) = range(L)`: `k = clamp((d - start) / (end - start))`.
//!   The morph depends on the vertex's world position only, so the meshes change
//!   continuously as the camera moves (no popping), and:
//!   - where a level-L tile meets a level L+1 tile, every shared point is farther than
//!     range(L) (the L+1 tile lies beyond range(L)): the level-L side is fully morphed,
//!     its vertices are level L+1's lattice points, and no T-junction opens a crack;
//!   - the same points lie in a level-L node, which reaches at most range(L) + √2·node(L)
//!     from the camera (its nearest point within range(L), plus its diagonal): the level
//!     L+1 side is not morphed there yet when `morph_start(L+1) ≥ range(L) + √2·node(L)`;
//!   - a node splits into its children when its nearest point comes within range(L-1): its
//!     vertices are then at most range(L-1) + √2·node(L) away, unmorphed when
//!     `morph_start(L) ≥ range(L-1) + √2·node(L)`, while the children, all beyond
//!     range(L-1), are fully morphed: the same mesh before and after.
//!
//!   Both conditions hold with `morph_start(L) = range(L)·(1/2 + √2/c)` for ranges
//!   `range(L) = c·node(L)`, c > 2√2; `MIN_RANGE_FACTOR` keeps a morph zone of a seventh of
//!   the range at least.
//!
//! Positions: tiles are world-aligned (fixed to the world lattice, so vertices never slide over
//! the waves) and handed to the GPU relative to the water's grid centre (`WaterFrame`), as
//! the tessellated path's are; with power-of-two cell sizes every vertex is exact in f32.

use glam::{Mat4, Vec3, Vec4};

/// Most levels (the morph table's size in water_clipmap.vert).
pub const MAX_LEVELS: usize = 24;
/// Most tiles a frame draws (the per-slot tile buffer's capacity): more than the largest range
/// factor draws with no culling at all (`select` keeps the nearest if ever exceeded).
pub const MAX_TILES: usize = 16384;
/// Smallest range factor c (range(L) = c·node(L)); see the module's doc.
pub const MIN_RANGE_FACTOR: f64 = 4.0;
/// Largest range factor: the tile count grows with c², so cells finer than this allows (tiny
/// `--tess-edge` on a large screen, with tiles already `MAX_QUARTER` wide) are drawn coarser.
pub const MAX_RANGE_FACTOR: f64 = 8.0;
/// Relative margin between the morph's bounds and the distances they must clear: the shader
/// computes distances in f32 (relative error about 1e-7).
const MORPH_MARGIN: f64 = 1e-3;
/// Cells per quarter tile side, smallest and largest (the morph follows each vertex's world
/// lattice parity, which the tile carries: an odd side is fine).
pub const MIN_QUARTER: u32 = 1;
pub const MAX_QUARTER: u32 = 16;
/// Finest cell (m): a power of two (exact lattice arithmetic in f32).
pub const FINEST_CELL_M: f64 = 1.0 / 16.0;
/// How far the clipmap reaches (m): at least the tessellated grid's half-side
/// (FAR_M in shaders/common/water.glsl), to the horizon as it does.
pub const REACH_M: f64 = 20_000.0;

/// How the clipmap is laid out for a frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Layout {
    /// Cells per quarter tile side (the mesh drawn per tile); a node is twice as wide.
    pub quarter: u32,
    /// range(L) / node(L).
    pub range_factor: f64,
    /// Levels: range(levels - 1) reaches `REACH_M`.
    pub levels: u32,
}

impl Layout {
    /// The layout that draws cells about `cell_px` wide (the narrowest, at each level's far
    /// end; twice that at its near end) for a focal length of `focal_px` pixels.
    /// `cell_px` at distance d is `f·cell/d`; at d = range(L) that is `f / (c·2·quarter)`.
    pub fn for_screen(cell_px: f64, focal_px: f64) -> Layout {
        let cells_per_range = cells_per_range(cell_px, focal_px);
        let mut quarter = MIN_QUARTER;
        while quarter * 2 <= MAX_QUARTER
            && cells_per_range / (2.0 * (quarter * 2) as f64) >= MIN_RANGE_FACTOR
        {
            quarter *= 2;
        }
        Layout::with_quarter(quarter, cell_px, focal_px)
    }

    /// The layout with `quarter` cells per tile side (the mesh's, made when the screen size
    /// was last set) for this frame: the range factor follows the focal length, within
    /// `MIN_RANGE_FACTOR..=MAX_RANGE_FACTOR`.
    pub fn with_quarter(quarter: u32, cell_px: f64, focal_px: f64) -> Layout {
        let range_factor = (cells_per_range(cell_px, focal_px) / (2.0 * quarter as f64))
            .clamp(MIN_RANGE_FACTOR, MAX_RANGE_FACTOR);
        let range0 = range_factor * 2.0 * quarter as f64 * FINEST_CELL_M;
        let levels = ((REACH_M / range0).log2().ceil().max(0.0) as u32 + 1).min(MAX_LEVELS as u32);
        Layout {
            quarter,
            range_factor,
            levels,
        }
    }

    /// Cell side of level `level` (m).
    pub fn cell_m(&self, level: u32) -> f64 {
        FINEST_CELL_M * f64::from(1u32 << level)
    }

    /// Node side of level `level` (m): two quarters.
    pub fn node_m(&self, level: u32) -> f64 {
        self.cell_m(level) * f64::from(2 * self.quarter)
    }

    /// Distance within which a node is drawn at `level` or finer (m).
    pub fn range(&self, level: u32) -> f64 {
        self.range_factor * self.node_m(level)
    }

    /// Where level `level`'s vertices start to morph toward level + 1 (m); see the module doc.
    /// `MORPH_MARGIN` keeps the conditions true through the shader's f32 rounding.
    pub fn morph_start(&self, level: u32) -> f64 {
        self.range(level)
            * (0.5 + std::f64::consts::SQRT_2 / self.range_factor)
            * (1.0 + MORPH_MARGIN)
    }

    /// Where level `level`'s vertices are fully morphed (m): just inside its range.
    pub fn morph_end(&self, level: u32) -> f64 {
        self.range(level) * (1.0 - MORPH_MARGIN)
    }

    /// The morph table of water_clipmap.vert: per level, (start, 1 / (end - start)).
    pub fn morph_table(&self) -> [[f32; 4]; MAX_LEVELS] {
        let mut table = [[0.0; 4]; MAX_LEVELS];
        for (level, row) in table.iter_mut().enumerate().take(self.levels as usize) {
            let (start, end) = (self.morph_start(level as u32), self.morph_end(level as u32));
            *row = [start as f32, (1.0 / (end - start)) as f32, 0.0, 0.0];
        }
        table
    }
}

/// c · 2 · quarter, the cells from a level's camera to its range for cells `cell_px` wide there:
/// a cell at distance d is `focal_px · cell / d` pixels wide.
fn cells_per_range(cell_px: f64, focal_px: f64) -> f64 {
    (focal_px / cell_px.max(1.0)).max(1.0)
}

/// One quarter tile to draw: its world corner (the lower x and z) and level.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tile {
    pub corner_m: [f64; 2],
    pub level: u32,
}

impl Tile {
    /// Whether the corner's world lattice index (corner / cell) is odd, per axis: the shader
    /// adds it to a vertex's index in the tile to know which vertices morph.
    pub fn corner_parity(&self, layout: &Layout) -> [u32; 2] {
        let cell = layout.cell_m(self.level);
        self.corner_m
            .map(|c| ((c / cell).round() as i64).rem_euclid(2) as u32)
    }

    /// The tile's `w` in water_clipmap.vert: its level, and its corner's parity in bits 6 and 7.
    pub fn packed_level(&self, layout: &Layout) -> f32 {
        let [px, pz] = self.corner_parity(layout);
        (self.level | px << 6 | pz << 7) as f32
    }
}

/// The camera as the selection sees it.
#[derive(Clone, Copy, Debug)]
pub struct Viewer {
    /// World xz (m).
    pub xz: [f64; 2],
    /// Height above the water level (m; negative under the water).
    pub height_m: f64,
    /// Camera-relative position → clip space (`Camera::view_proj`), for frustum culling;
    /// `None` draws every tile in range (tests).
    pub view_proj: Option<Mat4>,
    /// How far the waves move a point from its rest position (m): the culling margin.
    pub reach_m: f64,
}

impl Viewer {
    /// Distance from the camera to the nearest point of a square at the water level (m).
    fn distance_to(&self, corner: [f64; 2], side: f64) -> f64 {
        let axis = |i: usize| {
            (corner[i] - self.xz[i])
                .max(self.xz[i] - corner[i] - side)
                .max(0.0)
        };
        let (dx, dz) = (axis(0), axis(1));
        (dx * dx + dz * dz + self.height_m * self.height_m).sqrt()
    }

    /// Whether a square of level `level`'s tiles may be on screen: its box raised, lowered and
    /// widened by the waves' reach, and widened by one cell more, as far as the morph moves a
    /// tile's vertices out of its square (a tile whose corner is odd on the level's lattice
    /// slides its low edge onto the even neighbour's).
    fn may_see(&self, corner: [f64; 2], side: f64, cell: f64) -> bool {
        let Some(vp) = self.view_proj else {
            return true;
        };
        let m = self.reach_m + cell;
        let lo = Vec3::new(
            (corner[0] - m - self.xz[0]) as f32,
            (-m - self.height_m) as f32,
            (corner[1] - m - self.xz[1]) as f32,
        );
        let size = Vec3::new(
            (side + 2.0 * m) as f32,
            (2.0 * m) as f32,
            (side + 2.0 * m) as f32,
        );
        let corners: [Vec4; 8] = std::array::from_fn(|i| {
            let pick = Vec3::new((i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32);
            vp * (lo + pick * size).extend(1.0)
        });
        // Outside one clip plane with all 8 corners: culled. Reversed Z: in front of the near
        // plane is z <= w.
        let planes: [fn(Vec4) -> bool; 5] = [
            |c| c.x < -c.w,
            |c| c.x > c.w,
            |c| c.y < -c.w,
            |c| c.y > c.w,
            |c| c.z > c.w,
        ];
        !planes.iter().any(|out| corners.iter().all(|&c| out(c)))
    }
}

/// The quarter tiles to draw for `viewer`: at most `MAX_TILES`, the nearest kept if a frame
/// ever needed more (the range factor's cap keeps it under: `the_tile_count_stays_bounded`).
pub fn select(layout: &Layout, viewer: &Viewer) -> Vec<Tile> {
    let top = layout.levels - 1;
    let node = layout.node_m(top);
    let reach = layout.range(top);
    let first = [0, 1].map(|i| ((viewer.xz[i] - reach) / node).floor() as i64);
    let last = [0, 1].map(|i| ((viewer.xz[i] + reach) / node).floor() as i64);
    let mut tiles = Vec::new();
    for z in first[1]..=last[1] {
        for x in first[0]..=last[0] {
            let corner = [x as f64 * node, z as f64 * node];
            select_node(layout, viewer, corner, top, &mut tiles);
        }
    }
    if tiles.len() > MAX_TILES {
        let side = layout.node_m(0) / 2.0;
        let distance = |t: &Tile| viewer.distance_to(t.corner_m, side * f64::from(1u32 << t.level));
        tiles.sort_by(|a, b| distance(a).total_cmp(&distance(b)));
        log::warn!(
            "the clipmap needed {} tiles; drawing the nearest {MAX_TILES}",
            tiles.len()
        );
        tiles.truncate(MAX_TILES);
    }
    tiles
}

/// Strugar's `LODSelect` for the node at `corner` of `level`: false when the node lies beyond
/// range(level) (its parent draws it); true when it or its children drew it (or it is off
/// screen).
fn select_node(
    layout: &Layout,
    viewer: &Viewer,
    corner: [f64; 2],
    level: u32,
    tiles: &mut Vec<Tile>,
) -> bool {
    let side = layout.node_m(level);
    let cell = layout.cell_m(level);
    let distance = viewer.distance_to(corner, side);
    if distance > layout.range(level) {
        return false;
    }
    if !viewer.may_see(corner, side, cell) {
        return true;
    }
    let half = side / 2.0;
    let quarters = [[0.0, 0.0], [half, 0.0], [0.0, half], [half, half]]
        .map(|[dx, dz]| [corner[0] + dx, corner[1] + dz]);
    if level == 0 || distance > layout.range(level - 1) {
        tiles.extend(quarters.map(|q| Tile { corner_m: q, level }));
        return true;
    }
    for q in quarters {
        if !select_node(layout, viewer, q, level - 1, tiles) && viewer.may_see(q, half, cell) {
            tiles.push(Tile { corner_m: q, level });
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    fn viewer(x: f64, z: f64, h: f64) -> Viewer {
        Viewer {
            xz: [x, z],
            height_m: h,
            view_proj: None,
            reach_m: 0.0,
        }
    }

    /// The morph factor water_clipmap.vert computes for a level-`level` vertex at `p`.
    fn morph(layout: &Layout, v: &Viewer, level: u32, p: [f64; 2]) -> f64 {
        let d = v.distance_to(p, 0.0);
        let (start, end) = (layout.morph_start(level), layout.morph_end(level));
        ((d - start) / (end - start)).clamp(0.0, 1.0)
    }

    /// Where a level-`level` lattice point (i, j) of a tile at `corner` lands after the
    /// shader's morph (odd lattice points, by world index, slide toward their lower even
    /// neighbour).
    fn morphed(layout: &Layout, v: &Viewer, t: &Tile, i: u32, j: u32) -> [f64; 2] {
        let cell = layout.cell_m(t.level);
        let p = [
            t.corner_m[0] + i as f64 * cell,
            t.corner_m[1] + j as f64 * cell,
        ];
        let k = morph(layout, v, t.level, p);
        let [px, pz] = t.corner_parity(layout);
        [
            p[0] - ((i + px) & 1) as f64 * cell * k,
            p[1] - ((j + pz) & 1) as f64 * cell * k,
        ]
    }

    #[test]
    fn layouts_follow_the_screen_and_keep_the_morph_conditions() {
        for (px, f) in [
            (16.0, 623.5),
            (24.0, 467.6),
            (48.0, 311.8),
            (2.0, 2000.0),
            (256.0, 100.0),
        ] {
            let l = Layout::for_screen(px, f);
            assert!(
                l.quarter.is_power_of_two() && (MIN_QUARTER..=MAX_QUARTER).contains(&l.quarter)
            );
            assert!(l.range_factor >= MIN_RANGE_FACTOR, "{l:?}");
            assert!(l.range(l.levels - 1) >= REACH_M, "{l:?}");
            assert!(l.levels as usize <= MAX_LEVELS);
            // Cells at a level's far end (d = range) are px wide unless the factor was clamped:
            // raised to the smallest (finer cells), or lowered to the largest (coarser).
            let narrowest = f * l.cell_m(3) / l.range(3);
            if l.range_factor == MIN_RANGE_FACTOR {
                assert!(narrowest <= px, "{l:?}");
            } else if l.range_factor == MAX_RANGE_FACTOR {
                assert!(narrowest >= px, "{l:?}");
            } else {
                assert!((narrowest - px).abs() < 1e-9 * px, "{l:?}: {narrowest} px");
            }
            assert!(l.range_factor <= MAX_RANGE_FACTOR);
            for level in 1..l.levels {
                let diag = std::f64::consts::SQRT_2 * l.node_m(level);
                // Splitting keeps the mesh; a coarser neighbour is unmorphed at the seam.
                assert!(l.morph_start(level) >= l.range(level - 1) + diag - 1e-9);
                assert!(l.morph_start(level) >= l.range(level - 1) + diag / 2.0);
                assert!(l.morph_start(level) < l.morph_end(level));
            }
        }
    }

    /// Where tiles of two levels meet, the finer side's boundary vertices, as drawn after the
    /// morph, land on the coarser lattice and the coarser side is not morphed: every edge of
    /// the seam is an edge of both meshes (no crack), for cameras at several heights and places.
    /// Levels further apart never meet.
    #[test]
    fn tiles_meet_without_cracks() {
        // Tiles of 4 cells (--quality high's) and of 1 (low's: odd corners morph too).
        for layout in [
            Layout::for_screen(16.0, 623.5),
            Layout::for_screen(48.0, 311.8),
        ] {
            assert!(layout.quarter == 4 || layout.quarter == 1, "{layout:?}");
            tiles_of_layout_meet_without_cracks(&layout);
        }
    }

    fn tiles_of_layout_meet_without_cracks(layout: &Layout) {
        let layout = *layout;
        for v in [
            viewer(0.3, -0.7, 12.0),
            viewer(1234.5, 77.25, 2.0),
            viewer(-900_000.0, 900_000.0, 40.0),
            viewer(17.0, 3.0, 600.0),
        ] {
            let tiles = select(&layout, &v);
            assert!(
                !tiles.is_empty() && tiles.len() < MAX_TILES,
                "{}",
                tiles.len()
            );
            eprintln!("camera {:?}: {} tiles", v.xz, tiles.len());
            let q = layout.quarter;
            let side = |level: u32| layout.cell_m(level) * q as f64;
            let index: std::collections::HashSet<(u32, i64, i64)> = tiles
                .iter()
                .map(|t| {
                    let s = side(t.level);
                    (
                        t.level,
                        (t.corner_m[0] / s) as i64,
                        (t.corner_m[1] / s) as i64,
                    )
                })
                .collect();
            // The tiles of `level` whose closed square holds p (two per axis on a tile edge).
            let holders = |level: u32, p: [f64; 2]| {
                let s = side(level);
                let span = |c: f64| {
                    let i = (c / s).floor() as i64;
                    if (c / s).fract() == 0.0 {
                        vec![i - 1, i]
                    } else {
                        vec![i]
                    }
                };
                let mut n = 0;
                for x in span(p[0]) {
                    for z in span(p[1]) {
                        n += usize::from(index.contains(&(level, x, z)));
                    }
                }
                n
            };
            let mut seams = 0;
            for t in &tiles {
                let cell = layout.cell_m(t.level);
                for i in 0..=q {
                    for j in 0..=q {
                        if i != 0 && j != 0 && i != q && j != q {
                            continue;
                        }
                        let p = [
                            t.corner_m[0] + i as f64 * cell,
                            t.corner_m[1] + j as f64 * cell,
                        ];
                        for other in 0..layout.levels {
                            if other == t.level || holders(other, p) == 0 {
                                continue;
                            }
                            assert!(
                                other.abs_diff(t.level) == 1,
                                "levels {} and {other} meet at {p:?} (camera {:?})",
                                t.level,
                                v.xz
                            );
                            if other == t.level + 1 {
                                seams += 1;
                                let m = morphed(&layout, &v, t, i, j);
                                let coarse = layout.cell_m(other);
                                assert!(
                                    (m[0] / coarse).fract() == 0.0 && (m[1] / coarse).fract() == 0.0,
                                    "level {} vertex {p:?} drawn at {m:?}, off level {other}'s lattice (camera {:?})",
                                    t.level,
                                    v.xz
                                );
                                assert_eq!(
                                    morph(&layout, &v, other, p),
                                    0.0,
                                    "level {other} morphed at its seam with level {} at {p:?}",
                                    t.level
                                );
                            }
                        }
                    }
                }
            }
            assert!(
                seams > 0,
                "no seam between levels was checked (camera {:?})",
                v.xz
            );
        }
    }

    /// The tiles `select` draws whose square lies inside the square at `corner` of side `side`.
    fn tiles_inside(layout: &Layout, tiles: &[Tile], corner: [f64; 2], side: f64) -> Vec<Tile> {
        tiles
            .iter()
            .filter(|t| {
                let s = layout.cell_m(t.level) * layout.quarter as f64;
                (0..2).all(|i| t.corner_m[i] >= corner[i] && t.corner_m[i] + s <= corner[i] + side)
            })
            .copied()
            .collect()
    }

    /// Every lattice point of `t` as the shader places it.
    fn drawn_points(layout: &Layout, v: &Viewer, t: &Tile) -> Vec<[f64; 2]> {
        let q = layout.quarter;
        (0..=q)
            .flat_map(|i| (0..=q).map(move |j| (i, j)))
            .map(|(i, j)| morphed(layout, v, t, i, j))
            .collect()
    }

    /// A node's split into its children keeps the mesh: with the camera just outside the
    /// distance at which a node of each level splits, `select` draws it at its level and its
    /// vertices are unmorphed (its mesh is exactly that level's lattice); just inside, its
    /// square is drawn by finer tiles whose vertices all land on the same lattice points (fully
    /// morphed: the same mesh, no pop).
    #[test]
    fn splitting_a_node_does_not_pop() {
        for layout in [
            Layout::for_screen(16.0, 623.5),
            Layout::for_screen(48.0, 311.8),
        ] {
            let h = 1.0;
            for level in 3..layout.levels - 1 {
                let node = layout.node_m(level);
                // The node with corner (0, 0); the camera on the line z = node / 2, h up, at
                // ground distance `x` before the node's near edge.
                let split = layout.range(level - 1);
                let ground = (split * split - h * h).sqrt();
                for (eps, before) in [(1e-6 * split, true), (-1e-6 * split, false)] {
                    let v = viewer(-(ground + eps), node / 2.0, h);
                    let tiles = select(&layout, &v);
                    let inside = tiles_inside(&layout, &tiles, [0.0, 0.0], node);
                    let area: f64 = inside
                        .iter()
                        .map(|t| (layout.cell_m(t.level) * layout.quarter as f64).powi(2))
                        .sum();
                    assert!(
                        (area - node * node).abs() < 1e-9 * node * node,
                        "level {level}"
                    );
                    let coarse = layout.cell_m(level);
                    // Before: the node's four quarters. After: its near quarters by finer
                    // tiles (the far ones may stay, as CDLOD draws a straddling node).
                    if before {
                        assert!(
                            inside.iter().all(|t| t.level == level),
                            "level {level}: {inside:?}"
                        );
                    } else {
                        assert!(
                            inside.iter().any(|t| t.level < level),
                            "level {level} did not split"
                        );
                    }
                    for t in &inside {
                        for p in drawn_points(&layout, &v, t) {
                            assert!(
                                (p[0] / coarse).fract() == 0.0 && (p[1] / coarse).fract() == 0.0,
                                "level {level} {}: a vertex of {t:?} at {p:?}, off the node's lattice",
                                if before { "before its split" } else { "after" }
                            );
                        }
                        if t.level == level {
                            // Unmorphed: every vertex of the node's tiles at its own point.
                            let q = layout.quarter;
                            for i in 0..=q {
                                for j in 0..=q {
                                    let p = morphed(&layout, &v, t, i, j);
                                    let c = [
                                        t.corner_m[0] + i as f64 * coarse,
                                        t.corner_m[1] + j as f64 * coarse,
                                    ];
                                    assert_eq!(
                                        p, c,
                                        "level {level}: {t:?} morphed before its split"
                                    );
                                }
                            }
                        }
                    }
                }
            }
        }
    }

    /// With the largest range factor, at the largest and the smallest tiles, and no culling at
    /// all, a camera at the water's surface needs fewer tiles than the buffer holds.
    #[test]
    fn the_tile_count_stays_bounded() {
        for quarter in [MIN_QUARTER, MAX_QUARTER] {
            let layout = Layout::with_quarter(quarter, 1.0, 1e6);
            assert_eq!(layout.range_factor, MAX_RANGE_FACTOR);
            let n = select(&layout, &viewer(0.5, 0.5, 0.01)).len();
            assert!(n <= MAX_TILES, "quarter {quarter}: {n} tiles");
        }
    }

    /// Every point of the sea the default camera sees (a grid of rays through the screen, down
    /// to its 20 km reach), and the points a cell away from it, lie in drawn tiles: culling
    /// leaves no hole, even where the morph moves a tile's edge into its neighbour.
    #[test]
    fn culling_leaves_no_hole_on_screen() {
        let camera = crate::render::Camera::default();
        let aspect = 16.0 / 9.0;
        let inverse = camera.view_proj(aspect).inverse();
        for layout in [
            Layout::for_screen(16.0, 623.5),
            Layout::for_screen(48.0, 311.8),
        ] {
            let p = camera.position.as_dvec3();
            let v = Viewer {
                xz: [p.x, p.z],
                height_m: p.y,
                view_proj: Some(camera.view_proj(aspect)),
                reach_m: 0.5,
            };
            let tiles = select(&layout, &v);
            let drawn = |x: f64, z: f64| {
                tiles.iter().any(|t| {
                    let s = layout.cell_m(t.level) * layout.quarter as f64;
                    t.corner_m[0] <= x
                        && x <= t.corner_m[0] + s
                        && t.corner_m[1] <= z
                        && z <= t.corner_m[1] + s
                })
            };
            let mut checked = 0;
            for sy in 0..48 {
                for sx in 0..64 {
                    let ndc = glam::Vec2::new(
                        (sx as f32 + 0.5) / 32.0 - 1.0,
                        (sy as f32 + 0.5) / 24.0 - 1.0,
                    );
                    let far = inverse * glam::Vec4::new(ndc.x, ndc.y, 0.5, 1.0);
                    let dir = (far.truncate() / far.w).as_dvec3().normalize();
                    if dir.y >= -1e-3 {
                        continue; // at or above the horizon
                    }
                    let t = -p.y / dir.y;
                    let (x, z) = (p.x + dir.x * t, p.z + dir.z * t);
                    if ((x - p.x).powi(2) + (z - p.z).powi(2)).sqrt() > REACH_M {
                        continue;
                    }
                    // The cell there: the level whose range holds the point's distance.
                    let d = (t * dir.length()).max(p.y);
                    let level = (0..layout.levels)
                        .find(|&l| layout.range(l) >= d)
                        .unwrap_or(layout.levels - 1);
                    let cell = layout.cell_m(level);
                    for (dx, dz) in [
                        (0.0, 0.0),
                        (cell, 0.0),
                        (-cell, 0.0),
                        (0.0, cell),
                        (0.0, -cell),
                    ] {
                        assert!(
                            drawn(x + dx, z + dz),
                            "no tile at ({}, {}) (screen {sx}, {sy})",
                            x + dx,
                            z + dz
                        );
                    }
                    checked += 1;
                }
            }
            assert!(checked > 1000, "{checked} points checked");
        }
    }

    #[test]
    fn the_tiles_cover_the_sea_once_to_the_horizon() {
        let layout = Layout::for_screen(16.0, 623.5);
        let v = viewer(3.0, 5.0, 12.0);
        let tiles = select(&layout, &v);
        let area: f64 = tiles
            .iter()
            .map(|t| (layout.cell_m(t.level) * layout.quarter as f64).powi(2))
            .sum();
        // The union of whole top-level nodes around the camera within reach: tiles do not
        // overlap (sum of areas = the covered area) and cover at least the disc of REACH_M.
        let covered_disc = std::f64::consts::PI * REACH_M * REACH_M;
        assert!(area >= covered_disc, "{area} < {covered_disc}");
        let mut rects: Vec<(f64, f64, f64)> = tiles
            .iter()
            .map(|t| {
                (
                    t.corner_m[0],
                    t.corner_m[1],
                    layout.cell_m(t.level) * layout.quarter as f64,
                )
            })
            .collect();
        rects.sort_by(|a, b| a.partial_cmp(b).unwrap());
        for (i, a) in rects.iter().enumerate() {
            for b in &rects[i + 1..] {
                let overlap_x = a.0 < b.0 + b.2 && b.0 < a.0 + a.2;
                let overlap_z = a.1 < b.1 + b.2 && b.1 < a.1 + a.2;
                assert!(!(overlap_x && overlap_z), "{a:?} overlaps {b:?}");
            }
        }
        // And every point within the reach lies in a tile (polar samples to 20 km).
        for r in (0..40).map(|i| REACH_M * (i as f64 / 40.0).powi(2)) {
            for a in (0..64).map(|i| i as f64 * std::f64::consts::TAU / 64.0) {
                let (x, z) = (v.xz[0] + r * a.cos(), v.xz[1] + r * a.sin());
                assert!(
                    rects
                        .iter()
                        .any(|(cx, cz, s)| *cx <= x && x <= cx + s && *cz <= z && z <= cz + s),
                    "({x}, {z}) lies in no tile"
                );
            }
        }
        // The camera's own spot is drawn at the finest level its height allows.
        let under = tiles
            .iter()
            .find(|t| {
                let s = layout.cell_m(t.level) * layout.quarter as f64;
                (0..2).all(|i| t.corner_m[i] <= v.xz[i] && v.xz[i] < t.corner_m[i] + s)
            })
            .unwrap();
        assert!(layout.range(under.level) >= v.height_m);
        assert!(under.level == 0 || layout.range(under.level - 1) < v.height_m * 1.5);
    }
}
