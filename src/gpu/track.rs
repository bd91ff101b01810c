//! Barriers by construction: a render graph reduced to its core. Every image and buffer carries
//! the state its last use left it in ([`State`]: layout, the last write or layout transition,
//! the reads since). A pass names how it uses each resource ([`Use`]) and [`Recorder::uses`]
//! (`pass.rs`) records exactly the barriers those uses need, all in one
//! `vkCmdPipelineBarrier2`; `Recorder::rendering` does the same for a rendering scope's attachments and the textures its
//! shaders sample, then opens the scope. No barrier is written by hand above this file.
//!
//! The rules (Vulkan spec, "Synchronization and Cache Control"):
//! - a write, or a change of layout (itself a write), waits for the last write and every read
//!   since (write-after-write, write-after-read);
//! - a read waits for the last write, unless an earlier barrier already made that write visible
//!   to this stage and access (read-after-read needs nothing);
//! - a use that overwrites the whole resource (an attachment not loaded, a clear, a full
//!   copy) discards the contents: the transition starts from UNDEFINED.
//!
//! A state is the state on one queue, where the first scope of a pipeline barrier covers every
//! earlier submission. Images both queues use (the simulation images, CONCURRENT) are tracked
//! on the compute queue that writes them; the graphics queue samples them in GENERAL through the
//! compute timeline's wait and declares nothing. Modelled on kajiya's render graph
//! (`kajiya-rg/src/graph.rs`: a pass is what it reads and what it writes), much smaller.

use std::cell::Cell;

use ash::vk;

/// One side of a dependency: pipeline stages and the memory accesses made there.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Access {
    pub stage: vk::PipelineStageFlags2,
    pub access: vk::AccessFlags2,
}

