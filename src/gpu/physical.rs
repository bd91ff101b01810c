//! Physical devices: what each offers, whether vkocean can run on it (Vulkan 1.3 and the required
//! features, a graphics queue that can present), the ranking discrete > integrated > virtual > cpu,
//! and the `--list-gpus` listing.

use std::sync::Arc;

use ash::vk;

use super::debug::MessageCounters;
use super::error::{GpuResult, VkResultExt};
use super::instance::{create_instance, load_entry};
use super::queues::QueuePlan;

/// What a run uses of the device; the device check asks for these and nothing more.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Needs {
    /// It draws (dynamic rendering, clip distances for the reflection and refraction); `false`
    /// for compute-only commands (`bench fft`).
    pub rendering: bool,
    /// It draws the tessellated water (`--geometry tessellated` named on the command line).
    pub tessellation: bool,
}

impl Needs {
    /// Everything but tessellation: a run that draws with the default water geometry (clipmap).
    pub const RENDERING: Needs = Needs {
        rendering: true,
        tessellation: false,
    };
    /// Compute only.
    pub const COMPUTE: Needs = Needs {
        rendering: false,
        tessellation: false,
    };
}

/// Facts about the chosen device that the rest of the program reports or respects.
#[derive(Clone, Debug)]
pub struct DeviceInfo {
    pub name: String,
    /// Driver name and version, e.g. "llvmpipe: Mesa 22.3.6 (LLVM 15.0.6)".
    pub driver: String,
    pub device_type: vk::PhysicalDeviceType,
    pub api_version: u32,
    pub limits: vk::PhysicalDeviceLimits,
    /// Valid bits of timestamps on the graphics queue family (0: no timestamps).
    pub timestamp_valid_bits: u32,
    /// The same for the compute queue's family.
    pub compute_timestamp_valid_bits: u32,
    /// Tessellation shaders (the tessellated water; enabled where the device has them).
    pub tessellation_shader: bool,
    /// Dynamic rendering and clip distances: everything vkocean draws needs them.
    pub rendering: bool,
    pub fill_mode_non_solid: bool,
    pub sampler_anisotropy: bool,
    /// Pipeline-statistics queries (the water draw's counters in `--profile`).
    pub pipeline_statistics_query: bool,
    /// Occlusion queries that count samples (the water's covered pixels in `--profile`).
    pub occlusion_query_precise: bool,
    /// 64-bit integers in shaders (the CPU FFT kernel's 32-byte stores).
    pub shader_int64: bool,
    /// Invocations per subgroup (SIMD width on CPU drivers).
    pub subgroup_size: u32,
    /// Compute shaders can use subgroup shuffles (GL_KHR_shader_subgroup_shuffle).
    pub compute_subgroup_shuffle: bool,
}

/// One line of `--list-gpus`.
#[derive(Clone, Debug)]
pub struct DeviceSummary {
    pub index: usize,
    pub name: String,
    pub device_type: vk::PhysicalDeviceType,
    pub api_version: u32,
    pub driver: String,
    /// `None` when usable for a run that draws (`Needs::RENDERING`), else why not.
    pub unusable: Option<String>,
    /// Tessellation shaders: the tessellated water geometry runs here.
    pub tessellation: bool,
}

impl std::fmt::Display for DeviceSummary {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}: {} ({}, Vulkan {}.{}.{}, {})",
            self.index,
            self.name,
            type_name(self.device_type),
            vk::api_version_major(self.api_version),
            vk::api_version_minor(self.api_version),
            vk::api_version_patch(self.api_version),
            self.driver
        )?;
        match &self.unusable {
            None if self.tessellation => write!(f, " [water: tessellated, clipmap]"),
            None => write!(f, " [water: clipmap (no tessellationShader)]"),
            Some(why) => write!(f, " [unusable: {why}]"),
        }
    }
}

