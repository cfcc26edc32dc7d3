//! The Euler-spiral widget as the deck writes it.

use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpiralSpec {
    #[serde(default = "default_h")]
    pub h: f64,
    #[serde(default = "default_turns")]
    pub turns: f64,
    /// Draw the midpoint and RK4 panels beside Euler's.
    #[serde(default = "yes")]
    pub compare: bool,
}

pub fn default_h() -> f64 {
    0.1
}

pub fn default_turns() -> f64 {
    3.0
}

fn yes() -> bool {
    true
}
