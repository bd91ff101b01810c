//! Format features: every format vkocean creates an image (or texel-buffer view) in, and what it
//! does with it, checked against `vkGetPhysicalDeviceFormatProperties` before the object is made.
//! What the spec does not guarantee either has a fallback (linear filtering of RGBA32F: the
//! water shaders filter by hand; a linear blit: a nearest one; the register FFT kernel's RGBA32F
//! texel buffers: the shared-memory kernel) or fails with one line naming the format, the
//! feature and what needs it.

use ash::vk;

use super::context::Context;
use super::error::{GpuError, GpuResult};

/// Environment variable for tests: hide linear filtering of R32G32B32A32_SFLOAT (as on devices
/// that lack it), so the hand-filtered path runs on lavapipe too.
pub const NO_FLOAT32_FILTER_ENV: &str = "VKOCEAN_TEST_NO_FLOAT32_FILTER";

/// One use of a format: the features it needs and what for (the error text).
#[derive(Clone, Copy, Debug)]
pub struct FormatUse {
    pub format: vk::Format,
    pub features: vk::FormatFeatureFlags,
    /// What uses it, e.g. "the ocean simulation images".
    pub what: &'static str,
}

/// Checks `uses` against `features_of` (optimal-tiling features per format): the first
/// missing feature is an error naming the format, the features and the use.
pub fn check(
    device: &str,
    uses: &[FormatUse],
    features_of: impl Fn(vk::Format) -> vk::FormatFeatureFlags,
) -> Result<(), String> {
    for u in uses {
        let missing = u.features & !features_of(u.format);
        if !missing.is_empty() {
            return Err(format!(
                "{device} does not support {missing:?} for {:?}, which {} need",
                u.format, u.what
            ));
        }
    }
    Ok(())
}

impl Context {
    /// Optimal-tiling features of `format` on this device (with the test override above).
    pub fn format_features(&self, format: vk::Format) -> vk::FormatFeatureFlags {
        // SAFETY: the physical device belongs to the instance.
        let props = unsafe {
            self.instance
                .get_physical_device_format_properties(self.physical, format)
        };
        let mut features = props.optimal_tiling_features;
        if format == vk::Format::R32G32B32A32_SFLOAT
            && std::env::var_os(NO_FLOAT32_FILTER_ENV).is_some()
        {
            features &= !vk::FormatFeatureFlags::SAMPLED_IMAGE_FILTER_LINEAR;
        }
        features
    }

    /// Buffer (texel-buffer view) features of `format` on this device.
    pub fn buffer_format_features(&self, format: vk::Format) -> vk::FormatFeatureFlags {
        // SAFETY: as above.
        unsafe {
            self.instance
                .get_physical_device_format_properties(self.physical, format)
        }
        .buffer_features
    }

    /// Whether sampling `format` with a linear filter (or a linear blit from it) is supported.
    pub fn filters_linearly(&self, format: vk::Format) -> bool {
        self.format_features(format)
            .contains(vk::FormatFeatureFlags::SAMPLED_IMAGE_FILTER_LINEAR)
    }

    /// [`check`] on this device: `Err(GpuError::Unsupported)` with one line.
    pub fn require_formats(&self, uses: &[FormatUse]) -> GpuResult<()> {
        check(&self.info.name, uses, |f| self.format_features(f)).map_err(GpuError::Unsupported)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_features_name_the_format_and_the_use() {
        let uses = [
            FormatUse {
                format: vk::Format::D32_SFLOAT,
                features: vk::FormatFeatureFlags::DEPTH_STENCIL_ATTACHMENT
                    | vk::FormatFeatureFlags::SAMPLED_IMAGE,
                what: "the depth buffers",
            },
            FormatUse {
                format: vk::Format::R16G16B16A16_SFLOAT,
                features: vk::FormatFeatureFlags::COLOR_ATTACHMENT,
                what: "the HDR targets",
            },
        ];
        let all = |_| vk::FormatFeatureFlags::from_raw(u32::MAX);
        assert_eq!(check("gpu", &uses, all), Ok(()));
        // A device whose D32 can be sampled but not rendered to (the spec requires one of
        // X8_D24 and D32 as a depth attachment, not both).
        let no_d32_attachment = |f| {
            if f == vk::Format::D32_SFLOAT {
                vk::FormatFeatureFlags::SAMPLED_IMAGE
            } else {
                vk::FormatFeatureFlags::from_raw(u32::MAX)
            }
        };
        let err = check("gpu", &uses, no_d32_attachment).unwrap_err();
        assert!(err.contains("D32_SFLOAT"), "{err}");
        assert!(err.contains("DEPTH_STENCIL_ATTACHMENT"), "{err}");
        assert!(err.contains("the depth buffers"), "{err}");
        assert!(!err.contains('\n'));
    }
}