pub(super) fn type_name(t: vk::PhysicalDeviceType) -> &'static str {
    match t {
        vk::PhysicalDeviceType::DISCRETE_GPU => "discrete",
        vk::PhysicalDeviceType::INTEGRATED_GPU => "integrated",
        vk::PhysicalDeviceType::VIRTUAL_GPU => "virtual",
        vk::PhysicalDeviceType::CPU => "cpu",
        _ => "other",
    }
}

/// discrete > integrated > virtual > cpu > other.
pub(super) fn type_rank(t: vk::PhysicalDeviceType) -> u32 {
    match t {
        vk::PhysicalDeviceType::DISCRETE_GPU => 4,
        vk::PhysicalDeviceType::INTEGRATED_GPU => 3,
        vk::PhysicalDeviceType::VIRTUAL_GPU => 2,
        vk::PhysicalDeviceType::CPU => 1,
        _ => 0,
    }
}

/// The device vkocean picks when `--gpu` is not given: the first usable one (`Some(type)`) of
/// the highest rank. One rule for `Context::new` and the `--quality` default.
pub(super) fn best_usable(types: &[Option<vk::PhysicalDeviceType>]) -> Option<usize> {
    let mut best: Option<(usize, u32)> = None;
    for (i, t) in types.iter().enumerate() {
        if let Some(t) = t {
            if best.is_none_or(|(_, rank)| type_rank(*t) > rank) {
                best = Some((i, type_rank(*t)));
            }
        }
    }
    best.map(|(i, _)| i)
}

/// Why `info` cannot serve a run with `needs`, if it cannot: the features it lacks.
pub(super) fn lacks(info: &DeviceInfo, needs: Needs) -> Option<String> {
    let mut missing = Vec::new();
    if needs.rendering && !info.rendering {
        missing.push("dynamicRendering or shaderClipDistance");
    }
    if needs.tessellation && !info.tessellation_shader {
        missing.push("tessellationShader (--geometry tessellated; --geometry clipmap needs none)");
    }
    (!missing.is_empty()).then(|| format!("missing Vulkan feature {}", missing.join(", ")))
}

/// Whether the device a run would use (`--gpu N`, or the best usable one) is a CPU
/// implementation such as lavapipe; `None` when it cannot be told (no loader, no usable device,
/// a bad index): the run's own device creation then reports why. Judges the devices by `needs`,
/// as the run's device choice does; ignores presentation support, which only a window's
/// surface can answer.
pub fn chosen_device_is_cpu(gpu_index: Option<usize>, needs: Needs) -> Option<bool> {
    let devices = list_devices().ok()?;
    let types: Vec<_> = devices
        .iter()
        .map(|d| {
            let usable = d.unusable.is_none() && (d.tessellation || !needs.tessellation);
            usable.then_some(d.device_type)
        })
        .collect();
    let index = match gpu_index {
        Some(i) => i,
        None => best_usable(&types)?,
    };
    let device_type = (*types.get(index)?)?;
    Some(device_type == vk::PhysicalDeviceType::CPU)
}

/// What one physical device offers, as far as vkocean cares.
pub(crate) struct Candidate {
    pub(crate) physical: vk::PhysicalDevice,
    pub(crate) info: DeviceInfo,
    /// Which queues draw, present and compute.
    pub(crate) plan: QueuePlan,
}

/// "name: info" of the device's driver (e.g. "llvmpipe: Mesa 22.3.6 (LLVM 15.0.6)"); a driver
/// that gives no info string is named with its version and Vulkan conformance instead
/// ("SwiftShader driver 5.0.0, conformance 1.3.3.1"; the version decoded as Vulkan packs API
/// versions, which is SwiftShader's packing; vendors that pack their own way give an info
/// string).
pub(super) fn driver_string(instance: &ash::Instance, physical: vk::PhysicalDevice) -> String {
    let mut driver = vk::PhysicalDeviceDriverProperties::default();
    let mut props2 = vk::PhysicalDeviceProperties2::default().push_next(&mut driver);
    // SAFETY: `physical` belongs to `instance`; the chain points to locals.
    unsafe { instance.get_physical_device_properties2(physical, &mut props2) };
    let version = props2.properties.driver_version;
    let name = driver
        .driver_name_as_c_str()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let detail = driver
        .driver_info_as_c_str()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let c = driver.conformance_version;
    match (name.is_empty(), detail.is_empty()) {
        (false, false) => format!("{name}: {detail}"),
        (false, true) => format!(
            "{name} {}.{}.{}, conformance {}.{}.{}.{}",
            vk::api_version_major(version),
            vk::api_version_minor(version),
            vk::api_version_patch(version),
            c.major,
            c.minor,
            c.subminor,
            c.patch
        ),
        _ => "unknown driver".to_string(),
    }
}

