//! The Vulkan context: it ties together the instance (`instance.rs`), the chosen physical device
//! (`physical.rs`), the logical device with the features vkocean needs, the graphics and compute
//! queues, the memory allocator, the frame timeline semaphore and the deferred-deletion queue.
//!
//! Every other GPU object holds an `Arc<Context>`; the context is destroyed last.

use std::ffi::c_char;
use std::mem::ManuallyDrop;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

use ash::vk;
use gpu_allocator::vulkan::{Allocator, AllocatorCreateDesc};
use gpu_allocator::{AllocationSizes, AllocatorDebugSettings};
use raw_window_handle::{RawDisplayHandle, RawWindowHandle};

use super::debug::{self, DebugNames, MessageCounters};
use super::error::{GpuError, GpuResult, VkResultExt};
use super::garbage::Garbage;
use super::graph::{FrameGraph, Journal, SemaphoreRecord};
use super::track::Access;

/// How long a GPU wait may take before the device is declared hung (s).
pub const WAIT_TIMEOUT_S: u64 = 60;
/// The same under GPU-assisted validation: every dispatch is instrumented, a first frame may
/// carry many warm-up steps in one submission (a wake's 400), and a CPU driver (llvmpipe)
/// compiles a shader's variants at its first draw, inside the frame's work. Measured on
/// lavapipe, 2 cores busy with a build: 7 s a frame at 160x90 with floating bodies and a
/// wake, and once over 60 s for one frame (tools/validate-newest).
pub const GPU_ASSISTED_WAIT_TIMEOUT_S: u64 = 240;
use super::instance::{create_instance, load_entry, surface_handles, ValidationExtras};
use super::physical::{best_usable, inspect, lacks, type_name, Candidate};
pub use super::physical::{chosen_device_is_cpu, list_devices, DeviceInfo, DeviceSummary, Needs};
use super::queues::{QueuePlan, QueueUsers, Sharing};

/// What the caller wants from the context.
#[derive(Clone, Copy, Debug)]
pub struct ContextDesc {
    /// Enable VK_LAYER_KHRONOS_validation with synchronization validation.
    pub validation: bool,
    /// With `validation`: the layer's extra checks (`--validation-extra`).
    pub validation_extras: ValidationExtras,
    /// `--gpu N`: index into the device list (`--list-gpus`); `None` picks the best device.
    pub gpu_index: Option<usize>,
    /// What the run uses of the device: only devices that have it are candidates.
    pub needs: Needs,
    /// Window to present to (windowed frontend); `None` for headless.
    pub window: Option<(RawDisplayHandle, RawWindowHandle)>,
}

/// A queue and the family it belongs to.
#[derive(Clone, Copy, Debug)]
pub struct Queue {
    pub family: u32,
    pub(super) raw: vk::Queue,
}

/// The device-wide state every GPU object refers to.
pub struct Context {
    /// Keeps the loader library loaded; never used after creation.
    _entry: ash::Entry,
    pub(super) instance: ash::Instance,
    messenger: Option<(ash::ext::debug_utils::Instance, vk::DebugUtilsMessengerEXT)>,
    /// Object names and labels.
    pub(super) debug: DebugNames,
    /// Surface functions and the window's surface (windowed frontend only).
    pub(super) surface: Option<(ash::khr::surface::Instance, vk::SurfaceKHR)>,
    pub(super) physical: vk::PhysicalDevice,
    pub(super) device: ash::Device,
    pub info: DeviceInfo,
    /// Graphics queue; also presents in the windowed frontend.
    pub graphics: Queue,
    /// Compute queue: a family of its own where the device has one, else a second queue of the
    /// graphics family, else the graphics queue (`QueuePlan`).
    pub compute: Queue,
    /// Which queues draw, present and compute, and how shared resources are shared.
    pub plan: QueuePlan,
    /// The graphics timeline: frame f's graphics submission signals f + 1.
    pub(super) frame_timeline: vk::Semaphore,
    /// Shared (an `Arc`) with the overlay's egui renderer, which allocates through it too.
    allocator: ManuallyDrop<Arc<Mutex<Allocator>>>,
    /// Objects dropped by their owners, destroyed once `frame_timeline` passes their tag.
    garbage: Mutex<Vec<(u64, Garbage)>>,
    /// Timeline value the next graphics submission will signal (tag for new garbage).
    pending_value: AtomicU64,
    /// Highest timeline value submitted so far.
    signaled_value: AtomicU64,
    /// Validation message counts; dropped after the instance.
    counters: Arc<MessageCounters>,
    /// Device objects created and destroyed through the GPU layer (`live_objects`).
    objects_created: AtomicU64,
    objects_destroyed: AtomicU64,
    /// Command buffers whose recording failed (a pipeline made on first use could not be
    /// made) and the error their submission returns (`fail_recording`).
    recording_failures: Mutex<Vec<(vk::CommandBuffer, GpuError)>>,
    /// The frame graph being recorded (`capture_frame_graph`), if any.
    journal: Mutex<Option<Journal>>,
    /// Semaphore names, for the frame graph.
    semaphore_names: Mutex<std::collections::HashMap<u64, String>>,
    /// How long a GPU wait may take before the device is declared hung (s): `WAIT_TIMEOUT_S`,
    /// or `GPU_ASSISTED_WAIT_TIMEOUT_S` under GPU-assisted validation.
    pub(super) wait_timeout_s: u64,
}

