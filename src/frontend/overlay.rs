//! The overlay (F1 in a window, `--overlay`): an egui panel with the frame's timings (the same
//! per-pass GPU times as `--profile`), the device, and the settings a run can change while it
//! runs ([`Tunables`]). The panel edits a copy of the tunables; the frontend hands a changed
//! copy to the session (`Session::retune`) once no slider is being dragged, so a drag does not
//! rebuild the sea at every step. egui lays it out, `gpu::egui` draws it (the overlay pass).

use std::sync::Arc;
use std::time::Instant;

use clap::ValueEnum;
use egui::epaint::ClippedPrimitive;
use egui::{ComboBox, RawInput, Slider, TexturesDelta, Ui};

use super::session::Session;
use crate::gpu::egui::EguiPainter;
use crate::gpu::{Context, GpuResult};
use crate::render::{Geometry, OverlayDraw};
use crate::tuning::presets::{PresetArg, QualityArg};
use crate::tuning::Tunables;

/// What the user asked for in this frame's panel.
#[derive(Default)]
pub struct Requests {
    pub screenshot: bool,
    pub save: bool,
}

/// The overlay's state between frames.
pub struct Overlay {
    egui: egui::Context,
    painter: EguiPainter,
    /// Drawn (F1 toggles).
    pub visible: bool,
    /// What the controls show and edit.
    pub edit: Tunables,
    /// What the session runs with.
    pub applied: Tunables,
    /// Time stands still (the waves stop; the camera still flies).
    pub paused: bool,
    /// The last message for the user (a saved file, a setting the device refused).
    pub status: String,
    /// "device (driver), quality level".
    device: String,
    /// The water geometries the device can draw (tessellated needs tessellation shaders), and
    /// the default one.
    geometries: (Vec<Geometry>, Geometry),
    /// Wall time between frames (ms), smoothed, and when the last frame started.
    cpu_ms: f64,
    last_frame: Option<Instant>,
    /// This frame's triangles (`run`), drawn by `draw`.
    primitives: Vec<ClippedPrimitive>,
    pixels_per_point: f32,
    /// The panel's rectangle in the last frame (pixels): the only pixels the overlay draws.
    pub rect: Option<[f32; 4]>,
}

/// A value's name on the command line.
fn name<T: ValueEnum>(v: &T) -> String {
    v.to_possible_value()
        .map_or_else(String::new, |p| p.get_name().to_string())
}

/// A combo box over every value of a command-line enum.
fn choose<T: ValueEnum + PartialEq + Copy>(ui: &mut Ui, label: &str, value: &mut T) {
    ComboBox::from_label(label)
        .selected_text(name(value))
        .show_ui(ui, |ui| {
            for v in T::value_variants() {
                ui.selectable_value(value, *v, name(v));
            }
        });
}

impl Overlay {
    pub fn new(
        ctx: &Arc<Context>,
        format: ash::vk::Format,
        tunables: &Tunables,
        quality: &str,
        visible: bool,
    ) -> GpuResult<Overlay> {
        let egui = egui::Context::default();
        egui.set_theme(egui::Theme::Dark);
        // No fades: the panel is whole from its first frame (headless screenshots, F1).
        // No shadow: the panel's pixels are its rectangle (the test of its region holds it).
        egui.all_styles_mut(|style| {
            style.animation_time = 0.0;
            style.visuals.window_shadow = egui::Shadow::NONE;
        });
        Ok(Overlay {
            egui,
            painter: EguiPainter::new(ctx, format)?,
            visible,
            edit: tunables.clone(),
            applied: tunables.clone(),
            paused: false,
            status: String::new(),
            device: format!("{} ({}), quality {quality}", ctx.info.name, ctx.info.driver),
            geometries: (
                Geometry::value_variants()
                    .iter()
                    .copied()
                    .filter(|g| *g != Geometry::Tessellated || ctx.info.tessellation_shader)
                    .collect(),
                Geometry::resolve(None),
            ),
            cpu_ms: 0.0,
            last_frame: None,
            primitives: Vec::new(),
            pixels_per_point: 1.0,
            rect: None,
        })
    }

    /// The format it draws into.
    pub fn format(&self) -> ash::vk::Format {
        self.painter.format
    }

    /// The egui context (the window's input state feeds it).
    pub fn context(&self) -> &egui::Context {
        &self.egui
    }

