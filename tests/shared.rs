//! What Rust and the shaders both know agrees. Constants have one definition (src/shared.rs,
//! written into `shared.glsl` by build.rs); the terrain height and the waves over the shallows
//! are functions in both languages (Rust places cameras and floats the buoy with them), so they
//! are compared here on the GPU, at points over the island, its shore, its shelf, the slope and
//! the open sea's floor, for the default layout and a moved, smaller one, under a deep and a
//! finite-depth sea. The tests undo the display's tone map (`common::untone`) to measure light
//! in the radiance it conserves; that inverse is checked against the shader's tone map here.

mod common;

use common::{assert_validation_clean, gpu_context};
use vkocean::gpu::oneshot::{download, run_once, upload};
use vkocean::gpu::{
    vk, Bind, Bindings, BoundSet, Buffer, DescriptorSetLayout, MemoryLocation, Order, Pipeline,
    PipelineLayout,
};
use vkocean::ocean::moments::{SeaMoments, DEEP_WATER_M};
use vkocean::ocean::shore::{reference_group_speed, runup_m, shoaling, shore_waves, travel_time_s};
use vkocean::render::scene::terrain_height;
use vkocean::render::SceneLayout;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Push {
    terrain: [f32; 4],
    shore: [f32; 4],
    open_sea: [f32; 4],
    count: u32,
    _pad: [u32; 3],
}

/// At `points`, run on the GPU: `terrain_height` of terrain.glsl and `shore_waves` of
/// shore.glsl over the depth there (height, scale, breaking, local Hs), then the surf's travel
/// time and run-up at the point's slope (`surf_slope`) and the rest zero.
fn gpu_terrain(
    ctx: &std::sync::Arc<vkocean::gpu::Context>,
    layout: &SceneLayout,
    sea: &SeaMoments,
    points: &[[f32; 2]],
) -> Vec<[[f32; 4]; 2]> {
    let storage = vk::BufferUsageFlags::STORAGE_BUFFER
        | vk::BufferUsageFlags::TRANSFER_DST
        | vk::BufferUsageFlags::TRANSFER_SRC;
    let bytes = |n: usize| (n * 4) as u64;
    let xz = Buffer::new(
        ctx,
        "test points",
        bytes(2 * points.len()),
        storage,
        MemoryLocation::GpuOnly,
    )
    .unwrap();
    let heights = Buffer::new(
        ctx,
        "test heights",
        bytes(8 * points.len()),
        storage,
        MemoryLocation::GpuOnly,
    )
    .unwrap();
    upload(ctx, &xz, bytemuck::cast_slice(points)).unwrap();
    let ty = vk::DescriptorType::STORAGE_BUFFER;
    let stage = vk::ShaderStageFlags::COMPUTE;
    let set_layout =
        DescriptorSetLayout::new(ctx, "test set layout", &[(0, ty, stage), (1, ty, stage)])
            .unwrap();
    let t = Order::Tracked;
    let set = BoundSet::new(
        ctx,
        &set_layout,
        "test set",
        &[(0, Bind::Storage(&xz, t)), (1, Bind::Storage(&heights, t))],
    )
    .unwrap();
    let layout_push = PipelineLayout::new(
        ctx,
        "test layout",
        &[&set_layout],
        Some((stage, std::mem::size_of::<Push>() as u32)),
    )
    .unwrap();
    let pipeline = Pipeline::compute(
        ctx,
        &layout_push,
        "terrain height test",
        vkocean::shaders::TEST_TERRAIN_HEIGHT_COMP,
        &[],
    )
    .unwrap();
    let push = Push {
        terrain: [
            layout.island_xz[0],
            layout.island_xz[1],
            layout.sea_floor_m,
            layout.island_radius_m,
        ],
        shore: [sea.hs_m, sea.mean_omega, reference_group_speed(sea), 0.0].map(|v| v as f32),
        open_sea: [
            layout.deep_floor_m,
            shoaling(sea, layout.deep_floor_m as f64) as f32,
            0.0,
            0.0,
        ],
        count: points.len() as u32,
        _pad: [0; 3],
    };
    run_once(ctx, "terrain height test", |rec| {
        rec.push_constants(&pipeline, &push);
        let b = Bindings {
            pipeline: &pipeline,
            sets: &[&set],
        };
        rec.dispatch_with(&b, [(points.len() as u32).div_ceil(64), 1, 1]);
    })
    .unwrap();
    let out = download(ctx, &heights, points.len() * 32).unwrap();
    bytemuck::cast_slice(&out).to_vec()
}

/// The bed slope terrain_height.comp gives point `i` for the surf's functions.
fn surf_slope(i: usize) -> f64 {
    let m = 0.005 + 0.3 * (0.618f32 * i as f32).fract();
    f64::from(m)
}

