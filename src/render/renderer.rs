//! `Renderer`: what the frame draws with. The render targets, the frame uniforms of each slot,
//! the sky cube, the DU/DV map, samplers and the passes' pipelines; made for one output size
//! (`resize` remakes the targets). The frame itself, pass by pass, is `frame::record_frame`.
//! The main view's shaders write display colour (tone-mapped; the sRGB format encodes), the
//! reflection and refraction passes linear radiance.

use std::sync::Arc;

use ash::vk;

use super::atmosphere::Sky;
use super::camera::Camera;
use super::passes::caustic_means::CausticKey;
use super::passes::output::OutputPass;
use super::passes::water::{TileView, WaterKind, WaterSamplers};
use super::passes::{
    shafts_pass, AntiAliasingPass, CausticMeansPass, ReflectionDistancePass, ShaftsPass, SkyCube,
    SkyPass, SprayPass, TerrainPass, TexturesViewPass, WaterPass,
};
use super::scene::{dudv_size, generate_dudv, load_dudv, DUDV_SIDE};
use super::targets::Targets;
use super::targets::{DEPTH_FORMAT, HDR_FORMAT};
use super::uniforms::{
    sky_uniforms, FrameInputs, FrameParams, FrameUniforms, OceanBindings, SkyLight, ViewIndex,
};
use super::{Geometry, SceneSettings, ViewMode};
use crate::gpu::oneshot::upload_image_with;
use crate::gpu::{
    check_bindings, Bind, Bindings, BoundSet, Buffer, Context, DescriptorSetLayout, FormatUse,
    GpuResult, Image, ImageDesc, MemoryLocation, Order, Output, Sampler, FRAMES_IN_FLIGHT,
};
use crate::ocean::foam::FoamScene;
use crate::ocean::simulation::IMAGE_FORMAT;
use crate::pass_names as names;
use crate::shared::MAX_BODIES;

/// One floating body as shaders/terrain/bodies.vert reads it (`ocean::bodies::Body::instance`).
pub type BodyInstance = [[f32; 4]; 3];

/// The image a frame ends in: written by a copy or blit (it needs TRANSFER_DST usage), then
/// drawn over by the overlay when it is shown. Its state (`gpu::track`) is where the frontend handed it over: a swapchain image
/// after the acquire wait, the headless target after the previous frame.
pub struct OutputTarget<'a> {
    /// The image (the overlay pass renders into it: it needs COLOR_ATTACHMENT usage too).
    pub image: Output<'a>,
    pub extent: vk::Extent2D,
    /// An 8-bit sRGB format (or UNORM, with the shaders encoding).
    pub format: vk::Format,
    /// It has TRANSFER_DST usage: the output pass copies or blits into it; else it draws into
    /// it as a colour attachment (a swapchain whose surface does not offer TRANSFER_DST).
    pub transfer_dst: bool,
}

impl<'a> OutputTarget<'a> {
    /// Its width over its height (the camera's aspect).
    pub fn aspect(&self) -> f32 {
        self.extent.width as f32 / self.extent.height.max(1) as f32
    }

