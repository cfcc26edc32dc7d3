//! The scene's simulation step: time, the fish school, and the floating bodies riding the
//! waves. It produces a [`FrameSnapshot`] for the renderer and knows nothing of the GPU.

use glam::{Quat, Vec3};

use crate::school::FishInstance;

use super::model::{Object, Scene, Shape};
use super::orbit::OrbitCamera;
use super::snapshot::{BodyPose, FrameSnapshot};
use super::surface;

pub struct SceneSim {
    pub scene: Scene,
    pub camera: OrbitCamera,
    time_secs: f64,
}

impl SceneSim {
    pub fn new(scene: Scene) -> Self {
        Self {
            camera: OrbitCamera::from_scene(&scene.camera),
            scene,
            time_secs: 0.0,
        }
    }

    pub fn time_secs(&self) -> f64 {
        self.time_secs
    }

    /// Jumps to an absolute time (deterministic renders at `--time T`).
    pub fn set_time(&mut self, time_secs: f64) {
        self.time_secs = time_secs;
    }

    pub fn step(&mut self, dt_secs: f64) {
        self.time_secs += dt_secs.clamp(0.0, 0.1);
    }

    /// A reloaded scene replaces the model; camera and time stay where the lecturer left them.
    pub fn replace_scene(&mut self, scene: Scene) {
        self.scene = scene;
    }

    pub fn snapshot(&self) -> FrameSnapshot {
        let t = self.time_secs as f32;
        FrameSnapshot {
            time_secs: t,
            camera: self.camera.pose(),
            fish: school_instances(&self.scene, t),
            bodies: body_poses(&self.scene, t),
        }
    }
}

/// Deterministic hash in [0, 1).
fn hash01(i: u32, salt: u32) -> f32 {
    let mut x = i.wrapping_mul(0x9E37_79B9) ^ salt.wrapping_mul(0x85EB_CA6B);
    x ^= x >> 16;
    x = x.wrapping_mul(0x7FEB_352D);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846C_A68B);
    x ^= x >> 16;
    (x >> 8) as f32 / (1u32 << 24) as f32
}

/// A milling school (fish circling a common centre, the torus formation of real schools),
/// evaluated in closed form so any time renders without stepping from zero.
pub fn school_instances(scene: &Scene, t: f32) -> Vec<FishInstance> {
    let p = &scene.school;
    let depth = scene.seabed_depth();
    let level = scene.water.level;
    let salt = p.seed as u32;
    (0..p.count as u32)
        .map(|i| {
            let r = 1.5 + 3.0 * hash01(i, salt);
            let speed = p.min_speed + (p.max_speed - p.min_speed) * hash01(i, salt + 1);
            let phase0 = std::f32::consts::TAU * hash01(i, salt + 2);
            let y0 = level - depth * (0.3 + 0.45 * hash01(i, salt + 3));
            let theta = phase0 + speed / r * t;
            let bob = 0.15 * (0.7 * t + 6.0 * hash01(i, salt + 4)).sin();
            let position = Vec3::new(r * theta.cos(), y0 + bob, r * theta.sin());
            // counter-clockwise seen from above: heading is d/dθ of the circle
            let heading = Vec3::new(-theta.sin(), 0.0, theta.cos());
            let orientation = Quat::from_rotation_arc(Vec3::X, heading);
            FishInstance {
                position,
                orientation,
                scale: p.fish_scale * (0.8 + 0.4 * hash01(i, salt + 5)),
                tail_phase: 8.0 * t * (0.8 + 0.4 * hash01(i, salt + 6)) + phase0 * 3.0,
            }
        })
        .collect()
}

/// Floating bodies sit on the surface at their (x, z), tilted with its normal.
pub fn body_poses(scene: &Scene, t: f32) -> Vec<BodyPose> {
    scene
        .objects
        .iter()
        .enumerate()
        .filter_map(|(i, o)| match o {
            Object::Floating {
                position,
                draft,
                shape,
                ..
            } => {
                let (h, n) = surface::height_and_normal(&scene.water, position[0], position[1], t);
                let half_height = match shape {
                    Shape::Box { size } => size[1] * 0.5,
                    Shape::Sphere { radius } => *radius,
                    Shape::Capsule { radius, .. } => *radius,
                };
                let tilt = Quat::from_rotation_arc(Vec3::Y, n);
                let yaw = Quat::from_rotation_y(0.7 * i as f32 + 0.05 * t);
                Some(BodyPose {
                    object_index: i,
                    position: Vec3::new(position[0], h + half_height * 0.3 - draft, position[1]),
                    orientation: tilt * yaw,
                })
            }
            _ => None,
        })
        .collect()
}
