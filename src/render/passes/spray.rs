//! The spray's puffs over the main view (shaders/spray/): after the sky, one indirect draw of
//! the frame slot's live particles, which the compute queue moved and counted
//! (src/ocean/simulation/spray_sim.rs). Both the particles (read by the vertex shader) and the
//! draw's arguments come through the compute timeline's wait, which names the vertex and
//! DRAW_INDIRECT stages (`Order::Wait`, checked at creation and at the draw).

use std::sync::Arc;

use ash::vk;

use super::{bind_scene, scene_layout, scene_pipeline, Depth, SceneTarget};
use crate::gpu::{
    Bind, Bindings, BoundSet, Buffer, Context, DescriptorSetLayout, GpuResult, GraphicsDesc, Order,
    Pipeline, Recorder, FRAMES_IN_FLIGHT,
};
use crate::ocean::simulation::{SprayBuffers, DRAW_ARGS_OFFSET};
use crate::render::uniforms::ViewIndex;
use crate::shaders;

pub struct SprayPass {
    /// Kept alive with the sets and the pipeline.
    _set_layout: DescriptorSetLayout,
    pipeline: Pipeline,
    /// Per slot: the particles (set 1).
    sets: Vec<BoundSet>,
    /// Per slot: the draw's arguments.
    counts: Vec<Buffer>,
    /// How the simulation's writes are ordered before the draw (the compute timeline's wait).
    order: Order,
}

impl SprayPass {
    /// `order`: the compute timeline's wait, as the frame set has it.
    pub fn new(
        ctx: &Arc<Context>,
        frame_layout: &DescriptorSetLayout,
        display_format: vk::Format,
        buffers: &SprayBuffers,
        order: Order,
    ) -> GpuResult<SprayPass> {
        let set_layout = DescriptorSetLayout::new(
            ctx,
            "spray set layout (particles)",
            &[(
                0,
                vk::DescriptorType::STORAGE_BUFFER,
                vk::ShaderStageFlags::VERTEX,
            )],
        )?;
        let layout = scene_layout(ctx, "spray layout", frame_layout, &[&set_layout])?;
        let pipeline = scene_pipeline(
            ctx,
            &layout,
            GraphicsDesc {
                name: "spray",
                stages: &[
                    (vk::ShaderStageFlags::VERTEX, shaders::SPRAY_SPRAY_VERT),
                    (vk::ShaderStageFlags::FRAGMENT, shaders::SPRAY_SPRAY_FRAG),
                ],
                blend_over: true,
                ..Default::default()
            },
            Depth::Test,
            SceneTarget::Display(display_format),
        )?;
        let sets = (0..FRAMES_IN_FLIGHT)
            .map(|slot| {
                BoundSet::new(
                    ctx,
                    &set_layout,
                    &format!("spray set slot {slot}"),
                    &[(0, Bind::Storage(&buffers.particles[slot], order))],
                )
            })
            .collect::<GpuResult<Vec<_>>>()?;
        Ok(SprayPass {
            _set_layout: set_layout,
            pipeline,
            sets,
            counts: buffers.counts.iter().map(Buffer::share).collect(),
            order,
        })
    }

    /// The sets a draw of slot `slot` binds: the frame set, then the particles.
    pub fn sets<'a>(&'a self, frame: &'a BoundSet, slot: usize) -> [&'a BoundSet; 2] {
        [frame, &self.sets[slot]]
    }

    /// What `record` binds, with `sets` from [`SprayPass::sets`].
    pub fn draw<'a>(&'a self, sets: &'a [&'a BoundSet]) -> Bindings<'a> {
        Bindings {
            pipeline: &self.pipeline,
            sets,
        }
    }

    /// Draws slot `slot`'s particles (inside a rendering scope that declared `draw(sets)`).
    pub fn record(&self, rec: &Recorder, sets: &[&BoundSet], slot: usize) {
        bind_scene(rec, &self.draw(sets), ViewIndex::Main);
        rec.draw_indirect(&self.counts[slot], DRAW_ARGS_OFFSET, self.order);
    }
}