impl Access {
    pub const NONE: Access = Access {
        stage: vk::PipelineStageFlags2::NONE,
        access: vk::AccessFlags2::NONE,
    };
    pub const COLOUR_WRITE: Access = Access {
        stage: vk::PipelineStageFlags2::COLOR_ATTACHMENT_OUTPUT,
        access: vk::AccessFlags2::COLOR_ATTACHMENT_WRITE,
    };
    pub const COLOUR_RW: Access = Access {
        stage: vk::PipelineStageFlags2::COLOR_ATTACHMENT_OUTPUT,
        access: vk::AccessFlags2::from_raw(
            vk::AccessFlags2::COLOR_ATTACHMENT_WRITE.as_raw()
                | vk::AccessFlags2::COLOR_ATTACHMENT_READ.as_raw(),
        ),
    };
    pub const DEPTH_RW: Access = Access {
        stage: vk::PipelineStageFlags2::from_raw(
            vk::PipelineStageFlags2::EARLY_FRAGMENT_TESTS.as_raw()
                | vk::PipelineStageFlags2::LATE_FRAGMENT_TESTS.as_raw(),
        ),
        access: vk::AccessFlags2::from_raw(
            vk::AccessFlags2::DEPTH_STENCIL_ATTACHMENT_WRITE.as_raw()
                | vk::AccessFlags2::DEPTH_STENCIL_ATTACHMENT_READ.as_raw(),
        ),
    };
    pub const FRAGMENT_SAMPLED: Access = Access {
        stage: vk::PipelineStageFlags2::FRAGMENT_SHADER,
        access: vk::AccessFlags2::SHADER_SAMPLED_READ,
    };
    pub const COPY_READ: Access = Access {
        stage: vk::PipelineStageFlags2::COPY,
        access: vk::AccessFlags2::TRANSFER_READ,
    };
    pub const COPY_WRITE: Access = Access {
        stage: vk::PipelineStageFlags2::COPY,
        access: vk::AccessFlags2::TRANSFER_WRITE,
    };
    /// A transfer command's read or write: copies, blits (the BLIT stage) and resolves.
    pub const TRANSFER_READ: Access = Access {
        stage: vk::PipelineStageFlags2::ALL_TRANSFER,
        access: vk::AccessFlags2::TRANSFER_READ,
    };
    pub const TRANSFER_WRITE: Access = Access {
        stage: vk::PipelineStageFlags2::ALL_TRANSFER,
        access: vk::AccessFlags2::TRANSFER_WRITE,
    };
    pub const INDEX_READ: Access = Access {
        stage: vk::PipelineStageFlags2::INDEX_INPUT,
        access: vk::AccessFlags2::INDEX_READ,
    };
    /// The arguments of an indirect dispatch or draw (`vkCmdDispatchIndirect`,
    /// `vkCmdDrawIndirect`): read in the DRAW_INDIRECT stage.
    pub const INDIRECT_READ: Access = Access {
        stage: vk::PipelineStageFlags2::DRAW_INDIRECT,
        access: vk::AccessFlags2::INDIRECT_COMMAND_READ,
    };
    pub const HOST_READ: Access = Access {
        stage: vk::PipelineStageFlags2::HOST,
        access: vk::AccessFlags2::HOST_READ,
    };
    /// vkCmdClearColorImage's write (the CLEAR stage of synchronization2).
    pub const CLEAR_WRITE: Access = Access {
        stage: vk::PipelineStageFlags2::CLEAR,
        access: vk::AccessFlags2::TRANSFER_WRITE,
    };
    /// Storage reads and texel fetches (uniform texel buffers, sampled images) in compute.
    pub const COMPUTE_READ: Access = Access {
        stage: vk::PipelineStageFlags2::COMPUTE_SHADER,
        access: vk::AccessFlags2::from_raw(
            vk::AccessFlags2::SHADER_STORAGE_READ.as_raw()
                | vk::AccessFlags2::SHADER_SAMPLED_READ.as_raw(),
        ),
    };
    pub const COMPUTE_WRITE: Access = Access {
        stage: vk::PipelineStageFlags2::COMPUTE_SHADER,
        access: vk::AccessFlags2::SHADER_STORAGE_WRITE,
    };
    /// Any access by any command (coarse; for one-shot uploads and readbacks).
    pub const ALL_READ_WRITE: Access = Access {
        stage: vk::PipelineStageFlags2::ALL_COMMANDS,
        access: vk::AccessFlags2::from_raw(
            vk::AccessFlags2::MEMORY_READ.as_raw() | vk::AccessFlags2::MEMORY_WRITE.as_raw(),
        ),
    };

    /// Union of two scopes.
    pub const fn or(self, other: Access) -> Access {
        Access {
            stage: vk::PipelineStageFlags2::from_raw(self.stage.as_raw() | other.stage.as_raw()),
            access: vk::AccessFlags2::from_raw(self.access.as_raw() | other.access.as_raw()),
        }
    }
}

/// What a use does to a resource: the layout it needs (images), the stages and accesses it
/// makes, and whether it writes or overwrites all of it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Use {
    /// Colour attachment of a rendering scope; `keep`: loads the previous contents.
    Colour { keep: bool },
    /// Depth attachment (tested and written); `keep`: loads the previous contents.
    Depth { keep: bool },
    /// Sampled by shaders in these stages (SHADER_READ_ONLY_OPTIMAL): the stages come from the
    /// SPIR-V of the pipelines that read it (`reflect`, `Recorder::rendering`).
    Sampled(vk::PipelineStageFlags2),
    /// Read by compute shaders (storage, texel buffer or sampled; GENERAL).
    ComputeRead,
    /// Written by compute shaders (GENERAL).
    ComputeWrite,
    /// Read and written by compute shaders (GENERAL).
    ComputeReadWrite,
    /// Cleared whole by `vkCmdClearColorImage` (GENERAL); the contents are discarded.
    Clear,
    /// Source of a copy (`vkCmdCopy*`).
    CopySrc,
    /// Destination of a copy that writes all of it; the contents are discarded.
    CopyDst,
    /// Source of a copy or blit (ALL_TRANSFER).
    TransferSrc,
    /// Destination of a copy or blit that writes all of it; the contents are discarded.
    TransferDst,
    /// Read by the host once the submission is done (buffers).
    HostRead,
    /// Read as indices by indexed draws (buffers).
    IndexRead,
    /// Read as the arguments of an indirect dispatch or draw (buffers).
    IndirectRead,
    /// Handed to the presentation engine (the submission's semaphore signal orders it).
    Present,
}

