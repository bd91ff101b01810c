//! Windowed frontend: a winit 0.30 `ApplicationHandler` presenting through a swapchain.
//! The swapchain is recreated on resize and when it is out of date or suboptimal; a minimised
//! window (zero extent) pauses rendering. Esc or the close button end the run, `--frames N`
//! stops after N frames, F12 saves a screenshot (to `--screenshot` or `vkocean-<frame>.png`).
//! The title shows the size drawn at, the quality level and progress,
//! `vkocean - WxH - quality LEVEL[ (device default)] - frame N - X ms/frame`,
//! updated twice a second and as soon as the size changes.
//! The camera flies with W/A/S/D, Q/E, Shift and a left mouse drag (`fly.rs`).

use std::path::PathBuf;
use std::sync::Arc;

use ash::vk;
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, KeyEvent, MouseButton, WindowEvent};
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::keyboard::{Key, KeyCode, NamedKey, PhysicalKey};
use winit::raw_window_handle::{HasDisplayHandle, HasWindowHandle};
use winit::window::{Window, WindowId};

use super::fly::{FlyCamera, Move};
use super::overlay::{Overlay, Requests};
use super::session::{check_size, readback_buffer, Session};
use super::{Outcome, RunSettings};
use crate::gpu::{Buffer, Context, ContextDesc, MessageCounters, Output, Swapchain};
use crate::output::{encode_png, PendingFile, Staged};
use crate::render::{Delivery, FrameInputs, OutputTarget, ACQUIRE_WAIT_STAGE};

pub fn run(s: &RunSettings) -> anyhow::Result<Outcome> {
    crate::platform::check_display()?;
    let profile = s
        .profile
        .as_deref()
        .map(|p| PendingFile::create("--profile", p))
        .transpose()?;
    // Written once the window's second frame is submitted.
    let frame_graph = PendingFile::create_if("--frame-graph", s.frame_graph.as_deref())?;
    // Checked now so a bad path fails before the window opens; written at exit.
    let screenshot = s
        .screenshot
        .as_deref()
        .map(|p| PendingFile::create("--screenshot", p))
        .transpose()?;
    let event_loop = EventLoop::new().map_err(|e| {
        anyhow::anyhow!("cannot open a window ({e}); run with --headless, or under xvfb-run")
    })?;
    let mut app = App {
        settings: s.clone(),
        profile,
        frame_graph,
        screenshot,
        exit_shot: None,
        state: None,
        error: None,
        counters: None,
        frames_done: 0,
        capture_next: false,
        exit_after_capture: false,
        fly: FlyCamera::default(),
        clock: super::clock::Clock::new(s.start_time_s, s.time_scale),
        last_frame: None,
        title_since: None,
        cursor: None,
    };
    event_loop
        .run_app(&mut app)
        .map_err(|e| anyhow::anyhow!("window event loop: {e}"))?;
    if let Some(e) = app.error.take() {
        return Err(e);
    }
    let counters = app
        .counters
        .take()
        .ok_or_else(|| anyhow::anyhow!("the window never opened"))?;
    Ok(Outcome { counters })
}

/// GPU state tied to the window. Field order is drop order: GPU objects (and with the last of
/// them the context and its surface) go before the window they present to.
struct WindowState {
    /// The overlay (F1) and the window input it reads; before the session (drop order).
    overlay: Overlay,
    egui_input: egui_winit::State,
    session: Session,
    swapchain: Swapchain,
    /// Screenshot staging, sized to the swapchain.
    readback: Option<Buffer>,
    needs_recreate: bool,
    /// The window's inner size, from `Resized` events: asking winit every frame costs an X
    /// round trip (and panics inside winit once the X connection is gone).
    size: PhysicalSize<u32>,
    window: Arc<Window>,
}

struct App {
    settings: RunSettings,
    profile: Option<PendingFile>,
    /// `--frame-graph`, handed to the session when it is made.
    frame_graph: Option<PendingFile>,
    /// `--screenshot`: written with the last frame at exit.
    screenshot: Option<PendingFile>,
    /// The exit screenshot (its path, and the staged file), placed with the profile at shutdown.
    exit_shot: Option<(String, Staged)>,
    state: Option<WindowState>,
    /// First error; the event loop exits and `run` returns it.
    error: Option<anyhow::Error>,
    counters: Option<Arc<MessageCounters>>,
    frames_done: u64,
    /// Copy the next frame to a PNG (F12, or the last frame with --screenshot).
    capture_next: bool,
    /// Exit once the captured frame is saved (Esc / close with --screenshot).
    exit_after_capture: bool,
    fly: FlyCamera,
    /// Simulation time (`--time`, `--time-scale`, the overlay's pause).
    clock: super::clock::Clock,
    /// When the previous frame started (camera motion uses the wall-clock step).
    last_frame: Option<std::time::Instant>,
    /// When the title was last updated, the frame count and the size it showed.
    title_since: Option<(std::time::Instant, u64, vk::Extent2D)>,
    /// Where the cursor is in the window (physical pixels): a right click drops a body there.
    cursor: Option<(f64, f64)>,
}

