//! The camera and the per-frame uniforms derived from it.
//!
//! Rendering is camera-relative (positions minus the camera position) so precision does not
//! degrade far from the origin; the projection is reversed-Z with an infinite far plane (depth 1
//! at the near plane, 0 at infinity: clear depth to 0, test GREATER).

use glam::{Mat4, Vec3, Vec4};

/// A perspective camera in world space (metres, y up).
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

    /// Camera-relative position -> clip space.
    pub fn view_proj(&self, aspect: f32) -> Mat4 {
        self.projection(aspect) * self.view_rotation()
    }
}

/// What the scene passes sample of the ocean simulation.
#[derive(Clone, Debug)]
pub struct OceanBindings {
    /// Per frame slot: displacement and normal+foam image views (GENERAL layout).
    pub displacement: Vec<ash::vk::ImageView>,
    pub normals: Vec<ash::vk::ImageView>,
    /// Patch side of each cascade (m), padded to four.
    pub patch_m: [f32; 4],
    pub cascades: u32,
}

/// Mirrors `shaders/common/frame.glsl` (std140: matrices and vec4s only, so no padding).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct FrameUniforms {
    pub view_proj: [[f32; 4]; 4],
    pub inv_view_proj: [[f32; 4]; 4],
    /// xyz: camera position (m); w: time (s).
    pub camera_pos: [f32; 4],
    /// xyz: unit vector toward the sun; w: sun radiance scale.
    pub sun_dir: [f32; 4],
    /// xy: target size (px); zw: reciprocal.
    pub viewport: [f32; 4],
    /// Patch side of each ocean cascade (m).
    pub patch_m: [f32; 4],
    /// x: number of cascades; y: 1 for a bounded window (Gerstner); zw: origin of the images (m).
    pub ocean: [f32; 4],
}

impl FrameUniforms {
    pub fn new(
        camera: &Camera,
        sun_dir: Vec3,
        sun_scale: f32,
        time_s: f32,
        size: (u32, u32),
        ocean: &OceanBindings,
        inputs: &super::renderer::FrameInputs,
    ) -> Self {
        let (w, h) = (size.0.max(1) as f32, size.1.max(1) as f32);
        let view_proj = camera.view_proj(w / h);
        FrameUniforms {
            view_proj: view_proj.to_cols_array_2d(),
            inv_view_proj: view_proj.inverse().to_cols_array_2d(),
            camera_pos: camera.position.extend(time_s).to_array(),
            sun_dir: sun_dir.normalize().extend(sun_scale).to_array(),
            viewport: Vec4::new(w, h, 1.0 / w, 1.0 / h).to_array(),
            patch_m: ocean.patch_m,
            ocean: [
                ocean.cascades as f32,
                if inputs.ocean_window { 1.0 } else { 0.0 },
                inputs.ocean_origin_m[0],
                inputs.ocean_origin_m[1],
            ],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
