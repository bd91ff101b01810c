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
//!   - the same points lie in the level-L node that drew the level-L tile, which reaches at
//!     most range(L) + √2·node(L) from the camera (its nearest point within range(L), plus
//!     its diagonal): the level L+1 side is not morphed there yet when
//!     `morph_start(L+1) ≥ range(L) + √2·node(L)`;
//!   - a quarter of a level-L node is handed to its child (the level L-1 node of the same
//!     square) when the child's nearest point comes within range(L-1): the quarter's
//!     vertices are then at most range(L-1) + √2·node(L)/2 away (the quarter's diagonal),
//!     unmorphed when `morph_start(L) ≥ range(L-1) + √2·node(L)/2`, while the child's
//!     quarters, all beyond range(L-1), are fully morphed: the same mesh before and after.
//!     The node's other quarters are drawn at level L before and after, morphed alike.
//!
//!   Both conditions are one, `morph_start(L) ≥ range(L)·(1/2 + 1/(c√2))` for ranges
//!   `range(L) = c·node(L)` (node(L) = 2·node(L-1), range(L) = 2·range(L-1)), which leaves a
//!   morph zone for any c > √2; `MIN_RANGE_FACTOR` keeps a seventh of the range at least.
//!   (Until 2026-12-05 the handover was bounded by the whole node's diagonal, √2·node(L),
//!   which asked for c > 2√2 and held `--quality low`'s cells at 39 px where it asks for 48.)
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
/// Smallest range factor c (range(L) = c·node(L)): the morph zone, from
/// range·(1/2 + 1/(c√2)) to the range, is then a seventh of the range (see the module's doc).
pub const MIN_RANGE_FACTOR: f64 = 2.0;
/// The range factor a layout keeps while its tiles can get smaller (`Layout::for_screen`): a
/// morph zone of a third of the range, and tiles culled finer; below it only with 1-cell tiles.
pub const TILE_RANGE_FACTOR: f64 = 4.0;
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
    /// The largest tiles that keep c at `TILE_RANGE_FACTOR` or more; with 1-cell tiles c may
    /// fall to `MIN_RANGE_FACTOR` (the coarsest cells).
    pub fn for_screen(cell_px: f64, focal_px: f64) -> Layout {
        let cells_per_range = cells_per_range(cell_px, focal_px);
        let mut quarter = MIN_QUARTER;
        while quarter * 2 <= MAX_QUARTER
            && cells_per_range / (2.0 * (quarter * 2) as f64) >= TILE_RANGE_FACTOR
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
            * (0.5 + std::f64::consts::FRAC_1_SQRT_2 / self.range_factor)
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
mod block_model;
#[cfg(test)]
mod tests;