    /// `transfer_dst`: the image has TRANSFER_DST usage.
    pub fn new(image: Output<'a>, transfer_dst: bool) -> OutputTarget<'a> {
        OutputTarget {
            image,
            extent: image.extent(),
            format: image.format(),
            transfer_dst,
        }
    }
}

/// Checks every format the renderer creates images in for what it does with them (one line
/// naming the format and the use when the device lacks a feature; `gpu::formats`).
fn check_formats(
    ctx: &Context,
    display: vk::Format,
    scaled: bool,
    anti_aliased: bool,
) -> GpuResult<()> {
    use vk::FormatFeatureFlags as F;
    // Sampled: by the output pass where it draws (passes/output.rs).
    let mut display_features = F::COLOR_ATTACHMENT | F::TRANSFER_SRC | F::SAMPLED_IMAGE;
    if scaled {
        // Blitted up to the output (linearly where it filters; `output::record`).
        display_features |= F::BLIT_SRC;
    }
    if anti_aliased {
        // FXAA reads its edges' ends and blends with bilinear samples (shaders/post/fxaa.frag).
        display_features |= F::SAMPLED_IMAGE | F::SAMPLED_IMAGE_FILTER_LINEAR;
    }
    ctx.require_formats(&[
        FormatUse {
            format: HDR_FORMAT,
            // Blits: the blurred layers of the reflection and of the sky its objects hide.
            features: F::COLOR_ATTACHMENT
                | F::SAMPLED_IMAGE
                | F::SAMPLED_IMAGE_FILTER_LINEAR
                | F::BLIT_SRC
                | F::BLIT_DST,
            what: "the reflection, refraction and sky textures",
        },
        FormatUse {
            format: DEPTH_FORMAT,
            // Sampling D32 is required by Vulkan; rendering to it is required of D32 or X8_D24.
            features: F::DEPTH_STENCIL_ATTACHMENT | F::SAMPLED_IMAGE,
            what:
                "the depth buffers (the refraction's sampled by the water, the reflection's by a pass)",
        },
        FormatUse {
            format: display,
            features: display_features,
            what: "the main view's target (and the anti-aliased one)",
        },
        FormatUse {
            format: vk::Format::R8G8B8A8_UNORM,
            features: F::SAMPLED_IMAGE | F::SAMPLED_IMAGE_FILTER_LINEAR | F::TRANSFER_DST,
            what: "the DU/DV map",
        },
    ])
}

/// Radiance of the sun's disc above the atmosphere, in the scene's units. (The real disc's
/// radiance, the irradiance over its 6.8·10⁻⁵ sr, would be 3·10⁵; anything past the tone map's
/// white point looks the same, and a disc this bright keeps its anti-aliased edge.)
pub const SUN_SCALE: f32 = 40.0;

/// What the frame draws with: targets, frame uniforms, samplers, textures and passes. The
/// settings are fixed at construction (`new` checks them against the device); the camera moves.
pub struct Renderer {
    ctx: Arc<Context>,
    /// The main view's camera (the other two views are derived from it each frame).
    camera: Camera,
    /// How the scene looks (`--view`, `--fresnel`, scales, sun, ...), checked in `new`.
    pub(super) settings: SceneSettings,
    /// Main, reflection and refraction colour + depth targets (recreated on resize).
    pub(super) targets: Targets,

    // Frame uniforms: one buffer and set per frame slot.
    /// Layout of the frame-uniform sets; kept alive with them.
    _frame_set_layout: DescriptorSetLayout,
    /// Per frame slot: uniform buffer and the set that binds it (with the ocean images and
    /// the sky cube, which the set keeps alive).
    frame_uniforms: Vec<(Buffer, BoundSet)>,
    /// Per frame slot: the floating bodies (`--bodies`; binding 6 of the frame set,
    /// shaders/terrain/bodies.vert), and the ones the next frame draws.
    body_uniforms: Vec<Buffer>,
    bodies: Vec<BodyInstance>,
    /// The simulation images the frame sets bind, and the cascade layout.
    ocean: OceanBindings,

    // Textures the passes sample.
    /// The sky cubemap (analytic, re-rendered when the sun moves, or `--skybox`).
    pub(super) sky_cube: SkyCube,
    /// The sun's and the sky's light for the frame uniforms, and the sky they are for
    /// (`uniforms::sky_uniforms`, recomputed when it changes; a changed `--skybox` builds a new
    /// renderer, `needs_rebuild`).
    sky_light: (Sky, SkyLight),
    /// The DU/DV distortion map (generated, or `--dudv`).
    dudv: Image,
    /// Linear, clamped: reflection and refraction colour.
    clamp_sampler: Sampler,
    /// Nearest, clamped: the refraction and reflection depths.
    depth_sampler: Sampler,
    /// Linear, repeating: the DU/DV map.
    repeat_sampler: Sampler,

