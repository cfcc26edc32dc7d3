//! What the renderer reads each frame: plain data, extracted from the simulation (Bevy's
//! "extract" step). The renderer never sees or mutates the simulation itself.

use glam::{Mat4, Quat, Vec3};

use crate::school::FishInstance;

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CameraPose {
    pub eye: Vec3,
    pub target: Vec3,
    pub fov_y_rad: f32,
}

impl CameraPose {
    pub fn view_from_world(&self) -> Mat4 {
        glam::camera::rh::view::look_at_mat4(self.eye, self.target, Vec3::Y)
    }

    /// Reverse-free, 0..1 depth (wgpu convention).
    pub fn clip_from_view(&self, aspect: f32) -> Mat4 {
        glam::camera::rh::proj::directx::perspective(self.fov_y_rad, aspect, NEAR_M, FAR_M)
    }
}

impl CameraPose {
    /// Where the ray through the screen point `ndc` (x right, y up, both −1..1) meets the
    /// horizontal plane y = `height`, if it does in front of the camera (click on the water).
    pub fn pick_plane(&self, ndc: glam::Vec2, aspect: f32, height: f32) -> Option<Vec3> {
        let world_from_clip = (self.clip_from_view(aspect) * self.view_from_world()).inverse();
        let far = world_from_clip.project_point3(Vec3::new(ndc.x, ndc.y, 1.0));
        let dir = (far - self.eye).try_normalize()?;
        if dir.y.abs() < 1e-6 {
            return None;
        }
        let s = (height - self.eye.y) / dir.y;
        (s > 0.0 && s.is_finite()).then(|| self.eye + dir * s)
    }

    /// Screen position (ndc, y up) of a world point in front of the camera.
    pub fn project(&self, p_world: Vec3, aspect: f32) -> Option<glam::Vec2> {
        let clip = self.clip_from_view(aspect) * self.view_from_world() * p_world.extend(1.0);
        (clip.w > 1e-6).then(|| glam::Vec2::new(clip.x, clip.y) / clip.w)
    }
}

pub const NEAR_M: f32 = 0.05;
/// Far enough that the water's projected grid ends a pixel below the horizon.
pub const FAR_M: f32 = 2000.0;

/// Pose of one floating body (an `Object::Floating`, by index into `Scene::objects`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyPose {
    pub object_index: usize,
    pub position: Vec3,
    pub orientation: Quat,
}

#[derive(Debug, Clone, PartialEq)]
pub struct FrameSnapshot {
    pub time_secs: f32,
    pub camera: CameraPose,
    pub fish: Vec<FishInstance>,
    pub bodies: Vec<BodyPose>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn picking_the_plane_inverts_projection() {
        let cam = CameraPose {
            eye: Vec3::new(3.0, 5.0, 8.0),
            target: Vec3::new(0.0, -1.0, 0.0),
            fov_y_rad: 0.9,
        };
        let p = Vec3::new(1.5, 0.0, -2.0);
        let ndc = cam.project(p, 1.6).unwrap();
        let back = cam.pick_plane(ndc, 1.6, 0.0).unwrap();
        assert!((back - p).length() < 1e-3, "{back}");
        // looking up from below the plane, away from it: no hit
        let up = CameraPose {
            eye: Vec3::new(0.0, 1.0, 0.0),
            target: Vec3::new(0.0, 5.0, 1.0),
            fov_y_rad: 0.9,
        };
        assert!(up.pick_plane(glam::Vec2::ZERO, 1.0, 0.0).is_none());
    }
}
