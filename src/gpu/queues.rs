//! The queue plan: which queue family and queue draw and present, which one runs the ocean
//! simulation, and how resources used by both are shared. A pure function of the device's
//! `VkQueueFamilyProperties[]` (and which families can present), so it is unit-tested on real
//! GPUs' family tables although CI has only lavapipe (one family, one queue).
//!
//! The choice:
//! - graphics (and present): the first family with GRAPHICS that can present (any GRAPHICS
//!   family when there is no window);
//! - compute: the first family with COMPUTE and without GRAPHICS (NVIDIA's, AMD's and Intel's
//!   async-compute family), queue 0; else a second queue of the graphics family when it has
//!   one; else the graphics queue itself (lavapipe), where the two submissions simply run in
//!   order.
//!
//! Resources both families touch (the simulation images: compute writes, graphics samples) are
//! created CONCURRENT between the two families, so no queue-family ownership transfer is ever needed:
//! the timeline semaphores alone order the work and carry the memory dependencies (a
//! semaphore signal's first access scope and a wait's second access scope are all memory
//! accesses, Vulkan spec §7.4.1/7.4.2). Everything else has one user family and stays
//! EXCLUSIVE: h0 and the ω steps are uploaded, read and (`--dump`) read back on the compute
//! queue only (src/ocean/simulation/fft_model.rs, readback.rs), and every buffer is created
//! EXCLUSIVE (src/gpu/buffer.rs). On one family (or two queues of one family) everything is
//! EXCLUSIVE: ownership belongs to families, not queues.
//!
//! Priorities (`queue_priorities`): when compute has a queue of its own, the graphics and
//! present queue gets 1.0 and the compute queue 0.5, as in Khronos' async-compute sample
//! (KhronosGroup/Vulkan-Samples, `performance/async_compute`): the frame the user waits for
//! is drawn and presented on the graphics queue, and the simulation has a frame of slack
//! (double-buffered images). One queue (lavapipe) keeps 1.0.

use ash::vk;

/// Priority of the graphics and present queue: the frame on screen waits for it.
pub const GRAPHICS_PRIORITY: f32 = 1.0;
/// Priority of a compute queue of its own: lower than graphics, as in Khronos' async-compute
/// sample; the simulation runs a frame ahead of the graphics work that samples it.
pub const COMPUTE_PRIORITY: f32 = 0.5;

/// A queue: its family and its index in that family.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct QueueSlot {
    pub family: u32,
    pub index: u32,
}

/// Which queues a resource is used on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum QueueUsers {
    /// The graphics queue only (render targets, uniforms, uploads it alone reads).
    Graphics,
    /// The compute queue only (the FFT's working buffers, Gerstner wave tables written by the host).
    Compute,
    /// Both (the simulation images).
    Both,
}

/// How a resource is shared between queue families (`VkSharingMode` and, for CONCURRENT, the
/// family indices to list in its create info).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Sharing {
    pub mode: vk::SharingMode,
    pub families: Vec<u32>,
}

/// The queues vkocean uses on one device.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct QueuePlan {
    /// Draws every graphics pass, runs one-shot uploads and readbacks, presents.
    pub graphics: QueueSlot,
    /// Runs the ocean simulation (evolve, FFT, assemble, or Gerstner).
    pub compute: QueueSlot,
}

