//! The work-precision widget as the deck writes it.

use serde::{Deserialize, Serialize};

use super::methods::{MethodRef, default_methods};
use super::ode::OdeSource;

/// `WorkPrecision((ode: File("problems/circle.ron"), t_end: 10.0, levels: 10, rk5: true))`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WorkPrecisionSpec {
    pub ode: OdeSource,
    /// Integration from the problem's t0 to this time.
    #[serde(default = "default_t_end")]
    pub t_end: f64,
    /// Step sizes: h = 1 / 2^k, k = 0..levels.
    #[serde(default = "default_levels")]
    pub levels: usize,
    #[serde(default = "default_methods")]
    pub methods: Vec<MethodRef>,
    /// Also Dormand–Prince's fifth-order weights as a fixed-step method.
    #[serde(default = "yes")]
    pub rk5: bool,
}

pub fn default_t_end() -> f64 {
    10.0
}

pub fn default_levels() -> usize {
    10
}

pub fn yes() -> bool {
    true
}
