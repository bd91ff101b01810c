//! The sky: `SkyCube` renders the analytic sky (shaders/common/sky.glsl) into a cubemap when the
//! sun changes, or holds the six faces loaded with `--skybox`; `SkyPass` draws the cubemap
//! behind everything in a view (shaders/sky/sky.frag).

use std::path::Path;
use std::sync::Arc;

use ash::vk;

use super::{bind_scene, scene_layout, scene_pipeline, Depth, PerTarget, SceneTarget};
use crate::gpu::oneshot::{upload_image, upload_image_with};
use crate::gpu::{
    Bind, Bindings, BoundSet, Context, DescriptorSetLayout, GpuResult, GraphicsDesc, Image,
    ImageDesc, Load, Order, Pipeline, PipelineLayout, Recorder, Sampler, Target,
};
use crate::input::{decode_png_rgba8, png_size, regular_file, InputError};
use crate::pass_names as names;
use crate::render::atmosphere::{Sky, SUN_IRRADIANCE};
use crate::render::multiple_scattering;
use crate::render::targets::HDR_FORMAT;
use crate::render::uniforms::ViewIndex;
use crate::shaders;

/// Side of each face of the rendered sky cubemap (px).
pub const CUBE_SIDE: u32 = 256;
/// The side of `--skybox DIR`'s faces, from their PNG headers: each face must exist as a file
/// and be square, all of one size, at most `max_side` (the device's largest cube; the command
/// line checks against the largest any device has).
pub fn skybox_side(dir: &Path, max_side: u32) -> Result<u32, InputError> {
    let shown = dir.display();
    if !dir.is_dir() {
        let what = if dir.exists() {
            "not a directory"
        } else {
            "no such directory"
        };
        return Err(InputError(format!(
            "--skybox {shown}: {what} (it takes a directory of six faces: {}.png)",
            SKYBOX_FACES.join(".png ")
        )));
    }
    let mut side = None;
    for face in SKYBOX_FACES {
        let path = dir.join(format!("{face}.png"));
        if !path.exists() {
            return Err(InputError(format!(
                "--skybox {shown}: missing face {}",
                path.display()
            )));
        }
        regular_file("--skybox", &path)?;
        let (w, h) = png_size("--skybox", &path)?;
        if w != h || side.is_some_and(|s| s != w) {
            return Err(InputError(format!(
                "--skybox {}: is {w}x{h}; the six faces must be square and the same size",
                path.display()
            )));
        }
        if w > max_side {
            return Err(InputError(format!(
                "--skybox {}: {w}x{h} is larger than this device's largest cube face ({max_side}x{max_side})",
                path.display()
            )));
        }
        side = Some(w);
    }
    Ok(side.unwrap_or(1))
}

/// Face file names of `--skybox DIR`, in Vulkan's layer order.
pub const SKYBOX_FACES: [&str; 6] = ["px", "nx", "py", "ny", "pz", "nz"];

pub struct SkyPass {
    /// Into HDR (the reflection texture) and into the main target.
    pipelines: PerTarget<Pipeline>,
}

impl SkyPass {
    /// `display_format`: the main target's.
    pub fn new(
        ctx: &Arc<Context>,
        frame_layout: &DescriptorSetLayout,
        display_format: vk::Format,
    ) -> GpuResult<SkyPass> {
        let layout = scene_layout(ctx, "sky layout", frame_layout, &[])?;
        let pipelines = PerTarget::new(display_format, |target| {
            scene_pipeline(
                ctx,
                &layout,
                GraphicsDesc {
                    name: &format!("sky ({})", target.label()),
                    stages: &[
                        (
                            vk::ShaderStageFlags::VERTEX,
                            shaders::COMMON_FULLSCREEN_VERT,
                        ),
                        (vk::ShaderStageFlags::FRAGMENT, shaders::SKY_SKY_FRAG),
                    ],
                    // sky.frag's SKY_UNDERWATER: only the main view can see from under the
                    // water (the reflection's sky paid 1.6 ms a frame at --quality low on
                    // lavapipe for the untaken branch).
                    constants: &[u32::from(matches!(target, SceneTarget::Display(_)))],
                    ..Default::default()
                },
                Depth::Background,
                target,
            )
        })?;
        Ok(SkyPass { pipelines })
    }

