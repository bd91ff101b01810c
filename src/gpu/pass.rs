//! Passes name what they draw or dispatch with; the recorder turns that into barriers
//! (`track`) and, for rendering, into the scope's attachments.
//!
//! - [`Recorder::rendering`] takes the scope's attachments and the [`Bindings`] (pipeline and
//!   descriptor sets) of every draw in it. What each draw's shaders read comes from their
//!   SPIR-V (`reflect`), the resources from the sets (`descriptors::BoundSet`): the barriers
//!   wait at exactly the stages that read (a sky cube sampled by a tessellation-evaluation
//!   shader is waited for there), and a bind inside the scope must be one it declared.
//! - [`Recorder::dispatch_with`] does the same for a compute dispatch.
//! - [`Recorder::uses`]: a use no shader makes (attachments, copies, presentation).
//!
//! [`check_bindings`] checks a pass's bindings at creation: every descriptor its shaders use is
//! bound, and a resource ordered by a semaphore wait is read only in the stages that wait
//! covers. It names the pass, the binding and the stage.

use ash::vk;

use super::buffer::Buffer;
use super::command::{Attachment, BindingsKey, ImageBarrier, Load, Recorder};
use super::descriptors::{sampled_layout, BoundSet, Order, Resource};
use super::image::{Image, Output};
use super::pipeline::Pipeline;
use super::reflect::{pipeline_stages, Kind};
use super::track::{transition, Access, Handle, Raw, State, StateCell, Tracked, Use};

/// One layer of an image, tracked on its own while `Recorder::halve_down_layers` runs.
struct Layer<'a> {
    image: &'a Image,
    layer: u32,
    state: StateCell,
}

impl super::track::sealed::Sealed for Layer<'_> {}

impl Tracked for Layer<'_> {
    fn handle(&self) -> Handle {
        let range = vk::ImageSubresourceRange {
            base_array_layer: self.layer,
            layer_count: 1,
            ..self.image.range()
        };
        Handle::image(self.image.raw, range)
    }
    fn name(&self) -> &str {
        self.image.name()
    }
    fn state(&self) -> &StateCell {
        &self.state
    }
}

/// An attachment of [`Recorder::rendering`]: an image (through its default view, layer 0 of a
/// layered one, or another view, e.g. a cube face) and what the scope does with its previous
/// contents.
pub struct Target<'a> {
    image: &'a dyn Tracked,
    view: vk::ImageView,
    extent: vk::Extent2D,
    format: vk::Format,
    load: Load,
}

impl<'a> Target<'a> {
    pub fn new(image: &'a Image, load: Load) -> Target<'a> {
        expect_attachment(image);
        Target {
            image,
            view: image.layer_views.first().copied().unwrap_or(image.view),
            extent: image.extent,
            format: image.format,
            load,
        }
    }

    /// Face or layer `layer` of a cube or layered image. The image is tracked whole: only
    /// layer 0 may discard (its barrier discards every layer), the others keep (`Load::Keep`).
    pub fn layer(image: &'a Image, layer: u32, load: Load) -> Target<'a> {
        expect_attachment(image);
        assert!(
            layer == 0 || matches!(load, Load::Keep),
            "layer {layer} of {}: a later layer keeps what the earlier ones wrote (Load::Keep)",
            image.name()
        );
        Target {
            image,
            view: image.layer_views[layer as usize],
            extent: image.extent,
            format: image.format,
            load,
        }
    }

    /// The frame's output image.
    pub fn output(output: Output<'a>, load: Load) -> Target<'a> {
        output.expect_usage(vk::ImageUsageFlags::COLOR_ATTACHMENT, "a rendering scope");
        Target {
            image: output.tracked(),
            view: output.view(),
            extent: output.extent(),
            format: output.format(),
            load,
        }
    }
}

/// Panics unless `image` can be a colour or depth attachment (by its aspect).
fn expect_attachment(image: &Image) {
    let usage = if image.aspect.contains(vk::ImageAspectFlags::DEPTH) {
        vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT
    } else {
        vk::ImageUsageFlags::COLOR_ATTACHMENT
    };
    image.expect_usage(usage, "a rendering scope");
}

/// What a draw or dispatch binds: a pipeline and its descriptor sets, set 0 first.
#[derive(Clone, Copy)]
pub struct Bindings<'a> {
    pub pipeline: &'a Pipeline,
    pub sets: &'a [&'a BoundSet],
}

impl Bindings<'_> {
    fn key(&self) -> BindingsKey {
        BindingsKey(self.pipeline.id, self.sets.iter().map(|s| s.raw).collect())
    }
}