/// How often the title's frame count and frame time are updated.
const TITLE_PERIOD: std::time::Duration = std::time::Duration::from_millis(500);

/// The fly camera's keys (by position, so they work on any keyboard layout).
fn fly_key(code: KeyCode) -> Option<Move> {
    Some(match code {
        KeyCode::KeyW => Move::Forward,
        KeyCode::KeyS => Move::Back,
        KeyCode::KeyA => Move::Left,
        KeyCode::KeyD => Move::Right,
        KeyCode::KeyQ => Move::Down,
        KeyCode::KeyE => Move::Up,
        KeyCode::ShiftLeft | KeyCode::ShiftRight => Move::Fast,
        _ => return None,
    })
}

fn physical_size(size: PhysicalSize<u32>) -> vk::Extent2D {
    vk::Extent2D {
        width: size.width,
        height: size.height,
    }
}

impl App {
    /// Ends the run with an error: the GPU state is dropped without writing any output.
    fn fail(&mut self, event_loop: &ActiveEventLoop, error: anyhow::Error) {
        if self.error.is_none() {
            self.error = Some(error);
        }
        self.state = None;
        event_loop.exit();
    }

    /// Finishes a successful run: waits for the GPU, writes the profile, prints the summary.
    fn shutdown(&mut self, event_loop: &ActiveEventLoop) {
        if let Some(mut state) = self.state.take() {
            let size = (state.swapchain.extent.width, state.swapchain.extent.height);
            let suffix = format!("; swapchain created {} times", state.swapchain.generation);
            let profile = self.profile.take();
            let with_table = profile.is_some();
            let shot = self.exit_shot.take();
            let done = state.session.finish(size).and_then(|finished| {
                let mut staged: Vec<Staged> =
                    finished.stage_profile(profile)?.into_iter().collect();
                let path = shot.map(|(path, file)| {
                    staged.push(file);
                    path
                });
                crate::output::place_all(staged)?;
                if let Some(path) = path {
                    eprintln!("vkocean: saved {path}");
                }
                finished.report(with_table, &suffix);
                Ok(())
            });
            if let Err(e) = done {
                self.error.get_or_insert(e);
            }
        }
        event_loop.exit();
    }

    fn create(&mut self, event_loop: &ActiveEventLoop) -> anyhow::Result<WindowState> {
        let (w, h) = self.settings.size;
        let attributes = Window::default_attributes()
            .with_title("vkocean")
            .with_inner_size(PhysicalSize::new(w, h))
            .with_resizable(true);
        let window = Arc::new(
            event_loop
                .create_window(attributes)
                .map_err(|e| anyhow::anyhow!("cannot open a window: {e}"))?,
        );
        crate::platform::watch_display();
        let display = window
            .display_handle()
            .map_err(|e| anyhow::anyhow!("window display handle: {e}"))?
            .as_raw();
        let handle = window
            .window_handle()
            .map_err(|e| anyhow::anyhow!("window handle: {e}"))?
            .as_raw();
        let ctx = Context::new(&ContextDesc {
            validation: self.settings.validation,
            validation_extras: self.settings.validation_extras,
            gpu_index: self.settings.gpu,
            needs: self.settings.scene.needs(),
            window: Some((display, handle)),
        })?;
        self.counters = Some(ctx.counters());
        check_size(&ctx, self.settings.size)?;
        let size = window.inner_size();
        let swapchain = Swapchain::new(&ctx, physical_size(size), self.settings.present_mode)?;
        if self.screenshot.is_some() && !swapchain.can_copy {
            anyhow::bail!(
                "--screenshot: this window's swapchain images cannot be copied (no TRANSFER_SRC usage)"
            );
        }
        let mut session = Session::new(&ctx, swapchain.format, swapchain.extent, &self.settings)?;
        if let Some(file) = self.frame_graph.take() {
            // The second frame: the first also renders the sky cube and warms the foam up.
            session.write_frame_graph_of(1, file);
        }
        session.keep_live_timings();
        let s = &self.settings;
        let overlay = Overlay::new(&ctx, swapchain.format, &s.tunables, s.quality.0, s.overlay)?;
        let egui_input = egui_winit::State::new(
            overlay.context().clone(),
            egui::ViewportId::ROOT,
            &window,
            Some(window.scale_factor() as f32),
            None,
            Some(ctx.info.limits.max_image_dimension2_d as usize),
        );
        Ok(WindowState {
            overlay,
            egui_input,
            session,
            swapchain,
            readback: None,
            needs_recreate: false,
            size,
            window,
        })
    }

