//! The Euler-spiral widget as the deck writes it.

use serde::{Deserialize, Serialize};

use super::methods::{MethodRef, default_methods};
use super::ode::OdeSource;

/// `Spiral((ode: File("problems/circle.ron"), h: 0.1, turns: 3.0))`: one phase-plane panel per
/// method over `turns` × 2π of time.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpiralSpec {
    pub ode: OdeSource,
    #[serde(default = "default_h")]
    pub h: f64,
    #[serde(default = "default_turns")]
    pub turns: f64,
    #[serde(default = "default_methods")]
    pub methods: Vec<MethodRef>,
    /// Draw the other methods' panels beside the first one's.
    #[serde(default = "yes")]
    pub compare: bool,
    /// Default `Equal`: the exact circle stays round.
    #[serde(default)]
    pub aspect: Option<super::Aspect>,
}

pub fn default_h() -> f64 {
    0.1
}

pub fn default_turns() -> f64 {
    3.0
}

pub fn yes() -> bool {
    true
}
