//! Output pass: puts the main target (display colour at `--render-scale` of the output's size),
//! or with `--aa fxaa` the anti-aliased target of the same size and format, into the output
//! image (a swapchain image or the headless target). A copy when the two have the same size and
//! format; otherwise a blit, bilinear when the sizes differ, which also
//! converts between RGBA and BGRA byte orders (a recreated swapchain may change it).
//!
//! Why the tone map is not a pass of its own here: at 1280x720 on lavapipe a full-screen
//! tone-map pass at the output's size cost 12–14 ms, the blit from a half-size main target
//! 3.2–3.6 ms. The scene shaders tone-map per fragment at the main target's size instead
//! (shaders/common/display.glsl), and the sRGB attachment format encodes.

use ash::vk;

use crate::gpu::{Image, Recorder};

use crate::render::OutputTarget;

/// Records the copy or blit of `main` (the main or the anti-aliased colour, last written as a
/// colour attachment) into `output`. Outside any rendering scope. A blit that scales filters
/// with `scale_filter`.
pub fn record(rec: &Recorder, main: &Image, output: &OutputTarget, scale_filter: vk::Filter) {
    if main.extent() == output.extent && main.format() == output.format {
        rec.copy_image(main, output.image);
    } else {
        let filter = if main.extent() == output.extent {
            vk::Filter::NEAREST
        } else {
            scale_filter
        };
        rec.blit_image(main, output.image, filter);
    }
}