    /// Renders and presents one frame, recreating the swapchain first when needed; does nothing
    /// while the window is minimised.
    // Long: one window frame in the order its steps depend on each other (acquire, recreate,
    // capture, time, record, present, title); each step uses the previous one's result.
    fn draw(&mut self, event_loop: &ActiveEventLoop) -> anyhow::Result<()> {
        let Some(state) = self.state.as_mut() else {
            return Ok(());
        };
        // The surface's capabilities are queried only when the swapchain is recreated: on a
        // resize event, an out-of-date or suboptimal acquire or present (`needs_recreate`).
        let window_size = physical_size(state.size);
        let mut minimised = window_size.width == 0 || window_size.height == 0;
        if !minimised && state.needs_recreate {
            let mode = self.settings.present_mode;
            // `false`: the surface itself has zero size (minimised before the event arrived).
            minimised = !state.swapchain.recreate(window_size, mode)?;
            if !minimised {
                state.session.renderer.resize(state.swapchain.extent)?;
                state.needs_recreate = false;
            }
        }
        if minimised {
            self.title_since = None; // the title's next frame time starts after the pause
            return Ok(()); // pause until the next resize
        }
        let extent = state.swapchain.extent;
        if state.overlay.format() != state.swapchain.format {
            // A recreated swapchain in another format: the overlay's pipeline follows it.
            state.session.frames.wait_all()?;
            let mut o = Overlay::new(
                &state.session.ctx,
                state.swapchain.format,
                &state.overlay.applied,
                self.settings.quality.0,
                state.overlay.visible,
            )?;
            o.edit = state.overlay.edit.clone();
            state.overlay = o;
        }
        apply_pending(&self.settings, state);
        let progress = match self.settings.dt_s {
            Some(dt) => state.session.frames.submitted() as f64 * dt,
            None => state.session.elapsed_s(),
        };
        self.clock.set(
            progress,
            state.overlay.applied.time_scale,
            state.overlay.paused,
        );

        let Some((image, suboptimal)) = state.swapchain.acquire(&state.session.frames)? else {
            state.needs_recreate = true;
            return Ok(());
        };
        state.needs_recreate |= suboptimal;

        let last = self
            .settings
            .frames
            .is_some_and(|n| self.frames_done + 1 >= n);
        // The exit screenshot (--screenshot at the last frame, or after Esc/close) is part of
        // the run's output; an F12 screenshot is a convenience whose failure is only reported.
        let exit_shot = self.screenshot.is_some() && (last || self.exit_after_capture);
        if self.capture_next && !state.swapchain.can_copy {
            eprintln!("vkocean: F12: this swapchain's images cannot be copied; no screenshot");
            self.capture_next = false;
        }
        let capture = exit_shot || self.capture_next;
        let bytes = extent.width as u64 * extent.height as u64 * 4;
        if capture && state.readback.as_ref().is_none_or(|b| b.size() != bytes) {
            state.readback = Some(readback_buffer(&state.session.ctx, extent)?);
        }
        let readback = if capture {
            state.readback.as_ref()
        } else {
            None
        };

        // Free for writing once the acquire semaphore's wait is done.
        let swapchain_image = image.target(ACQUIRE_WAIT_STAGE);
        let transfer_dst = state.swapchain.transfer_dst;
        let output = OutputTarget::new(Output::External(&swapchain_image), transfer_dst);
        let now = std::time::Instant::now();
        let step = self
            .last_frame
            .map_or(0.0, |last| now.duration_since(last).as_secs_f32());
        self.last_frame = Some(now);
        self.fly.update(state.session.renderer.camera_mut(), step);
        let inputs = FrameInputs {
            time_s: self.clock.at(progress),
            ..FrameInputs::default()
        };
        let mut requests = Requests::default();
        let draw = if state.overlay.visible {
            let input = state.egui_input.take_egui_input(&state.window);
            let (asked, textures) = state.overlay.run(input, &state.session);
            state.overlay.upload(textures)?;
            requests = asked;
            Some(state.overlay.draw())
        } else {
            None
        };
        let delivery = Delivery {
            readback,
            present: Some(&image),
        };
        state.session.frame(&output, &inputs, &delivery, draw)?;
        self.capture_next |= requests.screenshot;
        state.needs_recreate |= state.swapchain.present(&image)?;
        self.frames_done += 1;
        match self.title_since {
            Some((since, frames, shown)) if now - since >= TITLE_PERIOD || shown != extent => {
                let ms = (now - since).as_secs_f64() * 1e3 / (self.frames_done - frames) as f64;
                state.window.set_title(&format!(
                    "vkocean - {}x{} - quality {}{} - frame {} - {ms:.1} ms/frame",
                    extent.width,
                    extent.height,
                    self.settings.quality.0,
                    match self.settings.quality.1 {
                        "device" => " (device default)",
                        _ => "",
                    },
                    self.frames_done
                ));
                self.title_since = Some((now, self.frames_done, extent));
            }
            Some(_) => {}
            None => self.title_since = Some((now, self.frames_done, extent)),
        }
        if self.settings.stats {
            state.session.print_stats()?;
        }

        if let Some(buffer) = readback {
            let pixels = bgra_to_rgba(
                &state.session.frames.read_back(buffer)?,
                state.swapchain.format,
            );
            if exit_shot {
                let png = encode_png(extent.width, extent.height, &pixels)?;
                let file = self
                    .screenshot
                    .take()
                    .expect("exit_shot implies --screenshot");
                // Placed with the profile at shutdown (both or neither).
                self.exit_shot = Some((file.path().display().to_string(), file.stage(&png)?));
            } else {
                // F12: to --screenshot's path if given (the exit screenshot overwrites it
                // later), else to vkocean-<frame>.png in the working directory.
                let path =
                    self.settings.screenshot.clone().unwrap_or_else(|| {
                        PathBuf::from(format!("vkocean-{}.png", self.frames_done))
                    });
                let saved = encode_png(extent.width, extent.height, &pixels)
                    .and_then(|png| PendingFile::create("F12 screenshot", &path)?.commit(&png));
                match saved {
                    Ok(()) => eprintln!("vkocean: saved {}", path.display()),
                    Err(e) => eprintln!("vkocean: F12 screenshot not saved: {e}"),
                }
            }
            self.capture_next = false;
        }
        if requests.save {
            save_settings(state);
        }
        if last || (self.exit_after_capture && self.screenshot.is_none()) {
            self.shutdown(event_loop);
        }
        Ok(())
    }