/// A read the shaders of one bindings make: the bound resource and how it is ordered.
struct Read<'a> {
    resource: &'a Resource,
    order: Order,
    kind: Kind,
    stages: vk::ShaderStageFlags,
    reads: bool,
    writes: bool,
}

/// Every descriptor the pipeline's shaders use, with what the sets bind there; an error names
/// the pass, the set and binding, and the stage.
fn reads<'a>(pass: &str, b: &Bindings<'a>) -> Result<Vec<Read<'a>>, String> {
    let mut out = Vec::new();
    for (&(set, binding), used) in &b.pipeline.interface.bindings {
        let bound = b
            .sets
            .get(set as usize)
            .and_then(|s| s.bindings.get(&binding));
        let Some(bound) = bound else {
            return Err(format!(
                "pass {pass}: pipeline {} reads set {set} binding {binding} in {:?}, but nothing is bound there",
                b.pipeline.name, used.stages
            ));
        };
        // Only formatted for an error (this runs for every draw of every frame).
        let what = || {
            format!(
                "pass {pass}: pipeline {} {} {} (set {set} binding {binding}) in {:?}",
                b.pipeline.name,
                if used.writes { "writes" } else { "reads" },
                bound.name(),
                used.stages
            )
        };
        // What a shader writes must be tracked: a host or another queue's order says nothing
        // of the writes this queue makes.
        if used.writes && bound.order != Order::Tracked {
            return Err(format!("{}, but it is not tracked on this queue", what()));
        }
        // Graphics shaders here sample images, read uniforms and read storage buffers the
        // compute queue wrote (through its wait): storage descriptors and tracked buffers
        // would need uses this tracker does not derive for those stages.
        let graphics = !used.stages.contains(vk::ShaderStageFlags::COMPUTE);
        let image = matches!(bound.resource, Resource::Image(_));
        let sampled = matches!(used.kind, Kind::CombinedImageSampler | Kind::SampledImage);
        if graphics && bound.order == Order::Tracked && !(image && sampled) {
            return Err(format!(
                "{}: graphics passes track sampled images only (uniforms are host-written)",
                what()
            ));
        }
        if let Order::Wait { by, stages } = bound.order {
            let reading = pipeline_stages(used.stages);
            if !stages.contains(reading) {
                return Err(format!(
                    "pass {pass}: pipeline {} reads {} (set {set} binding {binding}) in {reading:?}, but {by} waits at {stages:?} only",
                    b.pipeline.name,
                    bound.name()
                ));
            }
        }
        out.push(Read {
            resource: &bound.resource,
            order: bound.order,
            kind: used.kind,
            stages: used.stages,
            reads: used.reads,
            writes: used.writes,
        });
    }
    Ok(out)
}

fn resource_name(resource: &Resource) -> &str {
    match resource {
        Resource::Image(i) => i.name(),
        Resource::Buffer(b) => b.name(),
    }
}

/// Panics unless a scope's attachments share one size (one render area) and every draw's
/// pipeline renders to their formats (dynamic rendering: the pipeline's formats must be the
/// scope's).
fn check_scope(pass: &str, colour: &[Target], depth: Option<&Target>, draws: &[Bindings]) {
    let extent = colour.first().or(depth).map(|t| t.extent);
    assert!(
        colour.iter().chain(depth).all(|t| Some(t.extent) == extent),
        "pass {pass}: attachments of different sizes"
    );
    let formats = (
        colour.iter().map(|t| t.format).collect::<Vec<_>>(),
        depth.map(|t| t.format),
    );
    for b in draws {
        assert!(
            b.pipeline.formats.as_ref() == Some(&formats),
            "pass {pass}: pipeline {} renders to {:?}, the scope's attachments are {formats:?}",
            b.pipeline.name,
            b.pipeline.formats
        );
    }
}

/// Checks a pass's bindings at creation (`GpuError::Interface`, one line naming the pass, the
/// binding and the stage): what its pipelines' shaders read is bound, and what a semaphore
/// wait orders is read only in the stages the wait covers.
pub fn check_bindings(pass: &str, bindings: &[Bindings]) -> super::GpuResult<()> {
    for b in bindings {
        reads(pass, b).map_err(super::GpuError::Interface)?;
    }
    Ok(())
}