/// Inspects a device; `Err(reason)` when vkocean cannot run on it.
// Long: every property, feature and queue vkocean needs of a device, read and judged in
// one place so `--list-gpus` and device choice cannot disagree.
pub(super) fn inspect(
    instance: &ash::Instance,
    physical: vk::PhysicalDevice,
    surface: Option<&(ash::khr::surface::Instance, vk::SurfaceKHR)>,
) -> (DeviceSummaryParts, Result<Candidate, String>) {
    // SAFETY: `physical` was enumerated from `instance`.
    let props = unsafe { instance.get_physical_device_properties(physical) };
    let name = props
        .device_name_as_c_str()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let driver = driver_string(instance, physical);
    let mut subgroup = vk::PhysicalDeviceSubgroupProperties::default();
    let mut props2 = vk::PhysicalDeviceProperties2::default().push_next(&mut subgroup);
    // SAFETY: `physical` belongs to `instance`; the chain points to a local.
    unsafe { instance.get_physical_device_properties2(physical, &mut props2) };
    let compute_subgroup_shuffle = subgroup
        .supported_stages
        .contains(vk::ShaderStageFlags::COMPUTE)
        && subgroup
            .supported_operations
            .contains(vk::SubgroupFeatureFlags::SHUFFLE);
    let subgroup_size = subgroup.subgroup_size;
    let parts = DeviceSummaryParts {
        name: name.clone(),
        device_type: props.device_type,
        api_version: props.api_version,
        driver: driver.clone(),
    };
    if props.api_version < vk::API_VERSION_1_3 {
        return (parts, Err("needs Vulkan 1.3".to_string()));
    }

    let mut f12 = vk::PhysicalDeviceVulkan12Features::default();
    let mut f13 = vk::PhysicalDeviceVulkan13Features::default();
    let mut f2 = vk::PhysicalDeviceFeatures2::default()
        .push_next(&mut f12)
        .push_next(&mut f13);
    // SAFETY: as above; the chain points to locals.
    unsafe { instance.get_physical_device_features2(physical, &mut f2) };
    let f = f2.features;
    // What every run needs (the simulation's timelines and barriers); what drawing needs is
    // judged per run (`lacks`).
    let required = [
        ("timelineSemaphore", f12.timeline_semaphore),
        ("synchronization2", f13.synchronization2),
        ("maintenance4", f13.maintenance4),
    ];
    let missing: Vec<&str> = required
        .iter()
        .filter(|(_, v)| *v == vk::FALSE)
        .map(|(n, _)| *n)
        .collect();
    if !missing.is_empty() {
        return (
            parts,
            Err(format!("missing Vulkan feature {}", missing.join(", "))),
        );
    }

    // SAFETY: as above.
    let families = unsafe { instance.get_physical_device_queue_family_properties(physical) };
    let presents = |i: u32| match surface {
        None => true,
        // SAFETY: the surface belongs to this instance; `i` is a valid family index.
        Some((fns, surface)) => {
            unsafe { fns.get_physical_device_surface_support(physical, i, *surface) }
                .unwrap_or(false)
        }
    };
    let plan = match QueuePlan::choose(&families, presents) {
        Ok(plan) => plan,
        Err(why) if surface.is_none() => {
            return (
                parts,
                Err(why.replace(" (that can present to the window)", "")),
            )
        }
        Err(why) => return (parts, Err(why.to_string())),
    };
    let (graphics_family, compute_family) = (plan.graphics.family, plan.compute.family);

    let info = DeviceInfo {
        name,
        driver,
        device_type: props.device_type,
        api_version: props.api_version,
        limits: props.limits,
        timestamp_valid_bits: families[graphics_family as usize].timestamp_valid_bits,
        compute_timestamp_valid_bits: families[compute_family as usize].timestamp_valid_bits,
        tessellation_shader: f.tessellation_shader == vk::TRUE,
        rendering: f13.dynamic_rendering == vk::TRUE && f.shader_clip_distance == vk::TRUE,
        fill_mode_non_solid: f.fill_mode_non_solid == vk::TRUE,
        sampler_anisotropy: f.sampler_anisotropy == vk::TRUE,
        pipeline_statistics_query: f.pipeline_statistics_query == vk::TRUE,
        occlusion_query_precise: f.occlusion_query_precise == vk::TRUE,
        shader_int64: f.shader_int64 == vk::TRUE,
        subgroup_size,
        compute_subgroup_shuffle,
    };
    (
        parts,
        Ok(Candidate {
            physical,
            info,
            plan,
        }),
    )
}

