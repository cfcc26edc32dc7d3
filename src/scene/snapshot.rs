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

pub const NEAR_M: f32 = 0.05;
pub const FAR_M: f32 = 300.0;

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
