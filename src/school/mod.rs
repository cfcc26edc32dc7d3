//! The school of fish: a particle system with boids steering and orientation by a discrete
//! parallel-transport frame. Fish are oriented particles, not rigid bodies.

use glam::{Quat, Vec3};
use serde::{Deserialize, Serialize};

/// What the renderer needs of one fish, per frame (the per-instance buffer's source).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FishInstance {
    pub position: Vec3,
    pub orientation: Quat,
    pub scale: f32,
    /// Phase of the tail beat / body wave, radians; the vertex shader animates with it.
    pub tail_phase: f32,
}

/// The school's parameters as written in a scene file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct SchoolParams {
    pub count: usize,
    pub seed: u64,
    pub min_speed: f32,
    pub max_speed: f32,
    pub separation_radius: f32,
    pub neighbour_radius: f32,
    pub separation_weight: f32,
    pub alignment_weight: f32,
    pub cohesion_weight: f32,
    pub bounds_weight: f32,
    pub flee_radius: f32,
    pub flee_weight: f32,
    pub fish_scale: f32,
}

impl Default for SchoolParams {
    fn default() -> Self {
        Self {
            count: 2000,
            seed: 7,
            min_speed: 0.6,
            max_speed: 2.0,
            separation_radius: 0.35,
            neighbour_radius: 1.2,
            separation_weight: 1.5,
            alignment_weight: 1.0,
            cohesion_weight: 0.8,
            bounds_weight: 2.0,
            flee_radius: 3.0,
            flee_weight: 4.0,
            fish_scale: 0.25,
        }
    }
}