    /// A right click: a crate dropped on the water under the cursor (`Session::drop_body`).
    fn drop_body(&mut self) {
        let (Some(state), Some((x, y))) = (self.state.as_mut(), self.cursor) else {
            return;
        };
        let (w, h) = (state.size.width as f64, state.size.height as f64);
        if w < 1.0 || h < 1.0 {
            return;
        }
        let ndc = [(2.0 * x / w - 1.0) as f32, (2.0 * y / h - 1.0) as f32];
        state.overlay.status = match state.session.drop_body(ndc, (w / h) as f32) {
            Some([x, z]) => format!("dropped a crate at {x:.1}, {z:.1}"),
            None => "no room for another body, or no water under the cursor".to_string(),
        };
    }

    /// Esc or close: with --screenshot, render one more frame to capture it, then exit.
    fn request_exit(&mut self, event_loop: &ActiveEventLoop) {
        let minimised = self
            .state
            .as_ref()
            .is_some_and(|s| s.size.width == 0 || s.size.height == 0);
        match (&self.state, self.screenshot.is_some()) {
            (Some(state), true) if !minimised => {
                self.exit_after_capture = true;
                state.window.request_redraw();
            }
            (Some(_), true) => self.fail(
                event_loop,
                anyhow::anyhow!(
                    "the window was minimised at exit, so --screenshot was not written"
                ),
            ),
            _ => self.shutdown(event_loop),
        }
    }
}

/// F1 pressed (not a repeat).
fn is_f1(event: &WindowEvent) -> bool {
    matches!(
        event,
        WindowEvent::KeyboardInput {
            event: KeyEvent {
                logical_key: Key::Named(NamedKey::F1),
                state: ElementState::Pressed,
                repeat: false,
                ..
            },
            ..
        }
    )
}

/// Applies the overlay's changed tunables between frames (`Session::retune`); a setting the
/// run refuses (e.g. wireframe without fillModeNonSolid) is undone and reported in the panel.
fn apply_pending(settings: &RunSettings, state: &mut WindowState) {
    let Some(tunables) = state.overlay.pending() else {
        return;
    };
    let done = (settings.retune.0)(&tunables)
        .map_err(anyhow::Error::msg)
        .and_then(|s| state.session.retune(&s));
    match done {
        Ok(()) => {
            state.overlay.applied = tunables;
            state.overlay.status.clear();
        }
        Err(e) => {
            state.overlay.edit = state.overlay.applied.clone();
            state.overlay.status = format!("not applied: {e}");
        }
    }
}

