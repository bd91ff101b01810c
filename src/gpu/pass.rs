//! Passes declare what they use; the recorder turns that into barriers (`track`) and, for
//! rendering, into the scope's attachments: [`Recorder::uses`] and [`Recorder::rendering`].

use ash::vk;

use super::command::{Attachment, ImageBarrier, Load, Recorder};
use super::image::Image;
use super::track::{transition, Handle, Tracked, Use};

/// An attachment of [`Recorder::rendering`]: an image (through its default view or another one,
/// e.g. a cube face) and what the scope does with its previous contents.
pub struct Target<'a> {
    pub image: &'a Image,
    pub view: vk::ImageView,
    pub load: Load,
}

impl<'a> Target<'a> {
    pub fn new(image: &'a Image, load: Load) -> Target<'a> {
        Target {
            image,
            view: image.view,
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
                .map_or(vk::Extent2D::default(), |t| t.image.extent),
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