    /// Lays out this frame's panel from `input` and the session's last timings; returns what
    /// the user asked for and egui's texture changes (`upload` them before `draw`).
    pub fn run(&mut self, input: RawInput, session: &Session) -> (Requests, TexturesDelta) {
        let now = Instant::now();
        if let Some(last) = self.last_frame {
            let ms = (now - last).as_secs_f64() * 1e3;
            self.cpu_ms = if self.cpu_ms == 0.0 {
                ms
            } else {
                0.9 * self.cpu_ms + 0.1 * ms
            };
        }
        self.last_frame = Some(now);
        let mut requests = Requests::default();
        let mut rect = None;
        let egui = self.egui.clone();
        let output = egui.run_ui(input, |ui| {
            let shown = egui::Window::new("vkocean  (F1 hides)")
                .default_pos([8.0, 8.0])
                .default_width(300.0)
                .resizable(false)
                .show(ui.ctx(), |ui| {
                    // The buttons and the sea presets first: always in the same place.
                    ui.horizontal(|ui| {
                        requests.screenshot = ui.button("Screenshot").clicked();
                        requests.save = ui.button("Save settings").clicked();
                    });
                    ui.horizontal(|ui| {
                        ui.label("sea");
                        for p in PresetArg::value_variants() {
                            let chosen = self.edit.preset == Some(*p);
                            if ui.selectable_label(chosen, name(p)).clicked() {
                                self.edit.set_preset(*p);
                            }
                        }
                    });
                    if !self.status.is_empty() {
                        ui.label(&self.status);
                    }
                    let tall = ui.ctx().content_rect().height() - 120.0;
                    egui::ScrollArea::vertical()
                        .max_height(tall)
                        .show(ui, |ui| {
                            self.frame_section(ui, session);
                            self.sea_section(ui);
                            self.look_section(ui);
                        });
                });
            rect = shown.map(|r| r.response.rect);
        });
        self.rect = rect.map(|r| [r.min.x, r.min.y, r.width(), r.height()]);
        self.pixels_per_point = output.pixels_per_point;
        self.primitives = self.egui.tessellate(output.shapes, output.pixels_per_point);
        (requests, output.textures_delta)
    }

    /// The tunables to apply now: the controls changed something and no drag is under way.
    pub fn pending(&self) -> Option<Tunables> {
        (self.edit != self.applied && !self.egui.egui_is_using_pointer()).then(|| self.edit.clone())
    }

    /// Uploads egui's texture changes (the first frame, new glyphs) before the frame that draws
    /// them; textures egui frees are retired through the deletion queue (`gpu::egui`), so no
    /// wait for the frames in flight.
    pub fn upload(&mut self, mut delta: TexturesDelta) -> GpuResult<()> {
        if delta.is_empty() {
            return Ok(());
        }
        let set: Vec<_> = delta
            .set
            .drain()
            .flat_map(|(id, deltas)| deltas.into_iter().map(move |d| (id, d)))
            .collect();
        let free: Vec<_> = delta.free.drain().collect();
        self.painter.update_textures(&set, &free)
    }