/// What a [`Use`] needs of a resource.
struct UseInfo {
    layout: vk::ImageLayout,
    /// Stages and accesses.
    access: Access,
    /// The use writes.
    writes: bool,
    /// The use overwrites everything: the previous contents may be discarded.
    discards: bool,
}

impl Use {
    /// Sampled by fragment shaders only.
    pub const FRAGMENT_SAMPLED: Use = Use::Sampled(vk::PipelineStageFlags2::FRAGMENT_SHADER);

    /// Whether the use writes.
    pub fn writes(self) -> bool {
        self.info().writes
    }

    /// Its stages, accesses and layout (the frame graph).
    pub fn scope(self) -> (Access, vk::ImageLayout) {
        let info = self.info();
        (info.access, info.layout)
    }

    fn info(self) -> UseInfo {
        use vk::ImageLayout as L;
        let (layout, access, writes, discards) = match self {
            Use::Colour { keep } => (
                L::COLOR_ATTACHMENT_OPTIMAL,
                if keep {
                    Access::COLOUR_RW
                } else {
                    Access::COLOUR_WRITE
                },
                true,
                !keep,
            ),
            Use::Depth { keep } => (
                L::DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
                Access::DEPTH_RW,
                true,
                !keep,
            ),
            Use::Sampled(stage) => (
                L::SHADER_READ_ONLY_OPTIMAL,
                Access {
                    stage,
                    access: vk::AccessFlags2::SHADER_SAMPLED_READ,
                },
                false,
                false,
            ),
            Use::ComputeRead => (L::GENERAL, Access::COMPUTE_READ, false, false),
            Use::ComputeWrite => (L::GENERAL, Access::COMPUTE_WRITE, true, false),
            Use::ComputeReadWrite => (
                L::GENERAL,
                Access::COMPUTE_READ.or(Access::COMPUTE_WRITE),
                true,
                false,
            ),
            Use::Clear => (L::GENERAL, Access::CLEAR_WRITE, true, true),
            Use::CopySrc => (L::TRANSFER_SRC_OPTIMAL, Access::COPY_READ, false, false),
            Use::CopyDst => (L::TRANSFER_DST_OPTIMAL, Access::COPY_WRITE, true, true),
            Use::TransferSrc => (L::TRANSFER_SRC_OPTIMAL, Access::TRANSFER_READ, false, false),
            Use::TransferDst => (L::TRANSFER_DST_OPTIMAL, Access::TRANSFER_WRITE, true, true),
            Use::HostRead => (L::UNDEFINED, Access::HOST_READ, false, false),
            Use::IndexRead => (L::UNDEFINED, Access::INDEX_READ, false, false),
            Use::IndirectRead => (L::UNDEFINED, Access::INDIRECT_READ, false, false),
            Use::Present => (L::PRESENT_SRC_KHR, Access::NONE, false, false),
        };
        UseInfo {
            layout,
            access,
            writes,
            discards,
        }
    }
}

/// What the last uses of a resource left behind, on the queue that uses it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct State {
    /// The image's layout (UNDEFINED for buffers and new images).
    pub layout: vk::ImageLayout,
    /// The last write or layout transition: a read waits for it.
    pub written: Access,
    /// `written` and every read since: a write or a layout transition waits for them.
    pub used: Access,
    /// Stages and accesses that already see `written` (reads there need no barrier).
    pub visible: Access,
}

