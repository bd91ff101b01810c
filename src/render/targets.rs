//! Render targets the scene passes draw into: the main colour (display colour in the output's
//! 8-bit sRGB format) and depth at `--render-scale` of the output's size, and the reflection and
//! refraction textures (HDR colour + depth) at `--rtt-scale` of it (seed 001 §3.1: the
//! frame-buffer objects); with `--aa fxaa`, the anti-aliased colour the anti-aliasing pass
//! draws from the main colour. All are recreated on resize.

use std::sync::Arc;

use ash::vk;

use crate::gpu::{Context, GpuResult, Image, ImageDesc};

/// Reflection and refraction colour: linear radiance, which the water mixes before its tone
/// map (shaders/common/display.glsl). The reflection's and its sky's alphas carry where its
/// objects stand and how far (passes/reflection_distance.rs).
pub const HDR_FORMAT: vk::Format = vk::Format::R16G16B16A16_SFLOAT;
/// Scene depth (reversed-Z).
pub const DEPTH_FORMAT: vk::Format = vk::Format::D32_SFLOAT;
/// Layers of the reflection colour at most: layer 0 is drawn, layer l holds it blurred over 2^l
/// rows (`Recorder::halve_down_layers`), for the water to blur what it reflects up and down by
/// the slopes it does not resolve (shaders/common/reflection.glsl), up to 32 rows (layer 5).
pub const REFLECTION_LAYERS: u32 = 6;
/// Rows the last of those layers keeps at least (⌊H/2^l⌋ ≥ 5, but for the two layers the array
/// needs under 10 rows). A layer of fewer rows, each a large share of the sky the texture
/// spans, averages whatever it spans, so the far sea's mirrored sky followed the camera's pitch (at 640x360 `low`, H = 90, six layers to 2 rows:
/// the median mirrored elevation 21.4°, 20.5° and 29.3° looking level, 5° and 20° down, against
/// Cox & Munk's 25°; tests/reflection.rs). At 1280x720 (H = 180 at `low`, 360 at `high`) the
/// six layers keep 5 and 11 rows: this stops nothing there.
pub const REFLECTION_MIN_ROWS: u32 = 5;

/// A colour + depth pair.
pub struct ColourDepth {
    pub colour: Image,
    pub depth: Image,
}

impl ColourDepth {
    /// `colour_format`, `colour_usage` beside COLOR_ATTACHMENT and the colour's layers;
    /// `depth_usage` beside DEPTH_STENCIL_ATTACHMENT (SAMPLED where a pass reads the depth).
    fn new(
        ctx: &Arc<Context>,
        name: &str,
        extent: vk::Extent2D,
        (colour_format, colour_usage, layers): (vk::Format, vk::ImageUsageFlags, u32),
        depth_usage: vk::ImageUsageFlags,
    ) -> GpuResult<ColourDepth> {
        let image = |suffix: &str, format, usage, layers| {
            let name = format!("{name} {suffix}");
            plain_image(ctx, &name, extent, format, usage, layers)
        };
        let colour_usage = vk::ImageUsageFlags::COLOR_ATTACHMENT | colour_usage;
        let depth_usage = vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT | depth_usage;
        Ok(ColourDepth {
            colour: image("colour", colour_format, colour_usage, layers)?,
            depth: image("depth", DEPTH_FORMAT, depth_usage, 1)?,
        })
    }

    pub fn extent(&self) -> vk::Extent2D {
        self.colour.extent()
    }
}

/// A 2D image on the graphics queue (`layers` > 1: an array, viewed as one).
fn plain_image(
    ctx: &Arc<Context>,
    name: &str,
    extent: vk::Extent2D,
    format: vk::Format,
    usage: vk::ImageUsageFlags,
    layers: u32,
) -> GpuResult<Image> {
    Image::new(
        ctx,
        &ImageDesc {
            layers,
            ..ImageDesc::new(name, extent, format, usage)
        },
    )
}

pub struct Targets {
    /// The picture at `render_scale` of the output, in display colour, and its depth; copied
    /// or scaled into the output (passes/output.rs). Once the sky is drawn, the depth holds the
    /// anti-aliasing pass's edge mask.
    pub main: ColourDepth,
    /// What the water reflects (mirrored camera, clipped below the water); its colour has
    /// layers (up to REFLECTION_LAYERS, fewer under 160 rows: REFLECTION_MIN_ROWS), layer 0
    /// drawn, the others filled from it blurred up and down, for the water to blur what it
    /// reflects. Its alpha is the share of objects (the sky draws 0, the terrain and objects 1);
    /// its depth is sampled by the reflection distance pass (passes/reflection_distance.rs).
    pub reflection: ColourDepth,
    /// The sky the reflection's objects hide, layered and blurred as its colour (the
    /// reflection distance pass draws it): what the water puts in place of the objects that
    /// stand nearer than a sea point, blurred exactly as the colour it replaces. Its alpha:
    /// the share of objects times the log2 of their distance, which tells the water which
    /// of them stand nearer than a sea point, out of that point's reflection.
    pub reflection_sky: Image,
    /// What lies under the water (clipped above it); its depth gives the water's thickness.
    pub refraction: ColourDepth,
    /// `--aa fxaa`: the main colour anti-aliased (same size and format), copied or scaled into
    /// the output in its place.
    pub anti_aliased: Option<Image>,
    /// The output's size.
    output: vk::Extent2D,
}