/// The tracked use a compute dispatch's shader makes of what its set binds: a sampled image
/// in SHADER_READ_ONLY_OPTIMAL (as its descriptor says), storage read, written or both in
/// GENERAL (`readonly` / `writeonly` in the SPIR-V), texel and uniform reads.
fn compute_use(read: &Read) -> Use {
    if matches!(read.kind, Kind::CombinedImageSampler | Kind::SampledImage) {
        return Use::Sampled(vk::PipelineStageFlags2::COMPUTE_SHADER);
    }
    match (read.kind.is_storage(), read.reads, read.writes) {
        (true, true, true) => Use::ComputeReadWrite,
        (true, false, true) => Use::ComputeWrite,
        _ => Use::ComputeRead,
    }
}

impl Recorder<'_> {
    /// Records the barriers `uses` need (none when every use already sees what it needs) and
    /// moves each resource to its state after the use.
    pub fn uses(&self, uses: &[(&dyn Tracked, Use)]) {
        let mut images = Vec::new();
        let mut buffers = Vec::new();
        for (resource, next) in uses {
            let Handle(handle) = resource.handle();
            let (barrier, after) = transition(
                resource.state().get(),
                *next,
                matches!(handle, Raw::Image(..)),
            );
            resource.state().set(after);
            let (access, layout) = next.scope();
            let layout = matches!(handle, Raw::Image(..)).then_some(layout);
            let barrier_scopes = barrier.map(|b| (b.2, b.3));
            self.ctx.journal_use(
                resource.name(),
                (access, layout),
                next.writes(),
                barrier_scopes,
                None,
            );
            let Some((old_layout, new_layout, src, dst)) = barrier else {
                continue;
            };
            match handle {
                Raw::Image(image, range) => images.push(ImageBarrier {
                    image,
                    range,
                    old_layout,
                    new_layout,
                    src,
                    dst,
                }),
                Raw::Buffer(buffer) => buffers.push((buffer, src, dst)),
            }
        }
        if !images.is_empty() || !buffers.is_empty() {
            self.barrier(&images, &buffers);
        }
    }

    /// Fills layers 1.. of `image` from layer 0, each layer's top half-height rows the layer
    /// before's rows averaged in vertical pairs (a linear blit): layer l blurs layer 0 over 2^l
    /// rows and keeps its columns. The layers are tracked apart while the chain runs (layer
    /// l − 1 a blit source while layer l is its destination) and end together in
    /// TRANSFER_SRC_OPTIMAL, as one state again.
    pub fn halve_down_layers(&self, image: &Image) {
        image.expect_usage(
            vk::ImageUsageFlags::TRANSFER_SRC | vk::ImageUsageFlags::TRANSFER_DST,
            "blits between its layers",
        );
        if image.layers < 2 {
            return;
        }
        let layers: Vec<Layer> = (0..image.layers)
            .map(|layer| Layer {
                image,
                layer,
                state: StateCell::new(image.state.get()),
            })
            .collect();
        // Layer 0 is read; the others are written (their old contents discarded).
        let mut first: Vec<(&dyn Tracked, Use)> = vec![(&layers[0], Use::TransferSrc)];
        first.extend(
            layers[1..]
                .iter()
                .map(|l| (l as &dyn Tracked, Use::TransferDst)),
        );
        self.uses(&first);
        for layer in &layers[1..] {
            self.blit_half_height(image, layer.layer);
            self.uses(&[(layer, Use::TransferSrc)]);
        }
        let parts: Vec<State> = layers.iter().map(|l| l.state.get()).collect();
        image.state.set(State::merged(&parts));
    }

    /// Records the barriers of pass `pass`'s rendering scope (its attachments, loaded or not
    /// by `Load`, and whatever the shaders of `draws` read through their sets, at the stages
    /// that read) and returns the scope to record, so that a pass's timestamps can start
    /// after its barriers (they time the pass, not the wait for the pass before it). Inside
    /// the scope only these `draws` can be bound ([`Recorder::bind`]). Panics where
    /// [`check_bindings`] would have refused the draws at creation.
    pub fn rendering<'r>(
        &'r self,
        pass: &str,
        colour: &[Target],
        depth: Option<Target>,
        draws: &[Bindings],
    ) -> Rendering<'r> {
        self.expect_outside_scope("a rendering scope");
        self.expect_graphics("a rendering scope");
        check_scope(pass, colour, depth.as_ref(), draws);
        self.ctx.journal_pass(pass);
        let keep = |load: &Load| matches!(load, Load::Keep);
        let mut uses: Vec<(&dyn Tracked, Use)> = Vec::new();
        for t in colour {
            let keep = keep(&t.load);
            uses.push((t.image, Use::Colour { keep }));
        }
        if let Some(t) = &depth {
            let keep = keep(&t.load);
            uses.push((t.image, Use::Depth { keep }));
        }
        let mut sampled: Vec<(&Image, vk::PipelineStageFlags2)> = Vec::new();
        let mut host: Vec<(&Resource, vk::PipelineStageFlags2)> = Vec::new();
        for b in draws {
            for read in reads(pass, b).unwrap_or_else(|e| panic!("{e}")) {
                let stages = pipeline_stages(read.stages);
                match (read.order, read.resource) {
                    (Order::Tracked, Resource::Image(image)) => {
                        match sampled.iter_mut().find(|(i, _)| i.same(image)) {
                            Some((_, s)) => *s |= stages,
                            None => sampled.push((image, stages)),
                        }
                    }
                    // Ordered by a semaphore wait, sampled where its writer left it.
                    (order @ Order::Wait { by, .. }, Resource::Image(image)) => {
                        let access = Access {
                            stage: stages,
                            access: vk::AccessFlags2::SHADER_SAMPLED_READ,
                        };
                        let layout = Some(sampled_layout(order));
                        let journal = (access, layout);
                        self.require_wait(by, stages);
                        self.ctx
                            .journal_use(image.name(), journal, false, None, Some(by));
                    }
                    // A storage buffer written on the compute queue (the spray's particles),
                    // read through the wait like the images.
                    (Order::Wait { by, .. }, Resource::Buffer(buffer)) => {
                        buffer.expect_both_queues("a draw");
                        let access = Access {
                            stage: stages,
                            access: vk::AccessFlags2::SHADER_STORAGE_READ,
                        };
                        self.require_wait(by, stages);
                        self.ctx
                            .journal_use(buffer.name(), (access, None), false, None, Some(by));
                    }
                    // Uniforms, written by the host before the submission.
                    (_, resource) => {
                        let same = |r: &Resource| std::ptr::eq(r, resource);
                        match host.iter_mut().find(|(r, _)| same(r)) {
                            Some((_, s)) => *s |= stages,
                            None => host.push((resource, stages)),
                        }
                    }
                }
            }
        }
        for (resource, stages) in host {
            let access = Access {
                stage: stages,
                access: vk::AccessFlags2::UNIFORM_READ,
            };
            self.journal_host(resource, access);
        }
        for (image, stages) in &sampled {
            uses.push((*image, Use::Sampled(*stages)));
        }
        self.uses(&uses);

        let attachment = |t: &Target, layout| Attachment {
            view: t.view,
            layout,
            load: t.load,
        };
        Rendering {
            rec: self,
            draws: draws.iter().map(Bindings::key).collect(),
            extent: colour
                .first()
                .or(depth.as_ref())
                .map_or(vk::Extent2D::default(), |t| t.extent),
            colour: colour
                .iter()
                .map(|t| attachment(t, vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL))
                .collect(),
            depth: depth.map(|t| attachment(&t, vk::ImageLayout::DEPTH_STENCIL_ATTACHMENT_OPTIMAL)),
        }
    }
}