    // The passes, in frame order (`frame.rs`).
    /// The sky: into the cube, and behind everything in each view.
    pub(super) sky: SkyPass,
    /// The island and the objects, in each view.
    pub(super) terrain: TerrainPass,
    /// The sky the reflection's objects hide, with how far they stand (from its depth) as its
    /// alpha, for the water to put that sky in place of what stands nearer than a sea point.
    pub(super) reflection_distance: ReflectionDistancePass,
    /// The light shafts' means, drawn before the scene when the camera is under the water.
    pub(super) shafts: ShaftsPass,
    /// The caustics' measured means, drawn when what they depend on changes.
    pub(super) caustic_means: CausticMeansPass,
    /// The ocean (tessellated or clipmap) and its textures set.
    pub(super) water: WaterPass,
    /// The spray's puffs over the main view (`--spray on`, FFT waves).
    pub(super) spray: Option<SprayPass>,
    /// `--view reflection|refraction|dudv`.
    pub(super) textures_view: TexturesViewPass,
    /// `--aa fxaa` with the final view (`SceneSettings::anti_aliased`).
    pub(super) anti_aliasing: Option<AntiAliasingPass>,
    /// How the output pass scales the main target: linear where its format filters linearly
    /// (optional in Vulkan), else nearest.
    pub(super) scale_filter: vk::Filter,
    /// Copies, blits or draws the picture into the output.
    pub(super) output: OutputPass,
}

impl Renderer {
    /// `output_format`: format of the images the frontend renders to (8-bit sRGB); the main
    /// target takes it, so a frame at `--render-scale 1` ends in a plain copy.
    // Long: every object the renderer holds, created in dependency order (targets, layouts,
    // uniforms, samplers, sky, DU/DV, passes); each is a few lines.
    pub fn new(
        ctx: &Arc<Context>,
        output_format: vk::Format,
        extent: vk::Extent2D,
        ocean: OceanBindings,
        settings: &SceneSettings,
        camera: Camera,
    ) -> anyhow::Result<Renderer> {
        let anti_aliased = settings.anti_aliased();
        check_formats(
            ctx,
            output_format,
            settings.render_scale < 1.0,
            anti_aliased,
        )?;
        let targets = Targets::new(
            ctx,
            extent,
            output_format,
            (settings.render_scale, settings.rtt_scale),
            anti_aliased,
        )?;
        let graphics = vk::ShaderStageFlags::ALL_GRAPHICS;
        let sampled = vk::DescriptorType::COMBINED_IMAGE_SAMPLER;
        let frame_set_layout = DescriptorSetLayout::new(
            ctx,
            "frame set layout (uniforms, ocean images, sky cube, foam, shafts, bodies, wake, means)",
            &[
                (0, vk::DescriptorType::UNIFORM_BUFFER, graphics),
                (1, sampled, graphics),
                (2, sampled, graphics),
                (3, sampled, graphics),
                (4, sampled, graphics),
                (5, sampled, graphics),
                (6, vk::DescriptorType::UNIFORM_BUFFER, graphics),
                (7, sampled, graphics),
                (8, sampled, graphics),
            ],
        )?;
        let repeat = vk::SamplerAddressMode::REPEAT;
        let clamp = vk::SamplerAddressMode::CLAMP_TO_EDGE;
        // RGBA32F need not filter linearly (it does on desktop GPUs and lavapipe): without it,
        // the ocean images are sampled at texel centres and the water shaders interpolate.
        let ocean_linear = ctx.filters_linearly(IMAGE_FORMAT);
        let ocean_sampler = if ocean_linear {
            Sampler::linear(ctx, "ocean sampler (repeat)", repeat)?
        } else {
            log::info!(
                "{:?} has no linear filtering: the water filters the ocean images by hand",
                IMAGE_FORMAT
            );
            Sampler::new(
                ctx,
                "ocean sampler (nearest, repeat)",
                vk::Filter::NEAREST,
                repeat,
            )?
        };
        let water_kind = WaterKind {
            geometry: Geometry::resolve(settings.geometry),
            cascades: ocean.cascades,
            manual_filter: !ocean_linear,
            shadows: settings.shadows,
            refraction_caustics: settings.refraction_caustics,
            // 1×1 without a boat (`Simulation::wake`).
            wake: ocean.wake.iter().any(|image| image.extent().width > 1),
            slope_mips: ocean.normals.iter().all(|image| image.levels() > 1),
        };
        let sky_sampler = Sampler::linear(ctx, "sky cube sampler", clamp)?;
        let foam_sampler = Sampler::linear(ctx, "foam sampler (clamp)", clamp)?;
        // The wake is RGBA32F too (the height queries read it exactly): nearest where the
        // device does not filter it linearly, and `wake_at` (common/water.glsl) then filters
        // it by hand like the ocean images.
        let wake_sampler = if ocean_linear {
            Sampler::linear(ctx, "wake sampler (clamp)", clamp)?
        } else {
            Sampler::new(
                ctx,
                "wake sampler (nearest, clamp)",
                vk::Filter::NEAREST,
                clamp,
            )?
        };
        let shafts = shafts_pass(ctx, &frame_set_layout, water_kind)?;
        let caustic_means = CausticMeansPass::new(ctx, &frame_set_layout, water_kind)?;
        let means_sampler = Sampler::linear(ctx, "shafts and caustic means sampler", clamp)?;
        let sky_cube = match &settings.skybox {
            Some(dir) => SkyCube::load(ctx, dir)?,
            None => SkyCube::analytic(ctx)?,
        };
        let mut frame_uniforms = Vec::new();
        let mut body_uniforms = Vec::new();
        for slot in 0..FRAMES_IN_FLIGHT {
            let bodies = Buffer::new(
                ctx,
                &format!("floating bodies slot {slot}"),
                (MAX_BODIES as usize * std::mem::size_of::<BodyInstance>()) as u64,
                vk::BufferUsageFlags::UNIFORM_BUFFER,
                MemoryLocation::CpuToGpu,
            )?;
            let buffer = Buffer::new(
                ctx,
                &format!("frame uniforms slot {slot}"),
                std::mem::size_of::<FrameUniforms>() as u64,
                vk::BufferUsageFlags::UNIFORM_BUFFER,
                MemoryLocation::CpuToGpu,
            )?;
            // The ocean images are written on the compute queue and read through the
            // compute timeline's wait (graphics 2's submission must carry it: `Frames::submit`
            // checks); the sky cube, the light shafts and the caustics' means are tracked on
            // this queue (their readers wait for their last rendering where they sample them).
            let wait = Order::Wait {
                by: "compute timeline",
                stages: ocean.wait_stages,
            };
            let tracked = Order::Tracked;
            let set = BoundSet::new(
                ctx,
                &frame_set_layout,
                &format!("frame uniforms set slot {slot}"),
                &[
                    (0, Bind::Uniform(&buffer)),
                    (
                        1,
                        Bind::Sampled(&ocean.displacement[slot], &ocean_sampler, wait),
                    ),
                    (2, Bind::Sampled(&ocean.normals[slot], &ocean_sampler, wait)),
                    (3, Bind::Sampled(&sky_cube.image, &sky_sampler, tracked)),
                    (4, Bind::Sampled(&ocean.foam[slot], &foam_sampler, wait)),
                    (5, Bind::Sampled(&shafts.image, &means_sampler, tracked)),
                    (6, Bind::Uniform(&bodies)),
                    (7, Bind::Sampled(&ocean.wake[slot], &wake_sampler, wait)),
                    (
                        8,
                        Bind::Sampled(&caustic_means.fill.image, &means_sampler, tracked),
                    ),
                ],
            )?;
            frame_uniforms.push((buffer, set));
            body_uniforms.push(bodies);
        }

        let (w, h) = match &settings.dudv {
            Some(path) => dudv_size(path, ctx.info.limits.max_image_dimension2_d)?,
            None => (DUDV_SIDE, DUDV_SIDE),
        };
        let dudv = Image::new(
            ctx,
            &ImageDesc::new(
                "dudv map",
                vk::Extent2D {
                    width: w,
                    height: h,
                },
                vk::Format::R8G8B8A8_UNORM,
                vk::ImageUsageFlags::SAMPLED | vk::ImageUsageFlags::TRANSFER_DST,
            ),
        )?;
        let len = w as usize * h as usize * 4;
        upload_image_with(ctx, &dudv, len, |out| -> anyhow::Result<()> {
            match &settings.dudv {
                Some(path) => load_dudv(path, (w, h), out)?,
                None => out.copy_from_slice(&generate_dudv(DUDV_SIDE)),
            }
            Ok(())
        })?;

        let clamp_sampler = Sampler::linear(ctx, "render target sampler (clamp)", clamp)?;
        let depth_sampler = Sampler::new(
            ctx,
            "depth sampler (nearest, clamp)",
            vk::Filter::NEAREST,
            clamp,
        )?;
        let repeat_sampler = Sampler::linear(ctx, "dudv sampler (repeat)", repeat)?;
        let samplers = WaterSamplers {
            clamp: &clamp_sampler,
            depth: &depth_sampler,
            repeat: &repeat_sampler,
        };
        let sky = SkyPass::new(ctx, &frame_set_layout, targets.display_format())?;
        let terrain = TerrainPass::new(
            ctx,
            &frame_set_layout,
            settings.terrain_grid,
            targets.display_format(),
            water_kind,
        )?;
        let reflection_distance = ReflectionDistancePass::new(
            ctx,
            &frame_set_layout,
            &targets.reflection.depth,
            &depth_sampler,
        )?;
        let water = WaterPass::new(
            ctx,
            &frame_set_layout,
            &targets,
            &dudv,
            &samplers,
            water_kind,
        )?;
        let spray = ocean
            .spray
            .as_ref()
            .map(|buffers| {
                let order = Order::Wait {
                    by: "compute timeline",
                    stages: ocean.wait_stages,
                };
                SprayPass::new(
                    ctx,
                    &frame_set_layout,
                    targets.display_format(),
                    buffers,
                    order,
                )
            })
            .transpose()?;
        let textures_view = TexturesViewPass::new(
            ctx,
            &frame_set_layout,
            water.textures(),
            targets.display_format(),
        )?;
        let anti_aliasing = anti_aliased
            .then(|| {
                AntiAliasingPass::new(
                    ctx,
                    &targets.main.colour,
                    &clamp_sampler,
                    settings.fxaa_fast,
                )
            })
            .transpose()?;
        if settings.view == ViewMode::Wireframe && !water.has_wireframe() {
            anyhow::bail!(
                "--view wireframe: {} cannot draw lines (no fillModeNonSolid)",
                ctx.info.name
            );
        }
        let renderer = Renderer {
            ctx: ctx.clone(),
            camera,
            settings: settings.clone(),
            targets,
            _frame_set_layout: frame_set_layout,
            frame_uniforms,
            body_uniforms,
            bodies: Vec::new(),
            ocean,
            sky_cube,
            sky_light: (
                settings.sky(),
                sky_uniforms(&settings.sky(), settings.skybox.is_none()),
            ),
            dudv,
            clamp_sampler,
            depth_sampler,
            repeat_sampler,
            sky,
            terrain,
            reflection_distance,
            shafts,
            caustic_means,
            water,
            spray,
            textures_view,
            anti_aliasing,
            scale_filter: if ctx.filters_linearly(output_format) {
                vk::Filter::LINEAR
            } else {
                vk::Filter::NEAREST
            },
            output: OutputPass::new(ctx),
        };
        renderer.check_bindings()?;
        Ok(renderer)
    }