/// `extent` scaled by `scale`, at least 1x1.
pub fn scaled(extent: vk::Extent2D, scale: f32) -> vk::Extent2D {
    let side = |v: u32| ((v as f32 * scale).round() as u32).max(1);
    vk::Extent2D {
        width: side(extent.width),
        height: side(extent.height),
    }
}

impl Targets {
    /// `output`: the output's size; `render_scale` and `rtt_scale` size the main and the
    /// reflection/refraction targets relative to it; `display_format`: the main colour's (an
    /// 8-bit sRGB format, the output's when the renderer was made); `anti_aliased`: make the
    /// anti-aliased colour (and let the anti-aliasing pass sample the main colour).
    pub fn new(
        ctx: &Arc<Context>,
        output: vk::Extent2D,
        display_format: vk::Format,
        (render_scale, rtt_scale): (f32, f32),
        anti_aliased: bool,
    ) -> GpuResult<Targets> {
        let rtt = scaled(output, rtt_scale);
        let main_extent = scaled(output, render_scale);
        let hdr = (HDR_FORMAT, vk::ImageUsageFlags::SAMPLED, 1);
        // The reflection's layers halve its height down to REFLECTION_LAYERS or while a layer
        // keeps REFLECTION_MIN_ROWS rows (at least 2 layers: the water samples an array).
        let layers =
            (32 - (rtt.height / REFLECTION_MIN_ROWS).leading_zeros()).clamp(2, REFLECTION_LAYERS);
        let blits = vk::ImageUsageFlags::TRANSFER_SRC | vk::ImageUsageFlags::TRANSFER_DST;
        let blurred = (HDR_FORMAT, vk::ImageUsageFlags::SAMPLED | blits, layers);
        // The output pass copies the main colour or (into an output without TRANSFER_DST)
        // samples it; or the anti-aliasing pass samples it.
        let main_usage = if anti_aliased {
            vk::ImageUsageFlags::SAMPLED
        } else {
            vk::ImageUsageFlags::TRANSFER_SRC | vk::ImageUsageFlags::SAMPLED
        };
        // The refraction depth is sampled by the water (the water's thickness), the
        // reflection's by the reflection distance pass; the main depth is an attachment only.
        let (only, sampled) = (vk::ImageUsageFlags::empty(), vk::ImageUsageFlags::SAMPLED);
        let anti_aliased = anti_aliased
            .then(|| {
                // Copied, or sampled, by the output pass.
                let usage = vk::ImageUsageFlags::COLOR_ATTACHMENT
                    | vk::ImageUsageFlags::TRANSFER_SRC
                    | vk::ImageUsageFlags::SAMPLED;
                let name = "anti-aliased colour";
                plain_image(ctx, name, main_extent, display_format, usage, 1)
            })
            .transpose()?;
        Ok(Targets {
            main: ColourDepth::new(
                ctx,
                "main",
                main_extent,
                (display_format, main_usage, 1),
                only,
            )?,
            reflection: ColourDepth::new(ctx, "reflection", rtt, blurred, sampled)?,
            reflection_sky: plain_image(
                ctx,
                "reflection sky",
                rtt,
                HDR_FORMAT,
                vk::ImageUsageFlags::COLOR_ATTACHMENT | vk::ImageUsageFlags::SAMPLED | blits,
                layers,
            )?,
            refraction: ColourDepth::new(ctx, "refraction", rtt, hdr, sampled)?,
            anti_aliased,
            output,
        })
    }

    /// The colour the output pass puts into the output: the anti-aliased colour, else the main.
    pub fn final_colour(&self) -> &Image {
        self.anti_aliased.as_ref().unwrap_or(&self.main.colour)
    }

    /// The output's size.
    pub fn output_extent(&self) -> vk::Extent2D {
        self.output
    }

    /// The main colour's format (the scene pipelines' for the main view).
    pub fn display_format(&self) -> vk::Format {
        self.main.colour.format()
    }
}
