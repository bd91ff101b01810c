//! Passes declare what they use; the recorder turns that into barriers (`track`) and, for
//! rendering, into the scope's attachments: [`Recorder::uses`] and [`Recorder::rendering`].

use std::cell::Cell;

use ash::vk;

use super::command::{Attachment, ImageBarrier, Load, Recorder};
use super::image::Image;
use super::track::{transition, Handle, State, Tracked, Use};

/// One layer of an image, tracked on its own while `Recorder::halve_down_layers` runs.
struct Layer<'a> {
    image: &'a Image,
    layer: u32,
    state: Cell<State>,
}

impl Tracked for Layer<'_> {
    fn handle(&self) -> Handle {
        let range = vk::ImageSubresourceRange {
            base_array_layer: self.layer,
            layer_count: 1,
            ..self.image.range()
        };
        Handle::Image(self.image.raw, range)
    }
    fn state(&self) -> &Cell<State> {
        &self.state
    }
}

/// An attachment of [`Recorder::rendering`]: an image (through its default view, layer 0 of a
/// layered one, or another view, e.g. a cube face) and what the scope does with its previous
/// contents.
pub struct Target<'a> {
    pub image: &'a dyn Tracked,
    pub view: vk::ImageView,
    pub extent: vk::Extent2D,
    pub load: Load,
}

impl<'a> Target<'a> {
    pub fn new(image: &'a Image, load: Load) -> Target<'a> {
        Target {
            image,
            view: image.layer_views.first().copied().unwrap_or(image.view),
            extent: image.extent,
            load,
        }
    }

    /// An image the renderer does not own (a swapchain image), through `view`.
    pub fn external(
        image: &'a dyn Tracked,
        view: vk::ImageView,
        extent: vk::Extent2D,
        load: Load,
    ) -> Target<'a> {
        Target {
            image,
            view,
            extent,
            load,
        }
    }
}

impl Recorder<'_> {
    /// Records the barriers `uses` need (none when every use already sees what it needs) and
    /// moves each resource to its state after the use.
    pub fn uses(&self, uses: &[(&dyn Tracked, Use)]) {
        let mut images = Vec::new();
        let mut buffers = Vec::new();
        for (resource, next) in uses {
            let handle = resource.handle();
            let (barrier, after) = transition(
                resource.state().get(),
                *next,
                matches!(handle, Handle::Image(..)),
            );
            resource.state().set(after);
            let Some((old_layout, new_layout, src, dst)) = barrier else {
                continue;
            };
            match handle {
                Handle::Image(image, range) => images.push(ImageBarrier {
                    image,
                    range,
                    old_layout,
                    new_layout,
                    src,
                    dst,
                }),
                Handle::Buffer(buffer) => buffers.push((buffer, src, dst)),
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
        if image.layers < 2 {
            return;
        }
        let layers: Vec<Layer> = (0..image.layers)
            .map(|layer| Layer {
                image,
                layer,
                state: Cell::new(image.state.get()),
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

    /// Records the barriers a rendering scope needs (its attachments, loaded or not by `Load`,
    /// and `samples`, the images its shaders sample) and returns the scope to record, so that
    /// a pass's timestamps can start after its barriers (they time the pass, not the wait for
    /// the pass before it).
    pub fn rendering<'r>(
        &'r self,
        colour: &[Target],
        depth: Option<Target>,
        samples: &[&Image],
    ) -> Rendering<'r> {
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
        for image in samples {
            uses.push((*image, Use::FragmentSampled));
        }
        self.uses(&uses);
        let attachment = |t: &Target, layout| Attachment {
            view: t.view,
            layout,
            load: t.load,
        };
        Rendering {
            rec: self,
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

/// A rendering scope whose barriers are recorded ([`Recorder::rendering`]).
pub struct Rendering<'r> {
    rec: &'r Recorder<'r>,
    extent: vk::Extent2D,
    colour: Vec<Attachment>,
    depth: Option<Attachment>,
}

impl Rendering<'_> {
    /// `vkCmdBeginRendering` over the attachments' extent, `body`, `vkCmdEndRendering`.
    pub fn record(self, body: impl FnOnce()) {
        self.rec
            .begin_rendering(self.extent, &self.colour, self.depth);
        body();
        self.rec.end_rendering();
    }
}