    /// This frame's overlay pass.
    pub fn draw(&mut self) -> OverlayDraw<'_> {
        OverlayDraw {
            painter: &mut self.painter,
            primitives: &self.primitives,
            pixels_per_point: self.pixels_per_point,
        }
    }

    fn frame_section(&self, ui: &mut Ui, session: &Session) {
        egui::CollapsingHeader::new("Frame")
            .default_open(true)
            .show(ui, |ui| {
                ui.label(&self.device);
                let fps = if self.cpu_ms > 0.0 {
                    1e3 / self.cpu_ms
                } else {
                    0.0
                };
                let (graphics, compute) = session.latest_timings();
                // A fold from 0.0: `sum` of no f64 is -0.0, which printed as "GPU -0.0 ms"
                // before the first timings arrived.
                let gpu = graphics
                    .into_iter()
                    .chain(compute)
                    .fold(0.0, |sum, t| sum + t.total_ms);
                ui.label(format!(
                    "{fps:.1} FPS   CPU {:.1} ms/frame   GPU {gpu:.1} ms",
                    self.cpu_ms
                ));
                if let Some(bodies) = session.bodies_status() {
                    ui.label(bodies);
                }
                ui.label("right click on the water: drop a crate there");
                let passes: Vec<_> = compute
                    .into_iter()
                    .chain(graphics)
                    .flat_map(|t| t.passes.iter())
                    .collect();
                let most = passes.iter().map(|p| p.1).fold(1e-6, f64::max);
                for (pass, ms) in passes {
                    let bar = egui::ProgressBar::new((ms / most) as f32)
                        .desired_height(14.0)
                        .text(format!("{pass}  {ms:.2} ms"));
                    ui.add(bar);
                }
            });
    }

    fn sea_section(&mut self, ui: &mut Ui) {
        egui::CollapsingHeader::new("Sea")
            .default_open(true)
            .show(ui, |ui| {
                let t = &mut self.edit;
                let mut model = if t.gerstner { "gerstner" } else { "fft" };
                ComboBox::from_label("model")
                    .selected_text(model)
                    .show_ui(ui, |ui| {
                        ui.selectable_value(&mut model, "fft", "fft");
                        ui.selectable_value(&mut model, "gerstner", "gerstner");
                    });
                t.gerstner = model == "gerstner";
                choose(ui, "spectrum", &mut t.spectrum);
                let wind = Slider::new(&mut t.wind_speed, 0.5..=40.0).logarithmic(true);
                ui.add(wind.text("wind (m/s)"));
                ui.add(Slider::new(&mut t.wind_dir, -180.0..=180.0).text("wind dir (deg)"));
                let fetch = Slider::new(&mut t.fetch, 1.0..=2000.0).logarithmic(true);
                ui.add(fetch.text("fetch (km)"));
                let mut finite = t.depth.is_some();
                ui.horizontal(|ui| {
                    ui.checkbox(&mut finite, "finite depth");
                    let mut depth = t.depth.unwrap_or(50.0);
                    if finite {
                        let s = Slider::new(&mut depth, 1.0..=500.0).logarithmic(true);
                        ui.add(s.text("m"));
                    }
                    t.depth = finite.then_some(depth);
                });
                ui.add(Slider::new(&mut t.choppiness, 0.0..=3.0).text("choppiness"));
                ui.add(Slider::new(&mut t.cascades, 1..=4).text("cascades"));
                ComboBox::from_label("FFT size")
                    .selected_text(t.fft_size.to_string())
                    .show_ui(ui, |ui| {
                        for n in [64, 128, 256, 512, 1024] {
                            ui.selectable_value(&mut t.fft_size, n, n.to_string());
                        }
                    });
                ui.horizontal(|ui| {
                    ui.add(egui::DragValue::new(&mut t.seed));
                    ui.label("seed");
                });
            });
    }

    fn look_section(&mut self, ui: &mut Ui) {
        egui::CollapsingHeader::new("Look")
            .default_open(true)
            .show(ui, |ui| {
                let t = &mut self.edit;
                let mut quality = t.quality;
                choose::<QualityArg>(ui, "quality", &mut quality);
                if quality != t.quality {
                    t.set_quality(quality);
                }
                choose(ui, "view", &mut t.view);
                choose(ui, "Fresnel", &mut t.fresnel);
                choose(ui, "anti-aliasing", &mut t.aa);
                ui.add(Slider::new(&mut t.sun[0], -180.0..=180.0).text("sun azimuth"));
                ui.add(Slider::new(&mut t.sun[1], -10.0..=90.0).text("sun elevation"));
                ui.horizontal(|ui| {
                    ui.add(Slider::new(&mut t.clouds, 0.0..=1.0).text("clouds"));
                    ui.checkbox(&mut t.gusts, "gusts");
                });
                // Natural slicks: by the wind (Romano 1996's share) or a share of one's own.
                let mut own = t.slicks.is_some();
                ui.horizontal(|ui| {
                    ui.checkbox(&mut own, "slicks");
                    let mut share = t.slicks.unwrap_or(0.35);
                    if own {
                        ui.add(Slider::new(&mut share, 0.0..=1.0).text("of the sea"));
                    } else {
                        ui.label("by the wind");
                    }
                    t.slicks = own.then_some(share);
                });
                ui.horizontal(|ui| {
                    ui.add(Slider::new(&mut t.time_scale, 0.0..=4.0).text("time scale"));
                    ui.checkbox(&mut self.paused, "pause");
                });
                ui.add(Slider::new(&mut t.render_scale, 0.25..=1.0).text("render scale"));
                ui.add(Slider::new(&mut t.rtt_scale, 0.1..=1.0).text("RTT scale"));
                let (geometries, default) = &self.geometries;
                ComboBox::from_label("water geometry")
                    .selected_text(t.geometry.map_or_else(
                        || format!("default ({})", default.name()),
                        |g| g.name().to_string(),
                    ))
                    .show_ui(ui, |ui| {
                        let default_text = format!("default ({})", default.name());
                        ui.selectable_value(&mut t.geometry, None, default_text);
                        for g in geometries {
                            ui.selectable_value(&mut t.geometry, Some(*g), g.name());
                        }
                    });
                let edge = Slider::new(&mut t.tess_edge, 2.0..=128.0).logarithmic(true);
                ui.add(edge.text("tess edge / cell (px)"));
            });
    }
}