#[test]
fn the_terrain_and_the_shore_are_the_same_in_rust_and_glsl() {
    let ctx = gpu_context();
    let moved = SceneLayout {
        island_xz: [120.0, -40.0],
        island_radius_m: 90.0,
        sea_floor_m: 7.5,
        deep_floor_m: 40.0,
        ..SceneLayout::default()
    };
    // A storm over deep water, and a short sea simulated for 12 m.
    let seas = [
        SeaMoments {
            hs_m: 9.0,
            mean_omega: 0.5,
            depth_m: DEEP_WATER_M,
            slope_variance: [0.0; 4],
            slope_anisotropy: [[0.0; 2]; 4],
            curvature_variance: [0.0; 4],
            short_slope_variance: [0.0; 4],
            slope_mip_gain: [[1.0; 4]; vkocean::ocean::moments::MIP_LEVELS],
        },
        SeaMoments {
            hs_m: 1.2,
            mean_omega: 1.1,
            depth_m: 12.0,
            slope_variance: [0.0; 4],
            slope_anisotropy: [[0.0; 2]; 4],
            curvature_variance: [0.0; 4],
            short_slope_variance: [0.0; 4],
            slope_mip_gain: [[1.0; 4]; vkocean::ocean::moments::MIP_LEVELS],
        },
    ];
    for (layout, sea) in [SceneLayout::default(), moved].iter().zip(&seas) {
        // An 81 x 81 grid over 5 island radii each way: peak, slopes, shore, shelf, the slope
        // down to the open sea and its floor.
        let r = 5.0 * layout.island_radius_m;
        let points: Vec<[f32; 2]> = (0..81 * 81)
            .map(|i| {
                let (u, v) = ((i % 81) as f32 / 80.0, (i / 81) as f32 / 80.0);
                [
                    layout.island_xz[0] + (2.0 * u - 1.0) * r,
                    layout.island_xz[1] + (2.0 * v - 1.0) * r,
                ]
            })
            .collect();
        let gpu = gpu_terrain(&ctx, layout, sea, &points);
        let (mut worst_h, mut worst_shore, mut worst_surf) = (0.0f32, 0.0f64, 0.0f64);
        let mut breaking = 0;
        for (i, (p, [g, surf])) in points.iter().zip(&gpu).enumerate() {
            let cpu = terrain_height(layout, p[0], p[1]);
            worst_h = worst_h.max((cpu - g[0]).abs());
            let w = shore_waves(sea, -cpu as f64);
            let hs = sea.hs_m;
            for (c, g) in [
                (w.scale, g[1] as f64),
                (w.breaking, g[2] as f64),
                (w.hs_m / hs, g[3] as f64 / hs),
            ] {
                worst_shore = worst_shore.max((c - g).abs());
            }
            breaking += (w.breaking > 0.0 && cpu < 0.0) as usize;
            let m = surf_slope(i);
            // At the GPU's own height: T grows as √d, steeply at the waterline.
            let t = travel_time_s(sea.mean_omega, -g[0] as f64, m);
            let r = runup_m(sea.hs_m, sea.mean_omega, m);
            for (c, g) in [(t, surf[0] as f64), (r, surf[1] as f64)] {
                worst_surf = worst_surf.max((c - g).abs() / c.abs().max(1.0));
            }
        }
        // f32 on both sides; sin/exp of GLSL are within a few ulp of Rust's. 1 mm over a
        // height range of 60–250 m: any change to a constant or a term breaks it by metres.
        assert!(worst_h < 1e-3, "{layout:?}: max |CPU − GPU| = {worst_h} m");
        let range = gpu.iter().map(|g| g[0][0]).fold(f32::MIN, f32::max)
            - gpu.iter().map(|g| g[0][0]).fold(f32::MAX, f32::min);
        assert!(range > 40.0, "the grid covers the island: range {range} m");
        // Scale, breaking and local Hs / Hs (all about 0–1.3): f32 against f64. A changed
        // constant (γ, Guo's β) moves them by more than 10⁻².
        assert!(
            worst_shore < 1e-3,
            "{sea:?}: max |CPU − GPU| of the shore = {worst_shore}"
        );
        // The surf's travel time (s, up to hundreds over the shelf's gentlest slopes) and
        // run-up (m): relative to the value or 1, whichever is larger. A changed node or
        // weight of the quadrature, or a constant of Stockdon's, moves them by more than 10⁻³.
        assert!(
            worst_surf < 1e-4,
            "{sea:?}: max |CPU − GPU| of the surf = {worst_surf}"
        );
        assert!(
            breaking > 10,
            "the grid crosses the surf zone: {breaking} points"
        );
    }
    assert_validation_clean(ctx);
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct TonePush {
    sky_light: [f32; 4],
    top: f32,
    count: u32,
    _pad: [u32; 2],
}

/// `common::untone` undoes shaders/common/display.glsl's `tone_map` (tone_map.comp runs it):
/// 4096 colours with peaks up to 2.9 (just short of the white blend) come back to within 10⁻⁴
/// of their radiance (relative, or absolute under 10⁻²; measured 2.4·10⁻⁶: f32 against f64).
/// A changed constant of the curve or the blend moves them by 10⁻³ or more. (A picture's
/// byte holds the display colour to 1/255: near the curve's shoulder that is a few per cent
/// of the radiance, in its toe a fraction of one.)
#[test]
fn the_tests_undo_the_display_s_tone_map() {
    let count = 4096u32;
    let push = TonePush {
        sky_light: [0.0, 0.0, 0.0, 1.0],
        top: 2.9,
        count,
        _pad: [0; 2],
    };
    let out = common::run_test_kernel(
        "tone map test",
        vkocean::shaders::TEST_TONE_MAP_COMP,
        &[push],
        count as usize * 32,
        [count.div_ceil(64), 1, 1],
    );
    let (mut worst, mut undone) = (0.0f64, 0);
    for pair in out[0].chunks(8) {
        let x = [pair[0], pair[1], pair[2]].map(f64::from);
        let shown = [pair[4], pair[5], pair[6]].map(f64::from);
        let Some(back) = common::untone(shown) else {
            continue;
        };
        undone += 1;
        for (a, b) in x.iter().zip(back) {
            worst = worst.max((a - b).abs() / a.max(1e-2));
        }
    }
    eprintln!("tone map undone: {undone} of {count}, worst {worst:.2e}");
    assert!(undone > 4000, "only {undone} of {count} colours undone");
    assert!(worst < 1e-4, "untone(tone_map(x)) is off x by {worst:.2e}");
}