impl Context {
    /// A context without a window (headless runs and benchmarks).
    pub fn headless(
        validation: bool,
        validation_extras: ValidationExtras,
        gpu_index: Option<usize>,
        needs: Needs,
    ) -> GpuResult<Arc<Context>> {
        Context::new(&ContextDesc {
            validation,
            validation_extras,
            gpu_index,
            needs,
            window: None,
        })
    }

    /// Creates the instance, picks the device (`desc.gpu_index` or the best one), creates the
    /// device, queues, allocator and frame timeline.
    // Long: Vulkan's creation sequence (instance, messenger, surface, device choice, device,
    // queues, allocator, timeline) with one partial-teardown guard; split, the guard would
    // have to travel through every piece.
    pub fn new(desc: &ContextDesc) -> GpuResult<Arc<Context>> {
        let entry = load_entry()?;
        let counters = Arc::new(MessageCounters::new(desc.validation));
        let window = desc
            .window
            .map(|handles| surface_handles(&entry, handles))
            .transpose()?;
        let (instance, debug_utils) = create_instance(
            &entry,
            desc.validation,
            desc.validation_extras,
            window.map(|w| w.0),
            &counters,
        )?;
        // From here on, partial state is torn down by `Partial`'s Drop on early return.
        let mut partial = Partial {
            instance: Some(instance.clone()),
            messenger: None,
            surface: None,
            device: None,
        };

        if debug_utils {
            let fns = ash::ext::debug_utils::Instance::new(&entry, &instance);
            let info = debug::messenger_info(&counters);
            // SAFETY: `info` is valid; `counters` outlives the messenger (owned by Context).
            let messenger = unsafe { fns.create_debug_utils_messenger(&info, None) }
                .vk("vkCreateDebugUtilsMessengerEXT")?;
            partial.messenger = Some((fns, messenger));
        }
        if let Some((display, window)) = window {
            // SAFETY: the handles come from a live winit window that outlives the context
            // (the windowed frontend drops the context first).
            let surface =
                unsafe { ash_window::create_surface(&entry, &instance, display, window, None) }
                    .vk("vkCreate*SurfaceKHR (ash_window::create_surface)")?;
            partial.surface = Some((ash::khr::surface::Instance::new(&entry, &instance), surface));
        }

        // SAFETY: the instance is live.
        let physicals =
            unsafe { instance.enumerate_physical_devices() }.vk("vkEnumeratePhysicalDevices")?;
        if physicals.is_empty() {
            return Err(GpuError::NoDevice);
        }
        let inspected: Vec<_> = physicals
            .iter()
            .map(|&p| {
                let (parts, usable) = inspect(&instance, p, partial.surface.as_ref());
                let usable = usable.and_then(|c| match lacks(&c.info, desc.needs) {
                    None => Ok(c),
                    Some(why) => Err(why),
                });
                (parts, usable)
            })
            .collect();
        let chosen = match desc.gpu_index {
            Some(index) => {
                let count = inspected.len();
                let (parts, usable) = inspected
                    .into_iter()
                    .nth(index)
                    .ok_or(GpuError::BadGpuIndex { index, count })?;
                usable.map_err(|why| {
                    GpuError::NoSuitableDevice(format!("device {index} ({}): {why}", parts.name))
                })?
            }
            None => {
                let types: Vec<_> = inspected
                    .iter()
                    .map(|(_, usable)| usable.as_ref().ok().map(|c| c.info.device_type))
                    .collect();
                let best = best_usable(&types);
                let mut reasons = Vec::new();
                let mut chosen = None;
                for (i, (parts, usable)) in inspected.into_iter().enumerate() {
                    match usable {
                        Ok(c) if Some(i) == best => chosen = Some(c),
                        Ok(_) => {}
                        Err(why) => reasons.push(format!("device {i} ({}): {why}", parts.name)),
                    }
                }
                chosen.ok_or_else(|| GpuError::NoSuitableDevice(reasons.join("; ")))?
            }
        };
        log::info!(
            "device: {} ({}, {})",
            chosen.info.name,
            type_name(chosen.info.device_type),
            chosen.info.driver
        );

        let device = create_device(&instance, &chosen, desc.window.is_some())?;
        partial.device = Some(device.clone());

        let plan = chosen.plan;
        log::info!("queues: {}", plan.describe());
        // SAFETY: `create_device` requested these families and queue counts (`queue_requests`).
        let graphics = Queue {
            family: plan.graphics.family,
            raw: unsafe { device.get_device_queue(plan.graphics.family, plan.graphics.index) },
        };
        let compute = if plan.separate_queues() {
            // SAFETY: as above.
            Queue {
                family: plan.compute.family,
                raw: unsafe { device.get_device_queue(plan.compute.family, plan.compute.index) },
            }
        } else {
            graphics
        };

        let allocator = Allocator::new(&AllocatorCreateDesc {
            instance: instance.clone(),
            device: device.clone(),
            physical_device: chosen.physical,
            debug_settings: AllocatorDebugSettings::default(),
            buffer_device_address: false,
            // Smaller blocks than the 256 MiB default: lavapipe's "device memory" is host RAM.
            allocation_sizes: AllocationSizes::new(64 << 20, 64 << 20),
        })
        .map_err(|source| GpuError::Alloc {
            name: "allocator".into(),
            source,
        })?;

        let mut timeline_type = vk::SemaphoreTypeCreateInfo::default()
            .semaphore_type(vk::SemaphoreType::TIMELINE)
            .initial_value(0);
        let sem_info = vk::SemaphoreCreateInfo::default().push_next(&mut timeline_type);
        // SAFETY: the device is live; the info chain points to locals.
        let frame_timeline =
            unsafe { device.create_semaphore(&sem_info, None) }.vk("vkCreateSemaphore")?;

        let debug = DebugNames {
            device_fns: debug_utils.then(|| ash::ext::debug_utils::Device::new(&instance, &device)),
        };
        // Everything is owned by the context now.
        let messenger = partial.messenger.take();
        let surface = partial.surface.take();
        partial.device = None;
        partial.instance = None;

        let ctx = Context {
            _entry: entry,
            instance,
            messenger,
            debug,
            surface,
            physical: chosen.physical,
            device,
            info: chosen.info,
            graphics,
            compute,
            plan,
            frame_timeline,
            allocator: ManuallyDrop::new(Arc::new(Mutex::new(allocator))),
            garbage: Mutex::new(Vec::new()),
            pending_value: AtomicU64::new(1),
            signaled_value: AtomicU64::new(0),
            counters,
            objects_created: AtomicU64::new(0),
            objects_destroyed: AtomicU64::new(0),
            recording_failures: Mutex::new(Vec::new()),
            journal: Mutex::new(None),
            semaphore_names: Mutex::new(Default::default()),
            wait_timeout_s: if desc.validation && desc.validation_extras.gpu_assisted {
                GPU_ASSISTED_WAIT_TIMEOUT_S
            } else {
                WAIT_TIMEOUT_S
            },
        };
        ctx.name(
            ctx.device.handle(),
            &format!("vkocean device ({})", ctx.info.name),
        );
        // The surface stays unnamed: naming a VkSurfaceKHR through the device crashes
        // Mesa 22.3's lavapipe with the Vulkan 1.3.239 loader (segfault seen here).
        ctx.name(ctx.frame_timeline, "frame timeline (graphics)");
        ctx.name(ctx.graphics.raw, "graphics queue");
        if ctx.plan.separate_queues() {
            ctx.name(ctx.compute.raw, "compute queue");
        }
        Ok(Arc::new(ctx))
    }