impl Recorder<'_> {
    /// Binds `b`'s pipeline and sets. A draw inside a rendering scope must use bindings the
    /// scope declared (it panics otherwise: its reads would have no barrier).
    pub fn bind(&self, b: &Bindings) {
        // Each set must be of the layout the pipeline's layout has there (compatible sets:
        // Vulkan spec, "Pipeline Layout Compatibility").
        for (i, set) in b.sets.iter().enumerate() {
            assert!(
                b.pipeline.layout.set(i) == Some(set.layout.as_slice()),
                "set {} bound at {i} for pipeline {}, whose layout has another set there",
                set.name,
                b.pipeline.name
            );
        }
        *self.bound_key.borrow_mut() = Some(b.key());
        self.bind_pipeline(b.pipeline);
        let sets: Vec<vk::DescriptorSet> = b.sets.iter().map(|s| s.raw).collect();
        if !sets.is_empty() {
            self.bind_sets(b.pipeline, &sets);
        }
    }

    /// A compute dispatch of `groups` with `b`: the barriers its shaders' reads and writes of
    /// tracked resources need (storage `readonly`, `writeonly` or both, from the SPIR-V), the
    /// binds, the dispatch. Panics where [`check_bindings`] would have refused `b`.
    pub fn dispatch_with(&self, b: &Bindings, groups: [u32; 3]) {
        self.uses(&self.dispatch_uses(b));
        self.bind(b);
        self.dispatch(groups[0], groups[1], groups[2]);
    }

    /// A compute dispatch whose group counts the GPU wrote (`VkDispatchIndirectCommand` at
    /// `offset` in `args`, tracked on this queue: written by an earlier dispatch), with `b`'s
    /// barriers as [`Recorder::dispatch_with`] records them and the arguments' read in the
    /// DRAW_INDIRECT stage.
    pub fn dispatch_indirect(&self, b: &Bindings, args: &Buffer, offset: vk::DeviceSize) {
        args.expect_usage(
            vk::BufferUsageFlags::INDIRECT_BUFFER,
            "an indirect dispatch",
        );
        let mut uses = self.dispatch_uses(b);
        uses.push((args, Use::IndirectRead));
        self.uses(&uses);
        self.bind(b);
        self.dispatch_indirect_raw(args, offset);
    }

    /// One draw of `VkDrawIndirectCommand` at `offset` in `args`, with the bound pipeline,
    /// inside a rendering scope. The arguments were written on the compute queue: `order` must
    /// be the submission's wait for them (`Order::Wait` covering DRAW_INDIRECT), as a barrier
    /// cannot be recorded inside the scope.
    pub fn draw_indirect(&self, args: &Buffer, offset: vk::DeviceSize, order: Order) {
        args.expect_usage(vk::BufferUsageFlags::INDIRECT_BUFFER, "an indirect draw");
        let stage = vk::PipelineStageFlags2::DRAW_INDIRECT;
        let Order::Wait { by, stages } = order else {
            panic!(
                "indirect draw from {}: its arguments must come through a semaphore wait",
                args.name()
            );
        };
        assert!(
            stages.contains(stage),
            "indirect draw from {}: {by} waits at {stages:?}, not at DRAW_INDIRECT",
            args.name()
        );
        args.expect_both_queues("an indirect draw");
        self.require_wait(by, stage);
        let access = (Access::INDIRECT_READ, None);
        self.ctx
            .journal_use(args.name(), access, false, None, Some(by));
        self.draw_indirect_raw(args, offset);
    }

    /// The tracked uses the shaders of `b` make (barriers for a dispatch).
    fn dispatch_uses<'b>(&self, b: &Bindings<'b>) -> Vec<(&'b dyn Tracked, Use)> {
        let mut uses: Vec<(&dyn Tracked, Use)> = Vec::new();
        for read in reads(b.pipeline.name(), b).unwrap_or_else(|e| panic!("{e}")) {
            match read.order {
                Order::Tracked => {}
                // Written by the host before the submission (tables, twiddles); read only
                // (`reads` refuses a write of what is not tracked).
                Order::Host => {
                    self.journal_host(read.resource, Access::COMPUTE_READ);
                    continue;
                }
                Order::Wait { by, .. } => {
                    let access = (Access::COMPUTE_READ, None);
                    let name = resource_name(read.resource);
                    self.ctx.journal_use(name, access, false, None, Some(by));
                    continue;
                }
            }
            let next = compute_use(&read);
            match read.resource {
                Resource::Image(image) => uses.push((image, next)),
                Resource::Buffer(buffer) => uses.push((&**buffer, next)),
            }
        }
        uses
    }

    /// The frame graph: a read of what the host wrote before the submission.
    fn journal_host(&self, resource: &Resource, access: Access) {
        let by = Some(super::graph::HOST_WRITES);
        let name = resource_name(resource);
        self.ctx.journal_use(name, (access, None), false, None, by);
    }

    /// Names the pass the following uses belong to in the frame graph (uses outside any
    /// rendering scope or timed pass: the readback, the presentation).
    pub fn pass(&self, name: &str) {
        self.ctx.journal_pass(name);
    }
}

/// A rendering scope whose barriers are recorded ([`Recorder::rendering`]).
pub struct Rendering<'r> {
    rec: &'r Recorder<'r>,
    /// The draws it declared: the only bindings `Recorder::bind` accepts inside it.
    draws: Vec<BindingsKey>,
    extent: vk::Extent2D,
    colour: Vec<Attachment>,
    depth: Option<Attachment>,
}

impl Rendering<'_> {
    /// `vkCmdBeginRendering` over the attachments' extent, `body`, `vkCmdEndRendering`.
    pub fn record(self, body: impl FnOnce()) {
        self.rec.expect_outside_scope("a rendering scope");
        self.rec
            .begin_rendering(self.extent, &self.colour, self.depth);
        *self.rec.scope.borrow_mut() = Some(self.draws);
        body();
        self.rec.end_rendering();
        *self.rec.scope.borrow_mut() = None;
    }
}