impl State {
    /// A resource no command has used yet.
    pub const NEW: State = State {
        layout: vk::ImageLayout::UNDEFINED,
        written: Access::NONE,
        used: Access::NONE,
        visible: Access::NONE,
    };

    /// An image whose contents do not matter, free for use after `stage` (a swapchain image
    /// after the acquire semaphore's wait at `stage`).
    pub fn available_after(stage: vk::PipelineStageFlags2) -> State {
        let after = Access {
            stage,
            access: vk::AccessFlags2::NONE,
        };
        State {
            written: after,
            used: after,
            ..State::NEW
        }
    }

    /// The state of an image whose parts (layers) were tracked apart and left in the same
    /// layout: every write and use of any part, visible where it is visible for all of them.
    pub fn merged(parts: &[State]) -> State {
        let meet = |a: Access, b: Access| Access {
            stage: a.stage & b.stage,
            access: a.access & b.access,
        };
        let first = parts[0];
        parts[1..].iter().fold(first, |m, p| {
            debug_assert_eq!(m.layout, p.layout, "merged parts in different layouts");
            State {
                layout: m.layout,
                written: m.written.or(p.written),
                used: m.used.or(p.used),
                visible: meet(m.visible, p.visible),
            }
        })
    }
}

/// Where a resource's [`State`] lives: read and changed by the GPU layer only, so no code
/// above it can make the tracker skip a barrier.
#[derive(Debug)]
pub struct StateCell(Cell<State>);

impl StateCell {
    pub(super) fn new(state: State) -> StateCell {
        StateCell(Cell::new(state))
    }
    pub(super) fn get(&self) -> State {
        self.0.get()
    }
    pub(super) fn set(&self, state: State) {
        self.0.set(state)
    }
}

/// The barrier a transition needs: (old layout, new layout, src, dst).
pub type Transition = (vk::ImageLayout, vk::ImageLayout, Access, Access);

/// The barrier (if any) before `next` on a resource in `state`, and the state after `next`.
/// `image`: layouts apply (buffers have none).
pub fn transition(state: State, next: Use, image: bool) -> (Option<Transition>, State) {
    let UseInfo {
        layout,
        access,
        writes,
        discards,
    } = next.info();
    let layout = if image {
        layout
    } else {
        vk::ImageLayout::UNDEFINED
    };
    let relayout = image && layout != state.layout;
    if writes || relayout {
        let old = if discards && image {
            vk::ImageLayout::UNDEFINED
        } else {
            state.layout
        };
        let after = State {
            layout,
            written: access,
            used: access,
            visible: if writes { Access::NONE } else { access },
        };
        return (Some((old, layout, state.used, access)), after);
    }
    // Already visible, or never written by a command (host writes are visible to the device
    // at submission).
    if contains(state.visible, access) || state.written == Access::NONE {
        let after = State {
            used: state.used.or(access),
            ..state
        };
        return (None, after);
    }
    let after = State {
        used: state.used.or(access),
        visible: state.visible.or(access),
        ..state
    };
    (
        Some((state.layout, state.layout, state.written, access)),
        after,
    )
}

fn contains(have: Access, want: Access) -> bool {
    have.stage.contains(want.stage) && have.access.contains(want.access)
}

/// Implemented by the GPU layer's resources only (a sealed trait): no code above it can hand
/// the tracker a handle it does not own.
pub(super) mod sealed {
    pub trait Sealed {}
}

/// A resource with a tracked state. Its handle and state are visible to the GPU layer only
/// (`Recorder::uses` and the passes' derived reads change the state, nothing else); only the
/// GPU layer's resources implement it.
pub trait Tracked: sealed::Sealed {
    /// The image and its subresources, or the buffer.
    #[doc(hidden)]
    fn handle(&self) -> Handle;
    /// Its debug name (the frame graph).
    fn name(&self) -> &str;
    #[doc(hidden)]
    fn state(&self) -> &StateCell;
}