    /// Checks every pass's pipelines against the sets it draws with (`gpu::check_bindings`):
    /// each descriptor its shaders use is bound, and the ocean images are read only in stages
    /// the compute timeline's wait covers. One line naming the pass, binding and stage.
    fn check_bindings(&self) -> GpuResult<()> {
        let frame = [&self.frame_uniforms[0].1];
        let water = self.water.sets(frame[0], 0);
        for view in [ViewIndex::Main, ViewIndex::Reflection] {
            check_bindings(names::SKY, &[self.sky.draw(&frame, view)])?;
        }
        for view in [
            ViewIndex::Main,
            ViewIndex::Reflection,
            ViewIndex::Refraction,
        ] {
            for underwater in [false, true] {
                check_bindings(names::SCENE, &self.terrain.draws(&frame, view, underwater))?;
            }
        }
        check_bindings(names::SHAFTS, &[self.shafts.draw(&frame)])?;
        let means = &self.caustic_means.fill;
        check_bindings(names::CAUSTIC_MEANS, &[means.draw(&frame)])?;
        let sets = self.reflection_distance.sets(frame[0]);
        check_bindings(names::REFLECTION, &[self.reflection_distance.draw(&sets)])?;
        let draws: Vec<Bindings> = self
            .water
            .pipelines()
            .map(|pipeline| Bindings {
                pipeline,
                sets: &water,
            })
            .collect();
        check_bindings(names::WATER, &draws)?;
        if let Some(spray) = &self.spray {
            let sets = spray.sets(frame[0], 0);
            check_bindings(names::SPRAY, &[spray.draw(&sets)])?;
        }
        let textures = [frame[0], &self.water.textures().set];
        check_bindings(names::TEXTURES_VIEW, &[self.textures_view.draw(&textures)])?;
        if let Some(pass) = &self.anti_aliasing {
            let set = pass.set_ref();
            check_bindings(names::ANTI_ALIASING, &pass.draws(&set))?;
        }
        Ok(())
    }

    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    /// The camera, to move (the fly camera, tests).
    pub fn camera_mut(&mut self) -> &mut Camera {
        &mut self.camera
    }