    /// How a resource used on `users` is shared between the queue families ([`QueuePlan::sharing`]).
    pub fn sharing(&self, users: QueueUsers) -> Sharing {
        self.plan.sharing(users)
    }

    /// Names a Vulkan object (see [`DebugNames::name`]).
    pub(super) fn name<H: vk::Handle + Copy>(&self, handle: H, name: &str) {
        if H::TYPE == vk::ObjectType::SEMAPHORE {
            lock(&self.semaphore_names).insert(handle.as_raw(), name.to_string());
        }
        self.debug.name(handle, name);
    }

    /// The name a semaphore was created with.
    pub(super) fn semaphore_name(&self, semaphore: vk::Semaphore) -> Option<String> {
        lock(&self.semaphore_names)
            .get(&vk::Handle::as_raw(semaphore))
            .cloned()
    }

    /// Records the frame graph of what is recorded and submitted from now until
    /// [`Context::take_frame_graph`] (`--frame-graph`).
    pub fn capture_frame_graph(&self) {
        *lock(&self.journal) = Some(Journal::default());
    }

    /// The frame graph recorded since [`Context::capture_frame_graph`], ending the capture.
    pub fn take_frame_graph(&self) -> Option<FrameGraph> {
        lock(&self.journal).take().map(|j| j.graph)
    }

