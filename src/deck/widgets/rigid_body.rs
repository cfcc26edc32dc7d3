//! The tumbling-rigid-body widget as the deck writes it.

use serde::{Deserialize, Serialize};

use crate::rigid::Integrator;

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RigidBodySpec {
    /// Principal moments of the body (the diag(1, 2, 3)).
    #[serde(default = "default_i")]
    pub inertia: (f64, f64, f64),
    /// Initial angular velocity in body axes: mostly about the intermediate axis.
    #[serde(default = "default_omega")]
    pub omega0: (f64, f64, f64),
    #[serde(default = "default_h")]
    pub h: f64,
    /// Simulated time shown (advances while `playing`).
    #[serde(default)]
    pub t: f64,
    #[serde(default = "yes")]
    pub playing: bool,
    /// Simulated seconds per real second.
    #[serde(default = "default_speed")]
    pub speed: f64,
    /// Points per axis for the inertia approximation.
    #[serde(default = "default_n")]
    pub n: usize,
    /// The integrators shown side by side, in this order.
    #[serde(default = "default_methods")]
    pub methods: Vec<Integrator>,
}

pub fn default_i() -> (f64, f64, f64) {
    (1.0, 2.0, 3.0)
}

pub fn default_omega() -> (f64, f64, f64) {
    (0.02, 2.0, 0.02)
}

pub fn default_h() -> f64 {
    0.02
}

pub fn default_speed() -> f64 {
    2.0
}

pub fn default_n() -> usize {
    4
}

pub fn default_methods() -> Vec<Integrator> {
    Integrator::ALL.to_vec()
}

fn yes() -> bool {
    true
}