    /// Whether `new` settings need a new renderer (`remade`): other target scales, terrain
    /// lattice, anti-aliasing pass, textures or water geometry; the rest are uniforms and the
    /// clipmap's per-frame tiles (`set_scene`).
    pub fn needs_rebuild(&self, new: &SceneSettings) -> bool {
        let s = &self.settings;
        Geometry::resolve(new.geometry) != self.water.geometry()
            || s.render_scale != new.render_scale
            || s.rtt_scale != new.rtt_scale
            || s.terrain_grid != new.terrain_grid
            || s.anti_aliased() != new.anti_aliased()
            || s.fxaa_fast != new.fxaa_fast
            || s.dudv != new.dudv
            || s.skybox != new.skybox
            || (new.view == ViewMode::Wireframe && s.view != ViewMode::Wireframe)
            // Specialization constants of the water's and the terrain's pipelines.
            || s.shadows != new.shadows
            || s.refraction_caustics != new.refraction_caustics
    }

    /// Takes settings that change only uniforms (`needs_rebuild` is false): the next frame
    /// draws with them (the sky cube follows a moved sun).
    pub fn set_scene(&mut self, new: &SceneSettings) {
        debug_assert!(!self.needs_rebuild(new));
        self.settings = new.clone();
    }

    /// A renderer like this one (device, output, camera) for other ocean images or settings.
    /// This one is dropped by the caller; the deferred-deletion queue keeps its objects until
    /// the frames in flight are done with them.
    pub fn remade(&self, ocean: OceanBindings, settings: &SceneSettings) -> anyhow::Result<Self> {
        Renderer::new(
            &self.ctx,
            self.targets.display_format(),
            self.extent(),
            ocean,
            settings,
            self.camera,
        )
    }

