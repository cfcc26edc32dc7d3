//! The exercise widget as the deck writes it: fish oriented along a path by the Frenet frame
//! and by parallel transport, side by side, one transport step spelled out.

use serde::{Deserialize, Serialize};

pub use crate::school::frames::PathShape;

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParallelTransportSpec {
    /// Which path the fish follow (`StraightThenS`, `Helix`, `Loop`).
    #[serde(default)]
    pub path: PathShape,
    /// Fish along the path: one frame each, one transport step between neighbours.
    #[serde(default = "default_fish")]
    pub fish: usize,
    /// The transport step spelled out (from fish `step` to fish `step + 1`); `[`/`]` step.
    #[serde(default)]
    pub step: usize,
    /// The view: turn about the vertical axis, then tilt down (degrees); drag to orbit.
    #[serde(default = "default_yaw")]
    pub yaw_deg: f64,
    #[serde(default = "default_pitch")]
    pub pitch_deg: f64,
}

pub const FISH_RANGE: (usize, usize) = (6, 60);
pub const PITCH_RANGE_DEG: (f64, f64) = (-89.0, 89.0);

pub fn default_fish() -> usize {
    18
}
pub fn default_yaw() -> f64 {
    -25.0
}
pub fn default_pitch() -> f64 {
    50.0
}

impl Default for ParallelTransportSpec {
    fn default() -> Self {
        Self {
            path: PathShape::default(),
            fish: default_fish(),
            step: 0,
            yaw_deg: default_yaw(),
            pitch_deg: default_pitch(),
        }
    }
}
