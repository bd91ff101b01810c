//! The camera: position, orientation, reversed-Z projection. The per-frame uniforms derived
//! from it are `uniforms.rs`.
//!
//! Rendering is camera-relative (positions minus the camera position) so precision does not
//! degrade far from the origin; the projection is reversed-Z with an infinite far plane (depth 1
//! at the near plane, 0 at infinity: clear depth to 0, test GREATER).

use glam::{Mat4, Vec3, Vec4};

/// A perspective camera in world space (metres, y up).
/// The lowest a camera may go (m): under the water from 0 down (the view from below); past
/// 60 m the water has swallowed the daylight.
pub const LOWEST_M: f32 = -60.0;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub position: Vec3,
    /// Unit view direction.
    pub forward: Vec3,
    pub fov_y_deg: f32,
    pub near_m: f32,
}

impl Default for Camera {
    /// 12 m above the water, looking toward the horizon, tilted 4.6 degrees down.
    fn default() -> Self {
        Camera {
            position: Vec3::new(0.0, 12.0, 0.0),
            forward: Vec3::new(0.0, -0.08, -1.0).normalize(),
            fov_y_deg: 60.0,
            near_m: 0.1,
        }
    }
}

impl Camera {
    /// A camera at `position` looking at `target` (`None` if they coincide or the view is
    /// straight up or down, where the horizon has no direction).
    pub fn looking_at(position: Vec3, target: Vec3) -> Option<Camera> {
        let forward = (target - position).normalize_or_zero();
        if forward == Vec3::ZERO || forward.cross(Vec3::Y).length() < 1e-4 {
            return None;
        }
        Some(Camera {
            position,
            forward,
            ..Camera::default()
        })
    }

    /// Rotation-only view matrix (camera-relative rendering).
    pub fn view_rotation(&self) -> Mat4 {
        Mat4::look_to_rh(Vec3::ZERO, self.forward, Vec3::Y)
    }

    /// Reversed-Z, infinite-far projection for Vulkan (clip y points down, depth in [0, 1]).
    pub fn projection(&self, aspect: f32) -> Mat4 {
        let mut p =
            Mat4::perspective_infinite_reverse_rh(self.fov_y_deg.to_radians(), aspect, self.near_m);
        p.y_axis.y = -p.y_axis.y;
        p
    }

    /// The focal length in pixels of a target `height_px` high: |P[1][1]| = 1 / tan(fov/2),
    /// times half the height (a length L at distance d spans L · focal / d pixels).
    pub fn focal_px(&self, aspect: f32, height_px: f32) -> f32 {
        self.projection(aspect).y_axis.y.abs() * height_px * 0.5
    }

    /// Where the ray through `ndc` (x right, y down, −1 to 1) of a view of `aspect` meets the
    /// water plane y = `level` (world x, z): `None` at or above the horizon, or past `max_m`.
    pub fn water_point(
        &self,
        ndc: [f32; 2],
        aspect: f32,
        level: f32,
        max_m: f32,
    ) -> Option<[f32; 2]> {
        // Camera-relative: view_proj holds no translation.
        let p = self.view_proj(aspect).inverse() * Vec4::new(ndc[0], ndc[1], 0.5, 1.0);
        let dir = (p.truncate() / p.w).normalize();
        if dir.y > -1e-4 {
            return None;
        }
        let t = (level - self.position.y) / dir.y;
        (t > 0.0 && t <= max_m)
            .then_some([self.position.x + t * dir.x, self.position.z + t * dir.z])
    }

    /// `water_point` of the centre of pixel (`x`, `y`) (from the top left) of a picture `w` by
    /// `h` pixels, on the mean water level (y = 0): where the tests' pictures look.
    pub fn pixel_water_point(
        &self,
        (x, y): (usize, usize),
        (w, h): (usize, usize),
        max_m: f32,
    ) -> Option<[f32; 2]> {
        let ndc = [
            (x as f32 + 0.5) / w as f32 * 2.0 - 1.0,
            (y as f32 + 0.5) / h as f32 * 2.0 - 1.0,
        ];
        self.water_point(ndc, w as f32 / h as f32, 0.0, max_m)
    }

    /// Camera-relative position -> clip space.
    pub fn view_proj(&self, aspect: f32) -> Mat4 {
        self.projection(aspect) * self.view_rotation()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_water_under_a_pixel() {
        // 12 m up, forward (0, -0.08, -1): the centre ray meets the water 12/0.08 = 150 m ahead.
        let cam = Camera::default();
        let aspect = 16.0 / 9.0;
        let centre = cam.water_point([0.0, 0.0], aspect, 0.0, 1e4).unwrap();
        assert!(
            centre[0].abs() < 1e-3 && (centre[1] + 150.0).abs() < 0.1,
            "{centre:?}"
        );
        // Lower in the picture is nearer (Vulkan's y points down); right is +x.
        let near = cam.water_point([0.5, 0.8], aspect, 0.0, 1e4).unwrap();
        assert!(
            near[1] > -30.0 && near[1] < -10.0 && near[0] > 0.0,
            "{near:?}"
        );
        // Above the horizon, and past the range: none.
        assert_eq!(cam.water_point([0.0, -0.8], aspect, 0.0, 1e4), None);
        assert_eq!(cam.water_point([0.0, 0.0], aspect, 0.0, 100.0), None);
    }

    #[test]
    fn reversed_z_maps_near_to_one_and_far_to_zero() {
        let cam = Camera::default();
        let vp = cam.view_proj(16.0 / 9.0);
        let near = vp * (cam.forward * cam.near_m).extend(1.0);
        let far = vp * (cam.forward * 1.0e7).extend(1.0);
        assert!(
            (near.z / near.w - 1.0).abs() < 1e-4,
            "near depth {}",
            near.z / near.w
        );
        assert!(
            far.z / far.w < 1e-6 && far.z / far.w >= 0.0,
            "far depth {}",
            far.z / far.w
        );
    }

    #[test]
    fn up_is_up_on_screen() {
        // Vulkan clip y points down: a point above the view axis has negative y.
        let cam = Camera::default();
        let vp = cam.view_proj(1.0);
        let above = vp * (cam.forward * 10.0 + Vec3::Y).extend(1.0);
        assert!(above.y / above.w < 0.0);
    }
}
