//! [`record_frame`]: one frame, top to bottom, as the README's diagram ("The frame") draws it.
//!
//! ```text
//!  graphics 1  waits for nothing, signals nothing
//!    uniforms    slot f % 2: three views (camera, mirrored camera, refraction), sun, ocean
//!    sky cube    the analytic sky into the cubemap's 6 faces        (only when the sun moved)
//!    reflection  island + objects + sky, mirrored camera, clipped below the water
//!                                                        writes reflection colour + depth
//!                then the colour's layers 1.., each the one before halved in height
//!  compute     waits for the graphics timeline at f − 1 (frame f − 2 last sampled slot f % 2),
//!              signals the compute timeline with the frame's value
//!    evolve, fft, assemble (or the Gerstner kernel)      writes the slot's simulation images
//!    foam, spray (FFT; foam at medium and high)          writes the slot's foam, particles
//!  graphics 2  waits for the compute timeline at the frame's value (vertex, tessellation
//!              evaluation and fragment stages), signals the frame timeline (and the
//!              swapchain's `ready` semaphore); a window's image waits for `acquired`
//!    caustic means  the first frame with caustics, and when the sun, the waves or the focal
//!                length have changed and held for two frames: the caustics' mean over the
//!                floor   writes the means image
//!    light shafts  from under the water or at the waterline (caustics on): the caustics'
//!                means along the camera's rays at 256x144   writes the light shafts image
//!    refraction  island + objects below the water, with the caustics (they sample the
//!                simulation's normal images; at low only with --caustics on)
//!                                                 writes refraction colour + depth
//!    scene       island + objects (main camera; caustics from under the water)
//!                                                        writes main colour + depth
//!    water       tessellated patches; samples reflection, refraction (colour and depth each) and,
//!                through the compute wait, the simulation images   writes main colour + depth
//!    sky         where nothing else was drawn                        writes main colour
//!    spray       --spray on, final view: the spray's puffs, an indirect draw of what the
//!                compute queue counted (blended; depth tested)      writes main colour
//!    textures    --view reflection|refraction|dudv: that texture     writes main colour
//!    anti-aliasing  --aa fxaa, final view: FXAA; samples main colour
//!                writes anti-aliased colour (and its edge mask into main depth)
//!    output      main (or anti-aliased) colour copied (same size) or drawn (scaled) into
//!                the output image
//!    readback    screenshots: the output into a host buffer; present: to PRESENT_SRC
//! ```
//!
//! Every pass names the images it renders to and samples; `gpu::track` records the barriers
//! between them. With a compute queue of its own the simulation runs while graphics 1 draws
//! (README, "Across queues").

use ash::vk;
use egui::epaint::ClippedPrimitive;

use super::passes::TexturesViewPass;
use super::renderer::{OutputTarget, Renderer};
use super::targets::ColourDepth;
use super::uniforms::{ViewIndex, WaterSide};
use super::{FrameInputs, Upscale, ViewMode};
use crate::gpu::egui::EguiPainter;
use crate::gpu::selftest::SyncHazard;
use crate::gpu::{
    AcquiredImage, Bindings, Buffer, Context, Frames, GpuResult, Load, Profilers, Recorder,
    Rendering, Submission, Target, Use, GRAPHICS_OCEAN, GRAPHICS_SCENE,
};
use crate::ocean::simulation::Simulation;
use crate::pass_names as names;

/// The linear refraction texture where nothing lies under the water: the deep water colour.
const DEEP_WATER: [f32; 4] = {
    let [r, g, b] = crate::shared::WATER_COLOUR;
    [r, g, b, 1.0]
};

/// Reversed-Z: depth 0 is the far plane.
const CLEAR_DEPTH: Load = Load::Clear(vk::ClearValue {
    depth_stencil: vk::ClearDepthStencilValue {
        depth: 0.0,
        stencil: 0,
    },
});

/// The stages at which graphics 2 waits for a swapchain image's acquire: the output pass's
/// first write to it, a copy (transfer) or, when it scales or where the image takes no copies,
/// a draw (colour attachment output). The image's state starts `available_after` these stages, so the
/// first write's barrier chains with the wait.
pub const ACQUIRE_WAIT_STAGE: vk::PipelineStageFlags2 = vk::PipelineStageFlags2::from_raw(
    vk::PipelineStageFlags2::ALL_TRANSFER.as_raw()
        | vk::PipelineStageFlags2::COLOR_ATTACHMENT_OUTPUT.as_raw(),
);

