//! The caustics' means (issue 34; shaders/underwater/caustic_means.frag,
//! common/caustics.glsl): the area ratio the caustics draw is taken at one surface point per
//! floor point, found by one fixed-point step, so it samples the surface nearly uniformly and
//! its mean over the floor is not 1 (the light would be made, not moved). This pass measures
//! that mean from the sea as simulated: per texel of a small image (a floor depth and a pixel
//! footprint, `CAUSTIC_MEAN_DEPTHS` × `CAUSTIC_MEAN_PIXELS`), the mean ratio over 9,216 floor
//! points across the largest cascade's patch, with the step (the floor) and without (the
//! light shafts, the mirrored floor). The caustics divide by it (`caustic_mean`, sampled
//! linearly through the frame set's binding 8). The sea's statistics do not change with time,
//! so it is drawn on the first frame that needs the caustics and again only when what sets
//! them changes ([`CausticKey`]): the sun, the waves' moments and patches, the view's focal
//! length. The image is cleared to 1 (a level sea's mean) when it is made, so what samples it
//! is never undefined.

use std::sync::Arc;

use ash::vk;

use super::water::WaterKind;
use super::FrameSetImage;
use crate::gpu::{Context, DescriptorSetLayout, GpuResult};
use crate::render::uniforms::FrameUniforms;
use crate::shaders;
use crate::shared::{CAUSTIC_MEAN_DEPTHS, CAUSTIC_MEAN_PIXELS};

/// What the measured means depend on, from a frame's uniforms: the sun's direction, the
/// cascades' patches and moments (the waves' statistics), the view's focal length (the fade of
/// the cascades with distance) and the wave model's window. The simulation's images change
/// every frame; their statistics change only with these.
#[derive(Clone, Copy, PartialEq, Debug)]
pub struct CausticKey([[f32; 4]; 5]);

impl CausticKey {
    pub fn of(u: &FrameUniforms) -> CausticKey {
        // (The sun's w, the clouds' share of its light, does not change the means.)
        let [x, y, z, _] = u.sun_dir;
        CausticKey([
            [x, y, z, 0.0],
            u.patch_m,
            u.slope_variance,
            u.curvature_variance,
            [u.lod[0], u.modes[2] as f32, 0.0, 0.0],
        ])
    }
}

pub struct CausticMeansPass {
    /// Its image holds, per texel, the mean area ratio with one fixed-point step (r) and with
    /// none (g) (RGBA16F; the frame set's binding 8).
    pub fill: FrameSetImage,
    /// When to measure.
    schedule: Schedule,
}

/// When the means are measured ([`Schedule::due`]).
#[derive(Default)]
struct Schedule {
    /// What the image was last measured for (None: never, it holds 1).
    measured: Option<CausticKey>,
    /// What the frame being recorded asks (`want`), and the frame before it.
    wanted: Option<CausticKey>,
    before: Option<CausticKey>,
}

impl Schedule {
    fn want(&mut self, key: CausticKey) {
        self.before = self.wanted;
        self.wanted = Some(key);
    }

    fn due(&mut self) -> bool {
        let settled = self.measured.is_none() || self.before == self.wanted;
        let due = self.wanted.is_some() && self.measured != self.wanted && settled;
        if due {
            self.measured = self.wanted;
        }
        due
    }
}

impl CausticMeansPass {
    /// `ocean`: how the shader samples the ocean images (as the terrain's caustics do).
    pub fn new(
        ctx: &Arc<Context>,
        frame_layout: &DescriptorSetLayout,
        ocean: WaterKind,
    ) -> GpuResult<CausticMeansPass> {
        let extent = vk::Extent2D {
            width: CAUSTIC_MEAN_DEPTHS,
            height: CAUSTIC_MEAN_PIXELS,
        };
        let fill = FrameSetImage::new(
            ctx,
            frame_layout,
            "caustic means",
            extent,
            shaders::UNDERWATER_CAUSTIC_MEANS_FRAG,
            &[
                ocean.cascades,
                ocean.manual_filter as u32,
                0,
                0,
                0,
                0,
                ocean.slope_mips as u32,
            ],
        )?;
        Ok(CausticMeansPass {
            fill,
            schedule: Schedule::default(),
        })
    }

    /// What the frame being recorded needs the means for (from its uniforms).
    pub fn want(&mut self, key: CausticKey) {
        self.schedule.want(key);
    }

    /// Whether the means must be measured for the frame being recorded (and, if so, takes
    /// them as measured: the caller records [`Self::record`] in that frame): never measured,
    /// or measured for another key that has held for two frames. While a slider drags the sun
    /// the key changes every frame, and the means last measured serve until it stops (a
    /// measurement takes lavapipe a quarter to half a second).
    pub fn due(&mut self) -> bool {
        self.schedule.due()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_means_are_measured_first_and_again_once_a_change_has_held() {
        let key = |sun: f32| CausticKey([[sun, 0.0, 0.0, 0.0]; 5]);
        let mut s = Schedule::default();
        // Nothing asked yet (no frame has written its uniforms).
        assert!(!s.due());
        // The first frame with caustics measures; the same sea after it does not.
        s.want(key(1.0));
        assert!(s.due());
        s.want(key(1.0));
        assert!(!s.due());
        // A slider drags the sun: no measurement while the key changes every frame...
        for sun in [2.0, 3.0, 4.0] {
            s.want(key(sun));
            assert!(!s.due(), "dragged to {sun}");
        }
        // ...one when it has held for two frames, and none after.
        s.want(key(4.0));
        assert!(s.due());
        s.want(key(4.0));
        assert!(!s.due());
    }
}
