//! The slope-field / phase-plane widget as the deck writes it.

use serde::{Deserialize, Serialize};

use super::problems::{Field1, Field2};

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum FieldKind {
    /// ẋ = f(x, t), drawn in the t–x plane; `start` is (t₀, x₀).
    OneD(Field1),
    /// (ẋ, ẏ) = f(x, y), drawn in the phase plane; `start` is (x₀, y₀).
    Phase(Field2),
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SlopeFieldSpec {
    pub field: FieldKind,
    pub start: (f64, f64),
    #[serde(default = "default_h")]
    pub h: f64,
    /// End of the integration: a time for both kinds (for `OneD`, the right edge of the path).
    pub t_end: f64,
    /// Visible window: (x_min, x_max, y_min, y_max) in plot coordinates.
    pub view: (f64, f64, f64, f64),
    #[serde(default = "yes")]
    pub euler: bool,
    #[serde(default = "yes")]
    pub midpoint: bool,
    #[serde(default = "yes")]
    pub rk4: bool,
    #[serde(default = "yes")]
    pub exact: bool,
    /// Slope marks per axis.
    #[serde(default = "default_grid")]
    pub grid: usize,
}

pub fn default_h() -> f64 {
    0.5
}

pub fn default_grid() -> usize {
    21
}

fn yes() -> bool {
    true
}
