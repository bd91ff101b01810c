//! The clipmap's tests: the morph conditions, seams between levels, splits, coverage, culling
//! and the tile count, through `select` and the shader's morph rewritten here in f64.

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
pub(super) fn morphed(layout: &Layout, v: &Viewer, t: &Tile, i: u32, j: u32) -> [f64; 2] {
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
        (64.0, 311.8),
        (2.0, 2000.0),
        (256.0, 100.0),
    ] {
        let l = Layout::for_screen(px, f);
        assert!(l.quarter.is_power_of_two() && (MIN_QUARTER..=MAX_QUARTER).contains(&l.quarter));
        assert!(l.range_factor >= MIN_RANGE_FACTOR, "{l:?}");
        // Below TILE_RANGE_FACTOR only with the smallest tiles.
        assert!(
            l.range_factor >= TILE_RANGE_FACTOR || l.quarter == MIN_QUARTER,
            "{l:?}"
        );
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
            // A quarter handed to its child is unmorphed (within its diagonal of the child's
            // range); a coarser neighbour is unmorphed at its seam with the finer level's node.
            let quarter_diag = std::f64::consts::SQRT_2 * l.node_m(level) / 2.0;
            assert!(l.morph_start(level) >= l.range(level - 1) + quarter_diag);
            // The morph zone: a seventh of the range at least.
            let zone = l.morph_end(level) - l.morph_start(level);
            assert!(zone >= l.range(level) / 7.2, "{l:?}: zone {zone}");
        }
    }
}

/// Where tiles of two levels meet, the finer side's boundary vertices, as drawn after the
/// morph, land on the coarser lattice and the coarser side is not morphed: every edge of
/// the seam is an edge of both meshes (no crack), for cameras at several heights and places.
/// Levels further apart never meet.
#[test]
fn tiles_meet_without_cracks() {
    // Tiles of 4 cells (--quality high's) and of 1 (low's: odd corners morph too), and of
    // 1 at the smallest range factor (the narrowest morph zone).
    for (layout, quarter) in [
        (Layout::for_screen(16.0, 623.5), 4),
        (Layout::for_screen(48.0, 311.8), 1),
        (Layout::for_screen(96.0, 311.8), 1),
    ] {
        assert_eq!(layout.quarter, quarter, "{layout:?}");
        tiles_of_layout_meet_without_cracks(&layout);
    }
    assert_eq!(
        Layout::for_screen(96.0, 311.8).range_factor,
        MIN_RANGE_FACTOR
    );
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
/// distance at which a node of each level splits, `select` draws it at its level; just
/// inside, the quarters that came within the split distance are drawn by finer tiles. Those
/// quarters were unmorphed before (their mesh exactly that level's lattice) and their finer
/// tiles are fully morphed after (every vertex on the same lattice points: no pop); the
/// quarters that did not split are the same tiles, drawn where they were.
#[test]
fn splitting_a_node_does_not_pop() {
    for layout in [
        Layout::for_screen(16.0, 623.5),
        Layout::for_screen(48.0, 311.8),
        Layout::for_screen(96.0, 311.8),
    ] {
        let h = 1.0;
        for level in 3..layout.levels - 1 {
            let node = layout.node_m(level);
            let half = node / 2.0;
            let coarse = layout.cell_m(level);
            // The node with corner (0, 0); the camera on the line z = node / 2, h up, at
            // ground distance `x` before the node's near edge.
            let split = layout.range(level - 1);
            let ground = (split * split - h * h).sqrt();
            let at = |eps: f64| {
                let v = viewer(-(ground + eps), half, h);
                let tiles = tiles_inside(&layout, &select(&layout, &v), [0.0, 0.0], node);
                let area: f64 = tiles
                    .iter()
                    .map(|t| (layout.cell_m(t.level) * layout.quarter as f64).powi(2))
                    .sum();
                assert!(
                    (area - node * node).abs() < 1e-9 * node * node,
                    "level {level}"
                );
                (v, tiles)
            };
            let (v_before, before) = at(1e-6 * split);
            let (v_after, after) = at(-1e-6 * split);
            assert!(
                before.iter().all(|t| t.level == level),
                "level {level}: {before:?}"
            );
            let quarters = [[0.0, 0.0], [half, 0.0], [0.0, half], [half, half]];
            let in_quarter = |tiles: &[Tile], q: [f64; 2]| tiles_inside(&layout, tiles, q, half);
            let mut splits = 0;
            for q in quarters {
                let (was, is) = (in_quarter(&before, q), in_quarter(&after, q));
                if is.iter().all(|t| t.level == level) {
                    // Not split: the same tile, its vertices where they were (the camera
                    // moved by 2·10⁻⁶ of the split distance).
                    assert_eq!(was, is, "level {level}");
                    for t in &was {
                        let moved = drawn_points(&layout, &v_before, t)
                            .iter()
                            .zip(drawn_points(&layout, &v_after, t))
                            .map(|(a, b)| (a[0] - b[0]).hypot(a[1] - b[1]))
                            .fold(0.0, f64::max);
                        assert!(moved < 1e-4 * coarse, "level {level}: {t:?} moved {moved}");
                    }
                    continue;
                }
                splits += 1;
                for t in &was {
                    // Unmorphed: every vertex of the quarter at its own lattice point.
                    let q = layout.quarter;
                    for i in 0..=q {
                        for j in 0..=q {
                            let p = morphed(&layout, &v_before, t, i, j);
                            let c = [
                                t.corner_m[0] + i as f64 * coarse,
                                t.corner_m[1] + j as f64 * coarse,
                            ];
                            assert_eq!(p, c, "level {level}: {t:?} morphed before its split");
                        }
                    }
                }
                for t in &is {
                    for p in drawn_points(&layout, &v_after, t) {
                        assert!(
                            (p[0] / coarse).fract() == 0.0 && (p[1] / coarse).fract() == 0.0,
                            "level {level}: a vertex of {t:?} at {p:?}, off the node's lattice \
                             after its split"
                        );
                    }
                }
            }
            assert!(splits > 0, "level {level} did not split");
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