/// What a barrier names: opaque outside the GPU layer.
#[derive(Clone, Copy, Debug)]
pub struct Handle(pub(super) Raw);

#[derive(Clone, Copy, Debug)]
pub(super) enum Raw {
    Image(vk::Image, vk::ImageSubresourceRange),
    Buffer(vk::Buffer),
}

impl Handle {
    pub(super) fn image(raw: vk::Image, range: vk::ImageSubresourceRange) -> Handle {
        Handle(Raw::Image(raw, range))
    }
    pub(super) fn buffer(raw: vk::Buffer) -> Handle {
        Handle(Raw::Buffer(raw))
    }
}

/// An image this program does not own (a swapchain image), tracked for the length of one
/// frame from the state it was handed over in. Made by the GPU layer (`Swapchain`).
pub struct ExternalImage {
    pub(super) raw: vk::Image,
    pub(super) view: vk::ImageView,
    pub(super) extent: vk::Extent2D,
    pub(super) format: vk::Format,
    pub(super) usage: vk::ImageUsageFlags,
    pub(super) name: String,
    pub(super) state: StateCell,
}

impl ExternalImage {
    pub fn extent(&self) -> vk::Extent2D {
        self.extent
    }
    pub fn format(&self) -> vk::Format {
        self.format
    }
}

impl sealed::Sealed for ExternalImage {}

