//! The work-precision widget as the deck writes it.

use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WorkPrecisionSpec {
    /// Integration interval length (the problem is the circle, exact solution known).
    #[serde(default = "default_t_end")]
    pub t_end: f64,
    /// Steps sizes: h = h_max / 2^k, k = 0..levels.
    #[serde(default = "default_levels")]
    pub levels: usize,
    #[serde(default = "yes")]
    pub rk5: bool,
}

pub fn default_t_end() -> f64 {
    10.0
}

pub fn default_levels() -> usize {
    10
}

fn yes() -> bool {
    true
}