/// Where the frame's output goes after the output pass.
#[derive(Default)]
pub struct Delivery<'a> {
    /// Copy the output into this host-visible buffer (screenshots).
    pub readback: Option<&'a Buffer>,
    /// A swapchain image: present it after the frame.
    /// (Graphics 2 waits for its acquire before the output's first write, at
    /// `ACQUIRE_WAIT_STAGE`, and signals what the presentation waits for.)
    pub present: Option<&'a AcquiredImage>,
}

/// The overlay's part of a frame: egui's triangles, drawn last into the output image.
pub struct OverlayDraw<'a> {
    pub painter: &'a mut EguiPainter,
    pub primitives: &'a [ClippedPrimitive],
    pub pixels_per_point: f32,
}

/// What one frame records into: the frame loop, the renderer, the simulation and the
/// profilers of the two queues.
pub struct FrameParts<'a> {
    pub ctx: &'a Context,
    pub frames: &'a mut Frames,
    pub renderer: &'a mut Renderer,
    pub simulation: &'a mut Simulation,
    pub profilers: &'a mut Profilers,
    /// The overlay, when it is shown.
    pub overlay: Option<OverlayDraw<'a>>,
}

/// Records and submits frame `frames.next`: the three submissions of the diagram above.
/// `hazard` (tests only) is recorded first. Returns the frame's timeline value.
// Long: the frame top to bottom, as the README's diagram draws it: split, a reader would
// have to jump between functions to follow one frame (issue 15).
pub fn record_frame(
    parts: FrameParts,
    output: &OutputTarget,
    inputs: &FrameInputs,
    delivery: &Delivery,
    hazard: Option<SyncHazard>,
) -> GpuResult<u64> {
    let FrameParts {
        ctx,
        frames,
        renderer: r,
        simulation,
        profilers,
        overlay,
    } = parts;
    let Profilers {
        graphics: profiler,
        compute: compute_profiler,
    } = profilers;
    debug_assert_eq!(output.extent, r.extent());
    let mut frame = frames.begin()?;
    let value = frame.signal_value();
    let camera = r.camera();
    let (eye, forward) = (camera.position, camera.forward);
    simulation.place_window([eye.x as f64, eye.z as f64]);
    simulation.wake.place(
        [eye.x as f64, eye.z as f64],
        [forward.x as f64, forward.z as f64],
    );
    let inputs = &FrameInputs {
        ocean_origin_m: simulation.origin_m(),
        ocean_window: simulation.is_window(),
        foam_levels: simulation.foam_levels,
        wake: simulation.wake.place_of(),
        ..*inputs
    };

    // ── graphics 1: the passes that read no simulation output (the reflection's terrain
    // shader has no caustics) ──────────────────────────────────────────────────────────────
    let foam_scene;
    {
        let rec = frame.recorder(ctx, Submission::Scene);
        rec.begin_label(&format!("frame {} (graphics 1)", frame.index));
        profiler.begin_frame(&rec, &frame)?;
        profiler.set_submission(GRAPHICS_SCENE);
        if let Some(hazard) = hazard {
            hazard.record(&rec);
            // Dropped now; the deletion queue keeps it alive until this frame is done.
        }
        foam_scene = r.write_uniforms(frame.slot, output, inputs);
        let sky = r.settings.sky();
        if r.sky_cube.is_stale(&sky) {
            let cube = &mut r.sky_cube;
            profiler.pass(&rec, names::SKY_CUBE, || cube.update(&rec, &sky));
        }
        let r = &*r;
        let set = [r.frame_set(frame.slot)];
        let t = &r.targets;
        // Each pass: its rendering scope's barriers (from what its draws' shaders read), then
        // its timestamps around the drawing.
        let (view, reflection) = (ViewIndex::Reflection, &t.reflection);
        let [island, objects, bodies] = r.terrain.draws(&set, view, false);
        let draws = [island, objects, bodies, r.sky.draw(&set, view)];
        let scope = drawn_anew(&rec, names::REFLECTION, reflection, Load::DontCare, &draws);
        profiler.pass(&rec, names::REFLECTION, || {
            // The sky, last, writes every pixel the terrain left.
            scope.record(|| {
                r.terrain.record(&rec, &set, view, false, r.bodies());
                r.sky.record(&rec, &set, view);
            });
            // Its blurred layers, for the water to blur it by the slopes it does not resolve
            // (their alpha: the share of objects, as the sky writes 0); the sky its objects
            // hide with their distances (from its depth) as alpha, blurred alike, to put that
            // sky in place of what stands nearer than a sea point.
            rec.halve_down_layers(&t.reflection.colour);
            let targets = [Target::new(&t.reflection_sky, Load::DontCare)];
            let pass = &r.reflection_distance;
            let sets = pass.sets(set[0]);
            let draw = pass.draw(&sets);
            rec.rendering(names::REFLECTION_DISTANCE, &targets, None, &[draw])
                .record(|| pass.record(&rec, &draw));
            rec.halve_down_layers(&t.reflection_sky);
        });
        profiler.pause(&rec);
        rec.end_label();
    }
    frames.submit_scene(&mut frame)?;

    // ── compute: the simulation into slot f % 2 ─────────────────────────────────────────────
    simulation.submit(
        frame.slot,
        value,
        frame.previous_user(),
        inputs.time_s,
        &foam_scene,
        Some((compute_profiler, &frame)),
    )?;

    // ── graphics 2: after the simulation ────────────────────────────────────────────────────
    let mut waits = vec![simulation.graphics_wait(value)];
    let mut signals = Vec::new();
    if let Some(image) = delivery.present {
        waits.push(image.acquire_wait(ACQUIRE_WAIT_STAGE));
        signals.push(image.ready_signal());
    }
    {
        let rec = frame.recorder(ctx, Submission::Ocean);
        rec.begin_label(&format!("frame {} (graphics 2)", frame.index));
        profiler.resume(&rec, GRAPHICS_OCEAN);
        // Where the near plane lies against the water: under it, or split at the waterline,
        // the main view draws the terrain with the caustics and the shafts are needed.
        let side = inputs.water_side(r.camera(), output.aspect());
        let underwater = side != WaterSide::Above;
        // The caustics' means, before anything draws the caustics: on the first frame that
        // does, and when the sun, the waves or the focal length have changed and held since.
        let caustics = r.settings.caustics && (underwater || r.settings.refraction_caustics);
        let measure = caustics && r.caustic_means.due();
        let r = &*r;
        let set = [r.frame_set(frame.slot)];
        if measure {
            let target = [Target::new(&r.caustic_means.fill.image, Load::DontCare)];
            let draw = r.caustic_means.fill.draw(&set);
            let scope = rec.rendering(names::CAUSTIC_MEANS, &target, None, &[draw]);
            profiler.pass(&rec, names::CAUSTIC_MEANS, || {
                scope.record(|| r.caustic_means.fill.record(&rec, &set))
            });
        }
        // The water's sets: the frame set, its textures (reflection, refraction, DU/DV) and
        // the clipmap's tile list.
        let water_sets = r.water.sets(set[0], frame.slot);
        let texture_sets = [set[0], &r.water.textures().set];
        let t = &r.targets;
        // The refraction and the scene: their terrain is lit by the caustics, which sample the
        // simulation's images (terrain_caustics.frag; the scene's only from under the water).
        let deep = Load::Clear(vk::ClearValue {
            color: vk::ClearColorValue {
                float32: DEEP_WATER,
            },
        });
        // From under the water: the light shafts' means, which the scene, the water and the
        // sky sample (the caustics: the simulation's normal images).
        if underwater && r.settings.caustics {
            let target = [Target::new(&r.shafts.image, Load::DontCare)];
            let draw = r.shafts.draw(&set);
            let scope = rec.rendering(names::SHAFTS, &target, None, &[draw]);
            profiler.pass(&rec, names::SHAFTS, || {
                scope.record(|| r.shafts.record(&rec, &set))
            });
        }
        let view = ViewIndex::Refraction;
        let draws = r.terrain.draws(&set, view, underwater);
        let scope = drawn_anew(&rec, names::REFRACTION, &t.refraction, deep, &draws);
        profiler.pass(&rec, names::REFRACTION, || {
            scope.record(|| r.terrain.record(&rec, &set, view, underwater, r.bodies()))
        });
        // Scene, water and sky are three rendering scopes, so each pass's timestamps cover its
        // own rasterisation (a CPU driver may defer drawing to the end of a scope). The sky goes
        // last and fills only what terrain and water left: no covered pixel is shaded twice.
        let view = ViewIndex::Main;
        let draws = r.terrain.draws(&set, view, underwater);
        let scope = drawn_anew(&rec, names::SCENE, &t.main, Load::DontCare, &draws);
        profiler.pass(&rec, names::SCENE, || {
            scope.record(|| r.terrain.record(&rec, &set, view, underwater, r.bodies()))
        });
        let keep = |image| Target::new(image, Load::Keep);
        let main = [keep(&t.main.colour)];
        // Its barriers: the reflection, refraction and DU/DV textures and the sky cube at the
        // stages the water's shaders sample them in (the sky cube in tessellation evaluation
        // too); the simulation images are ordered by the compute timeline's wait.
        let draw = r.water.draw(&water_sets, r.settings.view, side);
        let scope = rec.rendering(names::WATER, &main, Some(keep(&t.main.depth)), &[draw]);
        profiler.begin_pass(&rec, names::WATER);
        scope.record(|| {
            // Patches, tessellation-evaluation invocations, triangles and fragments.
            profiler.statistics(&rec, || {
                r.water
                    .record(&rec, &water_sets, r.settings.view, side, frame.slot)
            });
        });
        profiler.end_pass(&rec);
        let draw = r.sky.draw(&set, ViewIndex::Main);
        let scope = rec.rendering(names::SKY, &main, Some(keep(&t.main.depth)), &[draw]);
        profiler.pass(&rec, names::SKY, || {
            scope.record(|| r.sky.record(&rec, &set, ViewIndex::Main))
        });
        // The spray over everything drawn (the final view only).
        if let Some(spray) = r
            .spray
            .as_ref()
            .filter(|_| r.settings.view == ViewMode::Final)
        {
            let sets = spray.sets(set[0], frame.slot);
            let draw = spray.draw(&sets);
            let scope = rec.rendering(names::SPRAY, &main, Some(keep(&t.main.depth)), &[draw]);
            profiler.pass(&rec, names::SPRAY, || {
                scope.record(|| spray.record(&rec, &sets, frame.slot))
            });
        }
        if TexturesViewPass::shows(r.settings.view) {
            let over = [Target::new(&t.main.colour, Load::DontCare)];
            let draw = r.textures_view.draw(&texture_sets);
            let scope = rec.rendering(names::TEXTURES_VIEW, &over, None, &[draw]);
            profiler.pass(&rec, names::TEXTURES_VIEW, || {
                scope.record(|| r.textures_view.record(&rec, &texture_sets))
            });
        }
        if let (Some(pass), Some(smooth)) = (&r.anti_aliasing, &t.anti_aliased) {
            // The main depth, done with, holds the pass's edge mask (every pixel written).
            let target = [Target::new(smooth, Load::DontCare)];
            let mask = Target::new(&t.main.depth, Load::DontCare);
            let aa_set = pass.set_ref();
            let draws = pass.draws(&aa_set);
            let scope = rec.rendering(names::ANTI_ALIASING, &target, Some(mask), &draws);
            profiler.pass(&rec, names::ANTI_ALIASING, || {
                scope.record(|| pass.record(&rec, &draws, r.settings.sharpen))
            });
        }
        profiler.pass(&rec, names::OUTPUT, || {
            // Edge-directed scaling for the final picture; the debug views show data.
            let edge = r.settings.view == ViewMode::Final && r.settings.upscale == Upscale::Edge;
            r.output
                .record(&rec, t.final_colour(), output, r.scale_filter, edge)
        })?;
        if let Some(o) = overlay {
            // Over the finished picture: the output image is the attachment, loaded.
            let target = [Target::output(output.image, Load::Keep)];
            let scope = rec.rendering(names::OVERLAY, &target, None, &[]);
            let extent = output.extent;
            let mut drawn = Ok(());
            profiler.pass(&rec, names::OVERLAY, || {
                scope.record(|| {
                    drawn = o
                        .painter
                        .draw(&rec, extent, o.pixels_per_point, o.primitives)
                })
            });
            drawn?;
        }
        if let Some(buffer) = delivery.readback {
            rec.pass("readback");
            record_readback(&rec, output, buffer);
        }
        if delivery.present.is_some() {
            rec.pass("present");
            rec.uses(&[(output.image.tracked(), Use::Present)]);
        }
        profiler.end_frame(&rec);
        rec.end_label();
    }
    frames.submit(frame, &waits, &signals)?;
    Ok(value)
}

/// The rendering scope of pass `pass`, which draws a colour target anew with `draws`: the
/// colour loaded as `colour` says, the depth cleared (barriers recorded).
fn drawn_anew<'r>(
    rec: &'r Recorder,
    pass: &str,
    cd: &ColourDepth,
    colour: Load,
    draws: &[Bindings],
) -> Rendering<'r> {
    let target = [Target::new(&cd.colour, colour)];
    rec.rendering(
        pass,
        &target,
        Some(Target::new(&cd.depth, CLEAR_DEPTH)),
        draws,
    )
}

/// Records a copy of the output into `buffer` for the host (screenshots).
fn record_readback(rec: &Recorder, output: &OutputTarget, buffer: &Buffer) {
    rec.copy_image_to_buffer(output.image, buffer);
    rec.uses(&[(buffer, Use::HostRead)]);
}
