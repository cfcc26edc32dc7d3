//! The "off to Neptune" widget as the deck writes it.

use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum NeptuneProblem {
    /// y' = λy with real λ < 0 (e.g. −5): decays; explicit methods blow up beyond their limit.
    Decay { lambda: f64 },
    /// x'' = −x: every Euler step gains energy; RK4 holds up to h = 2√2.
    Oscillator,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NeptuneSpec {
    pub problem: NeptuneProblem,
    #[serde(default = "default_h")]
    pub h: f64,
    #[serde(default = "default_t_end")]
    pub t_end: f64,
    #[serde(default = "yes")]
    pub euler: bool,
    #[serde(default)]
    pub midpoint: bool,
    #[serde(default)]
    pub rk4: bool,
}

pub fn default_h() -> f64 {
    0.3
}

pub fn default_t_end() -> f64 {
    6.0
}

fn yes() -> bool {
    true
}