    fn journal(&self, f: impl FnOnce(&mut Journal)) {
        if let Some(j) = lock(&self.journal).as_mut() {
            f(j);
        }
    }

    /// The frame graph: a command buffer's first label names its submission.
    pub(super) fn journal_label(&self, name: &str) {
        self.journal(|j| j.label(name));
    }

    /// The frame graph: the uses that follow belong to pass `name`.
    pub(super) fn journal_pass(&self, name: &str) {
        self.journal(|j| j.pass(name));
    }

    /// The frame graph: a use of `resource` (an image in `layout`, a buffer without), its
    /// barrier, or what orders it instead.
    pub(super) fn journal_use(
        &self,
        resource: &str,
        (access, layout): (Access, Option<vk::ImageLayout>),
        writes: bool,
        barrier: Option<(Access, Access)>,
        ordered_by: Option<&str>,
    ) {
        self.journal(|j| {
            let record = Journal::use_record(resource, access, layout, barrier, ordered_by);
            j.record(record, writes)
        });
    }

    /// The frame graph: a submission to `queue` of the passes recorded since the last.
    pub(super) fn journal_submit(
        &self,
        queue: vk::Queue,
        waits: &[vk::SemaphoreSubmitInfo],
        signals: &[vk::SemaphoreSubmitInfo],
    ) {
        if lock(&self.journal).is_none() {
            return;
        }
        let names = lock(&self.semaphore_names).clone();
        let record = |s: &vk::SemaphoreSubmitInfo| SemaphoreRecord {
            semaphore: names
                .get(&vk::Handle::as_raw(s.semaphore))
                .cloned()
                .unwrap_or_else(|| format!("semaphore {:#x}", vk::Handle::as_raw(s.semaphore))),
            value: s.value,
            stages: s.stage_mask,
        };
        let queue = if queue == self.compute.raw && self.compute.raw != self.graphics.raw {
            ("compute", self.compute.family)
        } else if queue == self.graphics.raw && self.compute.raw == self.graphics.raw {
            ("graphics and compute", self.graphics.family)
        } else {
            ("graphics", self.graphics.family)
        };
        let waits = waits.iter().map(record).collect();
        let signals = signals.iter().map(record).collect();
        self.journal(|j| j.submit(queue, waits, signals));
    }

    /// Validation message counters (shared; still readable after the context is dropped).
    pub fn counters(&self) -> Arc<MessageCounters> {
        self.counters.clone()
    }