impl Tracked for ExternalImage {
    fn handle(&self) -> Handle {
        let colour = vk::ImageSubresourceRange {
            aspect_mask: vk::ImageAspectFlags::COLOR,
            base_mip_level: 0,
            level_count: 1,
            base_array_layer: 0,
            layer_count: 1,
        };
        Handle::image(self.raw, colour)
    }
    fn name(&self) -> &str {
        &self.name
    }
    fn state(&self) -> &StateCell {
        &self.state
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use vk::ImageLayout as L;

    fn run(uses: &[Use]) -> Vec<Option<Transition>> {
        let mut state = State::NEW;
        uses.iter()
            .map(|u| {
                let (barrier, after) = transition(state, *u, true);
                state = after;
                barrier
            })
            .collect()
    }

    #[test]
    fn a_render_target_frame_needs_the_barriers_written_by_hand_before() {
        let b = run(&[
            Use::Colour { keep: false },
            Use::FRAGMENT_SAMPLED,
            Use::FRAGMENT_SAMPLED,
            Use::Colour { keep: false },
        ]);
        // First use: from nothing.
        assert_eq!(
            b[0],
            Some((
                L::UNDEFINED,
                L::COLOR_ATTACHMENT_OPTIMAL,
                Access::NONE,
                Access::COLOUR_WRITE
            ))
        );
        // Written, then sampled: layout change after the write.
        assert_eq!(
            b[1],
            Some((
                L::COLOR_ATTACHMENT_OPTIMAL,
                L::SHADER_READ_ONLY_OPTIMAL,
                Access::COLOUR_WRITE,
                Access::FRAGMENT_SAMPLED
            ))
        );
        // Sampled again: already visible.
        assert_eq!(b[2], None);
        // Next frame: discarded and rewritten after the reads.
        assert_eq!(
            b[3],
            Some((
                L::UNDEFINED,
                L::COLOR_ATTACHMENT_OPTIMAL,
                Access::FRAGMENT_SAMPLED,
                Access::COLOUR_WRITE
            ))
        );
    }

    #[test]
    fn reads_in_a_new_stage_wait_for_the_write_and_a_later_write_for_every_read() {
        let b = run(&[
            Use::ComputeWrite,
            Use::ComputeRead,
            Use::CopySrc,
            Use::CopySrc,
            Use::ComputeWrite,
        ]);
        assert_eq!(
            b[1],
            Some((
                L::GENERAL,
                L::GENERAL,
                Access::COMPUTE_WRITE,
                Access::COMPUTE_READ
            ))
        );
        // A new layout: a transition, after the write and the compute read.
        let (old, new, src, dst) = b[2].expect("copy needs a transition");
        assert_eq!((old, new), (L::GENERAL, L::TRANSFER_SRC_OPTIMAL));
        assert!(contains(src, Access::COMPUTE_WRITE) && contains(src, Access::COMPUTE_READ));
        assert_eq!(dst, Access::COPY_READ);
        assert_eq!(b[3], None);
        // Back to GENERAL for a write: after the copy's read.
        assert_eq!(
            b[4],
            Some((
                L::TRANSFER_SRC_OPTIMAL,
                L::GENERAL,
                Access::COPY_READ,
                Access::COMPUTE_WRITE
            ))
        );
    }

    #[test]
    fn buffers_have_no_layouts_and_read_after_read_is_free() {
        let mut state = State::NEW;
        let mut step = |u| {
            let (barrier, after) = transition(state, u, false);
            state = after;
            barrier
        };
        assert_eq!(
            step(Use::CopyDst),
            Some((L::UNDEFINED, L::UNDEFINED, Access::NONE, Access::COPY_WRITE))
        );
        assert_eq!(
            step(Use::ComputeRead),
            Some((
                L::UNDEFINED,
                L::UNDEFINED,
                Access::COPY_WRITE,
                Access::COMPUTE_READ
            ))
        );
        assert_eq!(step(Use::ComputeRead), None);
        let (_, _, src, _) = step(Use::ComputeWrite).expect("write after read");
        assert!(contains(src, Access::COMPUTE_READ));
    }

    #[test]
    fn a_swapchain_image_is_written_after_the_acquire_and_presented_after_the_write() {
        let mut state = State::available_after(vk::PipelineStageFlags2::ALL_TRANSFER);
        let (b, after) = transition(state, Use::TransferDst, true);
        let (old, new, src, _) = b.expect("first write");
        assert_eq!((old, new), (L::UNDEFINED, L::TRANSFER_DST_OPTIMAL));
        assert_eq!(src.stage, vk::PipelineStageFlags2::ALL_TRANSFER);
        state = after;
        let (b, _) = transition(state, Use::Present, true);
        assert_eq!(
            b,
            Some((
                L::TRANSFER_DST_OPTIMAL,
                L::PRESENT_SRC_KHR,
                Access::TRANSFER_WRITE,
                Access::NONE
            ))
        );
    }

    #[test]
    fn merged_layers_wait_for_every_write_and_see_only_what_all_see() {
        // A blit chain's end: layer 0 read by a blit after a colour write, layer 1 written
        // by that blit and then made a blit source.
        let after = |uses: &[Use]| {
            uses.iter()
                .fold(State::NEW, |state, u| transition(state, *u, true).1)
        };
        let zero = after(&[Use::Colour { keep: false }, Use::TransferSrc]);
        let one = after(&[Use::TransferDst, Use::TransferSrc]);
        let merged = State::merged(&[zero, one]);
        assert_eq!(merged.layout, L::TRANSFER_SRC_OPTIMAL);
        assert_eq!(merged.written, zero.written.or(one.written));
        assert_eq!(merged.used, zero.used.or(one.used));
        // A fragment read then waits for the transfers (a layout change) as for one image.
        let (barrier, _) = transition(merged, Use::FRAGMENT_SAMPLED, true);
        let (old, new, src, _) = barrier.expect("a layout transition");
        assert_eq!(
            (old, new),
            (L::TRANSFER_SRC_OPTIMAL, L::SHADER_READ_ONLY_OPTIMAL)
        );
        assert!(src.stage.contains(vk::PipelineStageFlags2::ALL_TRANSFER));
        // Visible only where every part is visible.
        let seen = State {
            visible: Access::COPY_READ,
            ..one
        };
        let unseen = State {
            visible: Access::NONE,
            ..one
        };
        assert_eq!(State::merged(&[seen, unseen]).visible, Access::NONE);
    }
}