    /// Size of the output the renderer was made for.
    pub fn extent(&self) -> vk::Extent2D {
        self.targets.output_extent()
    }

    /// Recreates the size-dependent targets for a new output size (in the main target's
    /// format: a swapchain recreated with another byte order is reached by a blit). Waits for
    /// the device to go idle first (resizes are rare).
    pub fn resize(&mut self, extent: vk::Extent2D) -> GpuResult<()> {
        if extent == self.targets.output_extent() {
            return Ok(());
        }
        self.ctx.wait_idle()?;
        let s = &self.settings;
        let format = self.targets.display_format();
        let scales = (s.render_scale, s.rtt_scale);
        self.targets = Targets::new(&self.ctx, extent, format, scales, s.anti_aliased())?;
        let samplers = WaterSamplers {
            clamp: &self.clamp_sampler,
            depth: &self.depth_sampler,
            repeat: &self.repeat_sampler,
        };
        self.water.resize(&self.targets, &self.dudv, &samplers)?;
        let depth = &self.targets.reflection.depth;
        self.reflection_distance
            .resize(depth, &self.depth_sampler)?;
        if let Some(pass) = &mut self.anti_aliasing {
            pass.resize(&self.targets.main.colour, &self.clamp_sampler)?;
        }
        self.output.resize();
        Ok(())
    }