/// The overlay's "Save settings": the settings in force and the camera, as a `--config` file
/// in the working directory.
fn save_settings(state: &mut WindowState) {
    let mut t = state.overlay.applied.clone();
    let camera = state.session.renderer.camera();
    let at = camera.position + camera.forward * 100.0;
    t.camera = Some((camera.position.to_array(), at.to_array()));
    let path = std::path::Path::new(SETTINGS_FILE);
    let saved = PendingFile::create("the overlay's settings file", path)
        .and_then(|f| f.commit(t.to_toml().as_bytes()));
    state.overlay.status = match saved {
        Ok(()) => format!("saved {SETTINGS_FILE} (vkocean --config {SETTINGS_FILE})"),
        Err(e) => format!("not saved: {e}"),
    };
    eprintln!("vkocean: {}", state.overlay.status);
}

/// Where the overlay saves the settings.
const SETTINGS_FILE: &str = "vkocean-settings.toml";

/// Swapchain bytes to RGBA (B8G8R8A8 formats swap red and blue).
fn bgra_to_rgba(bytes: &[u8], format: vk::Format) -> Vec<u8> {
    let mut pixels = bytes.to_vec();
    if crate::gpu::image::is_bgra(format) {
        for px in pixels.chunks_exact_mut(4) {
            px.swap(0, 2);
        }
    }
    pixels
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.state.is_some() || self.error.is_some() {
            return;
        }
        match self.create(event_loop) {
            Ok(state) => self.state = Some(state),
            Err(e) => self.fail(event_loop, e),
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        if let Some(state) = self.state.as_mut() {
            if is_f1(&event) {
                state.overlay.visible = !state.overlay.visible;
                self.fly.release_all();
                return;
            }
            // The overlay first: what it takes (a click on it, typing into it) goes no further.
            if state.overlay.visible
                && state
                    .egui_input
                    .on_window_event(&state.window, &event)
                    .consumed
            {
                return;
            }
        }
        match event {
            WindowEvent::CloseRequested => self.request_exit(event_loop),
            WindowEvent::KeyboardInput {
                event:
                    KeyEvent {
                        physical_key: PhysicalKey::Code(code),
                        state,
                        ..
                    },
                ..
            } if fly_key(code).is_some() => {
                let m = fly_key(code).expect("checked");
                self.fly.key(m, state == ElementState::Pressed);
            }
            WindowEvent::MouseInput {
                button: MouseButton::Left,
                state,
                ..
            } => self.fly.drag(state == ElementState::Pressed),
            WindowEvent::MouseInput {
                button: MouseButton::Right,
                state: ElementState::Pressed,
                ..
            } => self.drop_body(),
            WindowEvent::CursorMoved { position, .. } => {
                self.cursor = Some((position.x, position.y));
                self.fly.cursor(position.x, position.y);
            }
            WindowEvent::Focused(false) => self.fly.release_all(),
            WindowEvent::KeyboardInput {
                event:
                    KeyEvent {
                        logical_key,
                        state: ElementState::Pressed,
                        repeat: false,
                        ..
                    },
                ..
            } => match logical_key {
                Key::Named(NamedKey::Escape) => self.request_exit(event_loop),
                Key::Named(NamedKey::F12) => self.capture_next = true,
                _ => {}
            },
            WindowEvent::Resized(size) => {
                // A resize often reaches the swapchain first (out of date at the next acquire,
                // recreated at the new size); the event arriving after that needs nothing more.
                if let Some(state) = self.state.as_mut() {
                    state.size = size;
                    state.needs_recreate |= physical_size(size) != state.swapchain.extent;
                }
            }
            WindowEvent::RedrawRequested => {
                if let Err(e) = self.draw(event_loop) {
                    self.fail(event_loop, e);
                }
            }
            _ => {}
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        // Ctrl-C or SIGTERM: stop between frames, without the outputs (--screenshot, --profile).
        if let Err(interrupted) = crate::interrupt::check() {
            self.fail(event_loop, interrupted.into());
            return;
        }
        if let Some(state) = &self.state {
            if state.size.width > 0 && state.size.height > 0 {
                state.window.request_redraw();
            }
        }
    }

    fn exiting(&mut self, event_loop: &ActiveEventLoop) {
        // Covers exits the handler did not start itself; a no-op after `shutdown`.
        self.shutdown(event_loop);
    }
}