    /// What `record` binds for `view`: its pipeline with `sets` (the frame set).
    pub fn draw<'a>(&'a self, sets: &'a [&'a BoundSet], view: ViewIndex) -> Bindings<'a> {
        Bindings {
            pipeline: self.pipelines.for_view(view),
            sets,
        }
    }

    /// Draws the sky where nothing else was drawn (last, inside a scene rendering scope that
    /// declared `draw(sets, view)`).
    pub fn record(&self, rec: &Recorder, sets: &[&BoundSet], view: ViewIndex) {
        bind_scene(rec, &self.draw(sets, view), view);
        rec.draw(3, 1);
    }
}

/// Push constants of shaders/sky/sky_cube.frag.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct FacePush {
    sun_dir: [f32; 4],
    /// x: cloud cover (0–1); y: the sun's irradiance above the atmosphere; zw: unused.
    sky: [f32; 4],
    /// rgb: the sun's irradiance at the sea (`Sky::sun_light`); w: unused.
    sunlight: [f32; 4],
    /// rgb: the clear sky's radiance at the zenith (`Sky::zenith_radiance`); w: unused.
    zenith: [f32; 4],
    face: u32,
}

/// The sky cubemap and how it is filled.
pub struct SkyCube {
    pub image: Image,
    /// Renders the analytic sky; `None` for a loaded skybox.
    render: Option<Render>,
    /// The sky (sun and clouds) the cube was last rendered for.
    rendered_for: Option<Sky>,
}

impl SkyCube {
    /// A cube the analytic sky is rendered into (`update`).
    pub fn analytic(ctx: &Arc<Context>) -> GpuResult<SkyCube> {
        let image = cube_image(ctx, "sky cube", CUBE_SIDE, HDR_FORMAT, RENDERED)?;
        let (set_layout, set) = multiple_scattering_table(ctx)?;
        let layout = PipelineLayout::new(
            ctx,
            "sky cube layout",
            &[&set_layout],
            Some((
                vk::ShaderStageFlags::FRAGMENT,
                std::mem::size_of::<FacePush>() as u32,
            )),
        )?;
        let pipeline = Pipeline::graphics(
            ctx,
            &layout,
            &GraphicsDesc {
                name: "sky cube",
                stages: &[
                    (
                        vk::ShaderStageFlags::VERTEX,
                        shaders::COMMON_FULLSCREEN_VERT,
                    ),
                    (vk::ShaderStageFlags::FRAGMENT, shaders::SKY_SKY_CUBE_FRAG),
                ],
                colour_formats: &[HDR_FORMAT],
                ..Default::default()
            },
        )?;
        Ok(SkyCube {
            image,
            render: Some(Render {
                pipeline,
                set,
                _layouts: (layout, set_layout),
            }),
            rendered_for: None,
        })
    }

    /// A cube loaded from `DIR/{px,nx,py,ny,pz,nz}.png` (square, equal sizes, sRGB colour):
    /// every face's header is checked (and the side against the device's largest cube) before
    /// the faces are decoded, one after the other, into the upload buffer.
    pub fn load(ctx: &Arc<Context>, dir: &Path) -> anyhow::Result<SkyCube> {
        let side = skybox_side(dir, ctx.info.limits.max_image_dimension_cube)?;
        let image = cube_image(ctx, "skybox", side, vk::Format::R8G8B8A8_SRGB, UPLOADED)?;
        let face_len = side as usize * side as usize * 4;
        upload_image_with(ctx, &image, face_len * 6, |out| -> anyhow::Result<()> {
            for (face, out) in SKYBOX_FACES.iter().zip(out.chunks_exact_mut(face_len)) {
                let path = dir.join(format!("{face}.png"));
                decode_png_rgba8("--skybox", &path, (side, side), out)?;
            }
            Ok(())
        })?;
        Ok(SkyCube {
            image,
            render: None,
            rendered_for: None,
        })
    }

    /// Whether `update` has to render the cube for this sky (never for a loaded skybox).
    pub fn is_stale(&self, sky: &Sky) -> bool {
        self.render.is_some() && self.rendered_for != Some(*sky)
    }

