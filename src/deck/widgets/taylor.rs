//! The Taylor-series widget as the deck writes it.

use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum TaylorFn {
    Sin,
    Cos,
    Exp,
    /// ln(1 + x), radius of convergence 1.
    Log1p,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TaylorSpec {
    #[serde(default = "default_fn")]
    pub function: TaylorFn,
    /// Expansion point.
    #[serde(default)]
    pub a: f64,
    /// Highest order drawn (all orders 1..=order are shown).
    #[serde(default = "default_order")]
    pub order: usize,
    /// Visible t range.
    #[serde(default = "default_range")]
    pub range: (f64, f64),
}

pub fn default_fn() -> TaylorFn {
    TaylorFn::Sin
}

pub fn default_order() -> usize {
    4
}

pub fn default_range() -> (f64, f64) {
    (-4.0, 4.0)
}
