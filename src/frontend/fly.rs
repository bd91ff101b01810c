//! The window's fly camera: W/S forward and back, A/D sideways, Q/E down and up, Shift 4x
//! faster, left mouse drag to look around. Pure state (no winit types), so it is unit-tested.

use glam::Vec3;

use crate::render::Camera;

/// Speed without Shift (m/s).
pub const SPEED_M_S: f32 = 12.0;
/// Speed factor with Shift held.
pub const FAST: f32 = 4.0;
/// Look rotation per dragged pixel (radians).
pub const LOOK_RAD_PER_PX: f32 = 0.004;
/// The camera goes no lower than this (m): it may dive under the water.
pub const MIN_HEIGHT_M: f32 = crate::render::camera::LOWEST_M;

/// The movement keys, in the order of `FlyCamera::held`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Move {
    Forward,
    Back,
    Left,
    Right,
    Down,
    Up,
    Fast,
}

#[derive(Clone, Debug, Default)]
pub struct FlyCamera {
    held: [bool; 7],
    dragging: bool,
    last_cursor: Option<(f64, f64)>,
    /// Look rotation not yet applied: (yaw, pitch) in radians.
    pending_look: (f32, f32),
}

impl FlyCamera {
    pub fn key(&mut self, m: Move, pressed: bool) {
        self.held[m as usize] = pressed;
    }

    /// Left mouse button pressed or released.
    pub fn drag(&mut self, pressed: bool) {
        self.dragging = pressed;
        self.last_cursor = None;
    }

    /// Cursor moved to (x, y) px: while dragging, the view turns with it.
    pub fn cursor(&mut self, x: f64, y: f64) {
        if self.dragging {
            if let Some((lx, ly)) = self.last_cursor {
                self.pending_look.0 += (x - lx) as f32 * LOOK_RAD_PER_PX;
                self.pending_look.1 -= (y - ly) as f32 * LOOK_RAD_PER_PX;
            }
            self.last_cursor = Some((x, y));
        }
    }

    /// Focus lost: release everything (no key stays stuck down).
    pub fn release_all(&mut self) {
        *self = FlyCamera::default();
    }

    /// Moves and turns `camera` for a frame of `dt` seconds.
    pub fn update(&mut self, camera: &mut Camera, dt: f32) {
        let (yaw, pitch) = std::mem::take(&mut self.pending_look);
        if yaw != 0.0 || pitch != 0.0 {
            let f = camera.forward;
            let cur_yaw = f.z.atan2(f.x) + yaw;
            let cur_pitch = (f.y.asin() + pitch).clamp(-1.5, 1.5);
            camera.forward = Vec3::new(
                cur_pitch.cos() * cur_yaw.cos(),
                cur_pitch.sin(),
                cur_pitch.cos() * cur_yaw.sin(),
            );
        }
        let h = |m: Move| if self.held[m as usize] { 1.0 } else { 0.0 };
        let flat = Vec3::new(camera.forward.x, 0.0, camera.forward.z).normalize_or_zero();
        let right = flat.cross(Vec3::Y);
        let dir = camera.forward * (h(Move::Forward) - h(Move::Back))
            + right * (h(Move::Right) - h(Move::Left))
            + Vec3::Y * (h(Move::Up) - h(Move::Down));
        let speed = SPEED_M_S
            * if self.held[Move::Fast as usize] {
                FAST
            } else {
                1.0
            };
        camera.position += dir * speed * dt.clamp(0.0, 0.25);
        camera.position.y = camera.position.y.max(MIN_HEIGHT_M);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_move_and_drag_turns() {
        let mut fly = FlyCamera::default();
        let mut cam = Camera::default();
        let start = cam.position;
        fly.key(Move::Forward, true);
        fly.update(&mut cam, 1.0 / 4.0);
        let moved = cam.position - start;
        assert!((moved.length() - SPEED_M_S / 4.0).abs() < 1e-3);
        assert!(moved.dot(cam.forward) > 0.0);
        fly.key(Move::Forward, false);
        fly.key(Move::Fast, true);
        fly.key(Move::Up, true);
        let y = cam.position.y;
        fly.update(&mut cam, 0.1);
        assert!((cam.position.y - y - SPEED_M_S * FAST * 0.1).abs() < 1e-3);
        // Down stops at the lowest height (under the water).
        fly.release_all();
        fly.key(Move::Down, true);
        for _ in 0..400 {
            fly.update(&mut cam, 0.25);
        }
        assert_eq!(cam.position.y, MIN_HEIGHT_M);
        // Dragging right turns right (toward +x from -z).
        let before = cam.forward;
        fly.drag(true);
        fly.cursor(100.0, 100.0);
        fly.cursor(200.0, 100.0);
        fly.update(&mut cam, 0.0);
        assert!(
            cam.forward.x > before.x + 0.3,
            "{before} -> {}",
            cam.forward
        );
        assert!((cam.forward.length() - 1.0).abs() < 1e-5);
    }
}
