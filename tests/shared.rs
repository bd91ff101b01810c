//! What Rust and the shaders both know agrees. Constants have one definition (src/shared.rs,
//! written into `shared.glsl` by build.rs); the terrain height is a function in both languages
//! (Rust places cameras and the buoy with it), so it is compared here on the GPU, at points over
//! the island, its shore and the sea floor, for the default layout and a moved, smaller one.

mod common;

use common::{assert_validation_clean, gpu_context};
use vkocean::gpu::descriptors::{update, Write};
use vkocean::gpu::oneshot::{download, run_once, upload};
use vkocean::gpu::{
    vk, Buffer, DescriptorPool, DescriptorSetLayout, MemoryLocation, Pipeline, PipelineLayout, Use,
};
use vkocean::render::scene::terrain_height;
use vkocean::render::SceneLayout;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Push {
    terrain: [f32; 4],
    count: u32,
    _pad: [u32; 3],
}

/// `terrain_height` of terrain.glsl at `points`, run on the GPU.
fn gpu_heights(
    ctx: &std::sync::Arc<vkocean::gpu::Context>,
    layout: &SceneLayout,
    points: &[[f32; 2]],
) -> Vec<f32> {
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
        bytes(points.len()),
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
    let pool = DescriptorPool::new(ctx, "test pool", 1, &[(ty, 2)]).unwrap();
    let set = pool.allocate(&set_layout, "test set").unwrap();
    update(
        ctx,
        set,
        &[
            Write::StorageBuffer {
                binding: 0,
                buffer: xz.raw,
            },
            Write::StorageBuffer {
                binding: 1,
                buffer: heights.raw,
            },
        ],
    );
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
        count: points.len() as u32,
        _pad: [0; 3],
    };
    run_once(ctx, "terrain height test", |rec| {
        rec.uses(&[(&xz, Use::ComputeRead), (&heights, Use::ComputeWrite)]);
        rec.bind_pipeline(&pipeline);
        rec.bind_sets(&pipeline, &layout_push, &[set]);
        rec.push_constants(&layout_push, &push);
        rec.dispatch((points.len() as u32).div_ceil(64), 1, 1);
    })
    .unwrap();
    let out = download(ctx, &heights, points.len() * 4).unwrap();
    bytemuck::cast_slice(&out).to_vec()
}

#[test]
fn the_terrain_height_is_the_same_in_rust_and_glsl() {
    let ctx = gpu_context();
    let moved = SceneLayout {
        island_xz: [120.0, -40.0],
        island_radius_m: 90.0,
        sea_floor_m: 7.5,
        ..SceneLayout::default()
    };
    for layout in [SceneLayout::default(), moved] {
        // A 33 x 33 grid over 2.4 island radii each way: peak, slopes, shore, sea floor.
        let r = 2.4 * layout.island_radius_m;
        let points: Vec<[f32; 2]> = (0..33 * 33)
            .map(|i| {
                let (u, v) = ((i % 33) as f32 / 32.0, (i / 33) as f32 / 32.0);
                [
                    layout.island_xz[0] + (2.0 * u - 1.0) * r,
                    layout.island_xz[1] + (2.0 * v - 1.0) * r,
                ]
            })
            .collect();
        let gpu = gpu_heights(&ctx, &layout, &points);
        let mut worst = 0.0f32;
        for (p, g) in points.iter().zip(&gpu) {
            let cpu = terrain_height(&layout, p[0], p[1]);
            worst = worst.max((cpu - g).abs());
        }
        // f32 on both sides; sin/exp of GLSL are within a few ulp of Rust's. 1 mm over a
        // height range of about 60 m: any change to a constant or a term breaks it by metres.
        assert!(worst < 1e-3, "{layout:?}: max |CPU − GPU| = {worst} m");
        let range = gpu.iter().cloned().fold(f32::MIN, f32::max)
            - gpu.iter().cloned().fold(f32::MAX, f32::min);
        assert!(range > 40.0, "the grid covers the island: range {range} m");
    }
    assert_validation_clean(ctx);
}