    /// The memory allocator.
    pub(super) fn allocator(&self) -> std::sync::MutexGuard<'_, Allocator> {
        self.allocator
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
    }

    /// The allocator, for a renderer of another crate that allocates through it (the overlay's).
    /// Its holder must be dropped before the context (it holds an `Arc<Context>` too).
    pub(super) fn shared_allocator(&self) -> Arc<Mutex<Allocator>> {
        Arc::clone(&self.allocator)
    }

    /// Hands an object to the deletion queue: it is destroyed once the GPU has finished every
    /// submission up to the one being recorded now.
    pub(super) fn defer(&self, garbage: Garbage) {
        let tag = self.pending_value.load(Ordering::Acquire);
        self.garbage
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .push((tag, garbage));
    }

    /// Highest frame-timeline value submitted so far.
    pub fn signaled_value(&self) -> u64 {
        self.signaled_value.load(Ordering::Acquire)
    }

    pub(super) fn set_signaled_value(&self, value: u64) {
        self.signaled_value.store(value, Ordering::Release);
    }

    /// Sets the timeline value the next graphics submission signals (called by `Frames`).
    pub(super) fn set_pending_value(&self, value: u64) {
        self.pending_value.store(value, Ordering::Release);
    }

    /// Current value of the frame timeline.
    pub fn completed_value(&self) -> GpuResult<u64> {
        // SAFETY: the semaphore is a live timeline semaphore of this device.
        unsafe { self.device.get_semaphore_counter_value(self.frame_timeline) }
            .vk("vkGetSemaphoreCounterValue")
    }

    /// Blocks until the timeline `semaphore` reaches `value`; a device that does not get there
    /// within `wait_timeout_s` is reported as hung.
    pub(super) fn wait_timeline(&self, semaphore: vk::Semaphore, value: u64) -> GpuResult<()> {
        let semaphores = [semaphore];
        let values = [value];
        let info = vk::SemaphoreWaitInfo::default()
            .semaphores(&semaphores)
            .values(&values);
        // SAFETY: the semaphore is a live timeline semaphore of this device.
        match unsafe {
            self.device
                .wait_semaphores(&info, self.wait_timeout_s * 1_000_000_000)
        } {
            Ok(()) => Ok(()),
            Err(vk::Result::TIMEOUT) => Err(GpuError::Timeout {
                seconds: self.wait_timeout_s,
            }),
            Err(result) => Err(GpuError::Vk {
                call: "vkWaitSemaphores",
                result,
            }),
        }
    }

    /// Keeps the first error of `cmd`'s recording (a pipeline made on first use that could not
    /// be made) for its submission, which returns it instead of submitting.
    pub(super) fn fail_recording(&self, cmd: vk::CommandBuffer, error: GpuError) {
        let mut failures = self
            .recording_failures
            .lock()
            .unwrap_or_else(|e| e.into_inner());
        if !failures.iter().any(|(c, _)| *c == cmd) {
            failures.push((cmd, error));
        }
    }

    /// `cmd`'s recording error, if it failed (`fail_recording`); taken, so it is returned once
    /// (and a recording begun again in `cmd` starts clean: `submit::begin_one_time`).
    pub(super) fn take_recording_failure(&self, cmd: vk::CommandBuffer) -> Option<GpuError> {
        let mut failures = self
            .recording_failures
            .lock()
            .unwrap_or_else(|e| e.into_inner());
        let i = failures.iter().position(|(c, _)| *c == cmd)?;
        Some(failures.swap_remove(i).1)
    }

    /// Counts `n` device objects just created (every `vkCreate*` of the GPU layer reports here).
    pub(super) fn count_created(&self, n: u64) {
        self.objects_created.fetch_add(n, Ordering::Relaxed);
    }

    /// Counts `n` device objects just destroyed (every `vkDestroy*` of the GPU layer).
    pub(super) fn count_destroyed(&self, n: u64) {
        self.objects_destroyed.fetch_add(n, Ordering::Relaxed);
    }

    /// Vulkan objects alive now that the GPU layer made: buffers, images and their views,
    /// samplers, pipelines and their layouts, shader modules, descriptor set layouts and pools,
    /// command pools, semaphores, fences, query pools and swapchains. The context's own objects
    /// (instance, device, surface, messenger, frame timeline) are not counted; objects waiting in
    /// the deferred-deletion queue are still alive. A steady frame loop keeps this constant.
    pub fn live_objects(&self) -> u64 {
        let created = self.objects_created.load(Ordering::Relaxed);
        created.saturating_sub(self.objects_destroyed.load(Ordering::Relaxed))
    }

    /// Destroys the garbage whose frames the GPU has finished.
    pub(super) fn collect_garbage(&self) -> GpuResult<()> {
        let done = self.completed_value()?;
        let ready: Vec<Garbage> = {
            let mut list = self.garbage.lock().unwrap_or_else(|p| p.into_inner());
            let (ready, keep): (Vec<_>, Vec<_>) = list.drain(..).partition(|(tag, _)| *tag <= done);
            *list = keep;
            ready.into_iter().map(|(_, g)| g).collect()
        };
        for g in ready {
            let n = g.destroy(&self.device, &mut self.allocator());
            self.count_destroyed(n);
        }
        Ok(())
    }

    /// Waits until the device is idle (resize, shutdown).
    pub fn wait_idle(&self) -> GpuResult<()> {
        // SAFETY: the device is live; no other thread submits.
        unsafe { self.device.device_wait_idle() }.vk("vkDeviceWaitIdle")
    }
}