impl QueuePlan {
    /// Chooses the queues from the device's families; `presents(i)` tells whether family `i` can
    /// present to the window (always true without one). `Err` names what is missing.
    pub fn choose(
        families: &[vk::QueueFamilyProperties],
        presents: impl Fn(u32) -> bool,
    ) -> Result<QueuePlan, &'static str> {
        let usable = |q: &vk::QueueFamilyProperties| q.queue_count > 0;
        let graphics_family = families
            .iter()
            .enumerate()
            .position(|(i, q)| {
                usable(q) && q.queue_flags.contains(vk::QueueFlags::GRAPHICS) && presents(i as u32)
            })
            .ok_or("no graphics queue (that can present to the window)")?
            as u32;
        let graphics = QueueSlot {
            family: graphics_family,
            index: 0,
        };
        let dedicated = families.iter().position(|q| {
            usable(q)
                && q.queue_flags.contains(vk::QueueFlags::COMPUTE)
                && !q.queue_flags.contains(vk::QueueFlags::GRAPHICS)
        });
        let compute = match dedicated {
            Some(family) => QueueSlot {
                family: family as u32,
                index: 0,
            },
            // GRAPHICS families always support compute work (spec: a family with GRAPHICS
            // must also have COMPUTE when any family has COMPUTE); use a second queue if any.
            None if families[graphics_family as usize].queue_count > 1 => QueueSlot {
                family: graphics_family,
                index: 1,
            },
            None => graphics,
        };
        Ok(QueuePlan { graphics, compute })
    }

    /// The compute work runs on a family of its own.
    pub fn separate_families(&self) -> bool {
        self.graphics.family != self.compute.family
    }

    /// The compute work runs on a queue of its own (it can overlap the graphics work).
    pub fn separate_queues(&self) -> bool {
        self.graphics != self.compute
    }

    /// Family of the queue that presents (the graphics queue's).
    pub fn present_family(&self) -> u32 {
        self.graphics.family
    }

    /// Queues to create: (family, count), one entry per family.
    pub fn queue_requests(&self) -> Vec<(u32, u32)> {
        if self.separate_families() {
            vec![(self.graphics.family, 1), (self.compute.family, 1)]
        } else {
            vec![(self.graphics.family, self.compute.index + 1)]
        }
    }

    /// Priorities of the queues to create, per entry of `queue_requests` (same order): the
    /// graphics and present queue 1.0, a compute queue of its own 0.5 (see the file's doc).
    pub fn queue_priorities(&self) -> Vec<(u32, Vec<f32>)> {
        self.queue_requests()
            .into_iter()
            .map(|(family, count)| {
                let priorities = (0..count)
                    .map(|index| {
                        let queue = QueueSlot { family, index };
                        if queue == self.graphics {
                            GRAPHICS_PRIORITY
                        } else {
                            COMPUTE_PRIORITY
                        }
                    })
                    .collect();
                (family, priorities)
            })
            .collect()
    }

    /// How a resource used on `users` is shared: CONCURRENT between the two families only when
    /// both use it and they differ.
    pub fn sharing(&self, users: QueueUsers) -> Sharing {
        match users {
            QueueUsers::Both if self.separate_families() => Sharing {
                mode: vk::SharingMode::CONCURRENT,
                families: vec![self.graphics.family, self.compute.family],
            },
            _ => Sharing {
                mode: vk::SharingMode::EXCLUSIVE,
                families: Vec::new(),
            },
        }
    }

    /// One line for logs and `--list-gpus`-style reports.
    pub fn describe(&self) -> String {
        let compute = if !self.separate_queues() {
            "the graphics queue".to_string()
        } else if self.separate_families() {
            format!(
                "family {} queue {}",
                self.compute.family, self.compute.index
            )
        } else {
            format!(
                "queue {} of the graphics family {}",
                self.compute.index, self.compute.family
            )
        };
        format!(
            "graphics and present: family {} queue {}; compute: {compute}",
            self.graphics.family, self.graphics.index
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const G: vk::QueueFlags = vk::QueueFlags::GRAPHICS;
    const C: vk::QueueFlags = vk::QueueFlags::COMPUTE;
    const T: vk::QueueFlags = vk::QueueFlags::TRANSFER;
    const S: vk::QueueFlags = vk::QueueFlags::SPARSE_BINDING;

    fn table(rows: &[(vk::QueueFlags, u32)]) -> Vec<vk::QueueFamilyProperties> {
        rows.iter()
            .map(|&(flags, count)| vk::QueueFamilyProperties {
                queue_flags: flags,
                queue_count: count,
                timestamp_valid_bits: 64,
                ..Default::default()
            })
            .collect()
    }

    fn slot(family: u32, index: u32) -> QueueSlot {
        QueueSlot { family, index }
    }

    fn concurrent(families: &[u32]) -> Sharing {
        Sharing {
            mode: vk::SharingMode::CONCURRENT,
            families: families.to_vec(),
        }
    }

    fn exclusive() -> Sharing {
        Sharing {
            mode: vk::SharingMode::EXCLUSIVE,
            families: vec![],
        }
    }

    /// Asserts the plan for a family table: queues, what is CONCURRENT, and (by construction)
    /// that nothing needs an ownership transfer: every resource with two user families is
    /// CONCURRENT between exactly those families, every other one has one user family.
    fn check(
        families: &[vk::QueueFamilyProperties],
        graphics: QueueSlot,
        compute: QueueSlot,
        shared: Sharing,
        queues: &[(u32, u32)],
    ) {
        let plan = QueuePlan::choose(families, |_| true).unwrap();
        assert_eq!(plan.graphics, graphics, "{}", plan.describe());
        assert_eq!(plan.compute, compute, "{}", plan.describe());
        assert_eq!(plan.present_family(), graphics.family);
        assert_eq!(plan.sharing(QueueUsers::Both), shared);
        assert_eq!(plan.sharing(QueueUsers::Graphics), exclusive());
        assert_eq!(plan.sharing(QueueUsers::Compute), exclusive());
        assert_eq!(plan.queue_requests(), queues);
        for &(family, count) in queues {
            assert!(count <= families[family as usize].queue_count);
        }
        // One priority per queue created; graphics 1.0, a compute queue of its own 0.5.
        let priorities = plan.queue_priorities();
        let expected: Vec<(u32, Vec<f32>)> = if !plan.separate_queues() {
            vec![(graphics.family, vec![1.0])]
        } else if plan.separate_families() {
            vec![(graphics.family, vec![1.0]), (compute.family, vec![0.5])]
        } else {
            vec![(graphics.family, vec![1.0, 0.5])]
        };
        assert_eq!(priorities, expected);
    }

    #[test]
    fn nvidia_computes_on_its_compute_family() {
        // NVIDIA (e.g. RTX 30x0): 0 = G|C|T|S ×16, 1 = T|S ×2, 2 = C|T|S ×8.
        let nvidia = table(&[(G | C | T | S, 16), (T | S, 2), (C | T | S, 8)]);
        check(
            &nvidia,
            slot(0, 0),
            slot(2, 0),
            concurrent(&[0, 2]),
            &[(0, 1), (2, 1)],
        );
    }

    #[test]
    fn amd_rdna_computes_on_its_compute_family() {
        // AMD RDNA: 0 = G|C|T|S ×1, 1 = C|T|S ×4, 2 = T|S ×2.
        let amd = table(&[(G | C | T | S, 1), (C | T | S, 4), (T | S, 2)]);
        check(
            &amd,
            slot(0, 0),
            slot(1, 0),
            concurrent(&[0, 1]),
            &[(0, 1), (1, 1)],
        );
    }

    #[test]
    fn intel_arc_computes_on_its_compute_family() {
        // Intel Arc: 0 = G|C|T ×1, 1 = C|T ×1, 2 = T ×1.
        let arc = table(&[(G | C | T, 1), (C | T, 1), (T, 1)]);
        check(
            &arc,
            slot(0, 0),
            slot(1, 0),
            concurrent(&[0, 1]),
            &[(0, 1), (1, 1)],
        );
    }

    #[test]
    fn lavapipe_shares_its_one_queue() {
        // lavapipe: 0 = G|C|T|S ×1. Everything EXCLUSIVE, one queue, two submissions in order.
        let lavapipe = table(&[(G | C | T | S, 1)]);
        check(&lavapipe, slot(0, 0), slot(0, 0), exclusive(), &[(0, 1)]);
        let plan = QueuePlan::choose(&lavapipe, |_| true).unwrap();
        assert!(!plan.separate_queues());
    }

    #[test]
    fn one_family_with_two_queues_computes_on_the_second() {
        // A single universal family with several queues: overlap without any sharing.
        let one_family = table(&[(G | C | T, 4)]);
        check(&one_family, slot(0, 0), slot(0, 1), exclusive(), &[(0, 2)]);
    }

    #[test]
    fn graphics_family_must_present() {
        // Family 0 cannot present to the window, family 1 can: draw and present on 1.
        let families = table(&[(G | C | T, 1), (G | C | T, 1), (C | T, 2)]);
        let plan = QueuePlan::choose(&families, |i| i == 1).unwrap();
        assert_eq!(plan.graphics, slot(1, 0));
        assert_eq!(plan.compute, slot(2, 0));
        assert!(QueuePlan::choose(&families, |_| false).is_err());
        assert!(QueuePlan::choose(&table(&[(C | T, 2)]), |_| true).is_err());
    }
}