pub(crate) struct DeviceSummaryParts {
    pub(crate) name: String,
    pub(crate) device_type: vk::PhysicalDeviceType,
    pub(crate) api_version: u32,
    pub(crate) driver: String,
}

/// Lists every Vulkan device for `--list-gpus`, marking the ones vkocean cannot use.
pub fn list_devices() -> GpuResult<Vec<DeviceSummary>> {
    let entry = load_entry()?;
    let counters = Arc::new(MessageCounters::new(false));
    let (instance, _) = create_instance(&entry, false, Default::default(), None, &counters)?;
    // SAFETY: the instance is live; it is destroyed below, after its last use.
    let physicals = unsafe { instance.enumerate_physical_devices() };
    let list = physicals.map(|physicals| {
        physicals
            .into_iter()
            .enumerate()
            .map(|(index, p)| {
                let (parts, usable) = inspect(&instance, p, None);
                let tessellation = usable.as_ref().is_ok_and(|c| c.info.tessellation_shader);
                let unusable = match usable {
                    Ok(c) => lacks(&c.info, Needs::RENDERING),
                    Err(why) => Some(why),
                };
                DeviceSummary {
                    index,
                    name: parts.name,
                    device_type: parts.device_type,
                    api_version: parts.api_version,
                    driver: parts.driver,
                    unusable,
                    tessellation,
                }
            })
            .collect()
    });
    // SAFETY: no object created from this instance is alive.
    unsafe { instance.destroy_instance(None) };
    list.vk("vkEnumeratePhysicalDevices")
}

#[cfg(test)]
mod tests {
    use super::*;
    use vk::PhysicalDeviceType as T;

    #[test]
    fn the_best_usable_device_is_the_first_of_the_highest_rank() {
        assert_eq!(best_usable(&[]), None);
        assert_eq!(best_usable(&[None, None]), None);
        assert_eq!(best_usable(&[Some(T::CPU)]), Some(0));
        // lavapipe listed before a GPU: the GPU wins.
        assert_eq!(
            best_usable(&[Some(T::CPU), Some(T::INTEGRATED_GPU)]),
            Some(1)
        );
        // An unusable discrete GPU does not count; two integrated ones: the first.
        assert_eq!(
            best_usable(&[
                None,
                Some(T::INTEGRATED_GPU),
                Some(T::INTEGRATED_GPU),
                Some(T::CPU)
            ]),
            Some(1)
        );
        assert_eq!(
            best_usable(&[Some(T::VIRTUAL_GPU), Some(T::DISCRETE_GPU), Some(T::OTHER)]),
            Some(1)
        );
    }
}