    /// Writes slot `slot`'s frame uniforms for this frame (`frame_set(slot)` binds them), and
    /// returns what the foam simulation needs of them (the scene it meets).
    pub(super) fn write_uniforms(
        &mut self,
        slot: usize,
        output: &OutputTarget,
        inputs: &FrameInputs,
    ) -> FoamScene {
        // The main target's size (--render-scale of the output's).
        let extent = self.targets.main.extent();
        let s = &self.settings;
        let sky = s.sky();
        if self.sky_light.0 != sky {
            self.sky_light = (sky, sky_uniforms(&sky, s.skybox.is_none()));
        }
        let uniforms = FrameUniforms::new(
            &self.camera,
            &FrameParams {
                sky,
                sky_light: self.sky_light.1,
                sun_scale: SUN_SCALE,
                analytic_sky: s.skybox.is_none(),
                shadows: s.shadows,
                caustics: s.caustics,
                time_s: inputs.time_s,
                size: (extent.width, extent.height),
                aspect: output.aspect(),
                ocean: &self.ocean,
                inputs,
                view_mode: s.view,
                fresnel: s.fresnel,
                tess_edge_px: s.tess_edge_px,
                scene: &s.layout,
                background: s.background,
                slicks: s.slicks,
                gusts: s.gusts,
            },
        );
        self.frame_uniforms[slot]
            .0
            .write(bytemuck::bytes_of(&uniforms));
        self.caustic_means.want(CausticKey::of(&uniforms));
        if !self.bodies.is_empty() {
            self.body_uniforms[slot].write(bytemuck::cast_slice(&self.bodies));
        }
        let aspect = output.aspect();
        self.water.prepare(
            slot,
            &TileView {
                camera: &self.camera,
                aspect,
                focal_px: self.camera.focal_px(aspect, extent.height as f32),
                cell_px: s.tess_edge_px,
                reach_m: self.ocean.max_displacement_m,
            },
        );
        FoamScene {
            terrain: uniforms.terrain,
            shore: uniforms.shore,
            open_sea: uniforms.open_sea,
            objects: uniforms.objects,
        }
    }

    /// The floating bodies the next frames draw (`Body::instance`; at most `MAX_BODIES`, the
    /// CLI's bound), sorted by shape: one draw per shape, of its own vertex count.
    pub fn set_bodies(&mut self, mut bodies: Vec<BodyInstance>) {
        assert!(
            bodies.len() <= MAX_BODIES as usize,
            "--bodies is at most {MAX_BODIES}"
        );
        bodies.sort_by(|a, b| a[0][3].total_cmp(&b[0][3]));
        self.bodies = bodies;
    }

    /// How many floating bodies of each shape (box, boat, buoy) the frame draws.
    pub fn bodies(&self) -> [u32; 3] {
        let mut counts = [0; 3];
        for b in &self.bodies {
            counts[(b[0][3] as usize).min(2)] += 1;
        }
        counts
    }

    /// Slot `slot`'s frame descriptor set (uniforms, ocean images, sky cube).
    pub(super) fn frame_set(&self, slot: usize) -> &BoundSet {
        &self.frame_uniforms[slot].1
    }
}