    /// Renders the analytic sky into the six faces for this sun and cloud cover. Outside any
    /// rendering scope. Earlier frames sampling the cube are ordered before it by the barrier
    /// (same queue); the passes that sample it next wait for it at the stages their shaders
    /// read it in (`Recorder::rendering`).
    pub fn update(&mut self, rec: &Recorder, sky: &Sky) {
        let Some(Render { pipeline, set, .. }) = &self.render else {
            return;
        };
        // What every texel's sky shares, once (common/sky.glsl `sky_radiance`).
        let [sr, sg, sb] = sky.sun_light();
        let [zr, zg, zb] = sky.zenith_radiance();
        // Each face a rendering scope of its own (the first one's barrier covers the whole
        // cube: every face is written anew).
        let draw = Bindings {
            pipeline,
            sets: &[set],
        };
        // Bound once for the six scopes (a binding outlives a rendering scope; each scope
        // declares it): Best Practices' Pipeline-SortAndBind counted each face's rebinding.
        rec.bind(&draw);
        for face in 0..self.image.layers() {
            // Face 0's barrier discards the whole cube; the later faces keep what the earlier
            // ones wrote (a layout change from UNDEFINED would discard them).
            let load = if face == 0 {
                Load::DontCare
            } else {
                Load::Keep
            };
            let target = [Target::layer(&self.image, face, load)];
            let scope = rec.rendering(names::SKY_CUBE, &target, None, &[draw]);
            scope.record(|| {
                rec.push_constants(
                    pipeline,
                    &FacePush {
                        sun_dir: sky.sun_dir.normalize().extend(0.0).to_array(),
                        sky: [sky.cloud_cover, SUN_IRRADIANCE, 0.0, 0.0],
                        sunlight: [sr, sg, sb, 0.0],
                        zenith: [zr, zg, zb, 0.0],
                        face,
                    },
                );
                rec.draw(3, 1);
            });
        }
        self.rendered_for = Some(*sky);
    }
}

/// What renders the analytic sky into the cube: its pipeline and the multiple scattering's
/// table it samples.
struct Render {
    pipeline: Pipeline,
    set: BoundSet,
    /// Kept alive with the pipeline and the set made from them.
    _layouts: (PipelineLayout, DescriptorSetLayout),
}

/// The multiple scattering's table (src/render/multiple_scattering.rs), uploaded once, in a
/// set for shaders/sky/sky_cube.frag (binding 0, filtered linearly, clamped at its edges).
fn multiple_scattering_table(ctx: &Arc<Context>) -> GpuResult<(DescriptorSetLayout, BoundSet)> {
    let side = multiple_scattering::SIDE as u32;
    let table = Image::new(
        ctx,
        &ImageDesc::new(
            "sky multiple scattering",
            vk::Extent2D {
                width: side,
                height: side,
            },
            vk::Format::R16G16B16A16_SFLOAT,
            vk::ImageUsageFlags::SAMPLED | vk::ImageUsageFlags::TRANSFER_DST,
        ),
    )?;
    upload_image(ctx, &table, &multiple_scattering::lut_rgba16f())?;
    let sampler = Sampler::linear(
        ctx,
        "sky multiple scattering sampler",
        vk::SamplerAddressMode::CLAMP_TO_EDGE,
    )?;
    let layout = DescriptorSetLayout::new(
        ctx,
        "sky cube set layout",
        &[(
            0,
            vk::DescriptorType::COMBINED_IMAGE_SAMPLER,
            vk::ShaderStageFlags::FRAGMENT,
        )],
    )?;
    let set = BoundSet::new(
        ctx,
        &layout,
        "sky cube set",
        &[(0, Bind::Sampled(&table, &sampler, Order::Tracked))],
    )?;
    Ok((layout, set))
}

/// How a cube's faces are filled: rendered (the analytic sky) or uploaded (`--skybox`).
const RENDERED: vk::ImageUsageFlags = vk::ImageUsageFlags::COLOR_ATTACHMENT;
const UPLOADED: vk::ImageUsageFlags = vk::ImageUsageFlags::TRANSFER_DST;

/// A sampled cube image whose faces are filled through `filled_by` (`RENDERED`, `UPLOADED`).
fn cube_image(
    ctx: &Arc<Context>,
    name: &str,
    side: u32,
    format: vk::Format,
    filled_by: vk::ImageUsageFlags,
) -> GpuResult<Image> {
    Image::new(
        ctx,
        &ImageDesc {
            layers: 6,
            cube: true,
            ..ImageDesc::new(
                name,
                vk::Extent2D {
                    width: side,
                    height: side,
                },
                format,
                vk::ImageUsageFlags::SAMPLED | filled_by,
            )
        },
    )
}
