//! Passes declare what they use; the recorder turns that into barriers (`track`) and, for
//! rendering, into the scope's attachments: [`Recorder::uses`] and [`Recorder::render`].

use ash::vk;

use super::command::{Attachment, ImageBarrier, Load, Recorder};
use super::image::Image;
use super::track::{transition, Handle, Tracked, Use};

/// An attachment of [`Recorder::render`]: an image (through its default view or another one,
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

    /// A rendering scope over the colour attachments' extent: the barriers for the attachments
    /// (loaded or not, by `Load`) and for `samples` (images its shaders sample), then
    /// `vkCmdBeginRendering`, `body`, `vkCmdEndRendering`.
    pub fn render(
        &self,
        colour: &[Target],
        depth: Option<Target>,
        samples: &[&Image],
        body: impl FnOnce(),
    ) {
        let keep = |load: &Load| matches!(load, Load::Keep);
        let mut uses: Vec<(&dyn Tracked, Use)> = Vec::new();
        for t in colour {
            uses.push((
                t.image,
                Use::Colour {
                    keep: keep(&t.load),
                },
            ));
        }
        if let Some(t) = &depth {
            uses.push((
                t.image,
                Use::Depth {
                    keep: keep(&t.load),
                },
            ));
        }
        for image in samples {
            uses.push((*image, Use::FragmentSampled));
        }
        self.uses(&uses);
        let extent = colour
            .first()
            .or(depth.as_ref())
            .map_or(vk::Extent2D::default(), |t| t.image.extent);
        let attachment = |t: &Target, layout| Attachment {
            view: t.view,
            layout,
            load: t.load,
        };
        let colour: Vec<_> = colour
            .iter()
            .map(|t| attachment(t, vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL))
            .collect();
        let depth =
            depth.map(|t| attachment(&t, vk::ImageLayout::DEPTH_STENCIL_ATTACHMENT_OPTIMAL));
        self.begin_rendering(extent, &colour, depth);
        body();
        self.end_rendering();
    }
}