fn create_device(
    instance: &ash::Instance,
    chosen: &Candidate,
    swapchain: bool,
) -> GpuResult<ash::Device> {
    // Graphics above a compute queue of its own (queues.rs, Khronos' async-compute sample).
    let requests = chosen.plan.queue_priorities();
    let queue_infos: Vec<_> = requests
        .iter()
        .map(|(family, priorities)| {
            vk::DeviceQueueCreateInfo::default()
                .queue_family_index(*family)
                .queue_priorities(priorities)
        })
        .collect();
    // Optional features are enabled wherever the device has them (the tessellated water, the
    // clip planes), so the stage masks that name them stay valid (`simulation::wait_stages`).
    let features = vk::PhysicalDeviceFeatures::default()
        .tessellation_shader(chosen.info.tessellation_shader)
        .shader_int64(chosen.info.shader_int64)
        .shader_clip_distance(chosen.info.rendering)
        .fill_mode_non_solid(chosen.info.fill_mode_non_solid)
        .sampler_anisotropy(chosen.info.sampler_anisotropy)
        .pipeline_statistics_query(chosen.info.pipeline_statistics_query)
        .occlusion_query_precise(chosen.info.occlusion_query_precise);
    let mut f12 = vk::PhysicalDeviceVulkan12Features::default().timeline_semaphore(true);
    let mut f13 = vk::PhysicalDeviceVulkan13Features::default()
        .synchronization2(true)
        .dynamic_rendering(chosen.info.rendering)
        .maintenance4(true);
    let extensions: Vec<*const c_char> = if swapchain {
        vec![ash::khr::swapchain::NAME.as_ptr()]
    } else {
        vec![]
    };
    let info = vk::DeviceCreateInfo::default()
        .queue_create_infos(&queue_infos)
        .enabled_features(&features)
        .enabled_extension_names(&extensions)
        .push_next(&mut f12)
        .push_next(&mut f13);
    // SAFETY: the features were checked as supported in `inspect`; pointers refer to locals.
    unsafe { instance.create_device(chosen.physical, &info, None) }.map_err(|result| match result {
        vk::Result::ERROR_FEATURE_NOT_PRESENT => GpuError::NoSuitableDevice(format!(
            "{}: a required feature is not present",
            chosen.info.name
        )),
        result => GpuError::Vk {
            call: "vkCreateDevice",
            result,
        },
    })
}

/// Instance-level objects created before the context exists; destroyed if creation fails.
struct Partial {
    instance: Option<ash::Instance>,
    messenger: Option<(ash::ext::debug_utils::Instance, vk::DebugUtilsMessengerEXT)>,
    surface: Option<(ash::khr::surface::Instance, vk::SurfaceKHR)>,
    device: Option<ash::Device>,
}

impl Drop for Partial {
    fn drop(&mut self) {
        // SAFETY: only objects still owned here (not moved into a Context) are destroyed, children first.
        unsafe {
            if let Some(device) = self.device.take() {
                device.destroy_device(None);
            }
            if let Some((fns, surface)) = self.surface.take() {
                fns.destroy_surface(surface, None);
            }
            if let Some((fns, messenger)) = self.messenger.take() {
                fns.destroy_debug_utils_messenger(messenger, None);
            }
            if let Some(instance) = self.instance.take() {
                instance.destroy_instance(None);
            }
        }
    }
}

impl Drop for Context {
    fn drop(&mut self) {
        if let Err(e) = self.wait_idle() {
            log::error!("at shutdown: {e}");
        }
        let garbage: Vec<_> = self
            .garbage
            .get_mut()
            .unwrap_or_else(|p| p.into_inner())
            .drain(..)
            .collect();
        for (_, g) in garbage {
            let n = g.destroy(&self.device, &mut self.allocator());
            self.count_destroyed(n);
        }
        // SAFETY: the device is idle and every object created from it has been destroyed (all
        // owners hold an Arc<Context>, so they are gone); destruction runs children first.
        unsafe {
            self.device.destroy_semaphore(self.frame_timeline, None);
            ManuallyDrop::drop(&mut self.allocator);
            self.device.destroy_device(None);
            if let Some((fns, surface)) = self.surface.take() {
                fns.destroy_surface(surface, None);
            }
            if let Some((fns, messenger)) = self.messenger.take() {
                fns.destroy_debug_utils_messenger(messenger, None);
            }
            self.instance.destroy_instance(None);
        }
    }
}

/// Locks `m`, through a poisoned lock (the data is a log; a panic elsewhere does not make it
/// wrong).
fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}
