//! The slope-field / phase-plane widget as the deck writes it.

use serde::{Deserialize, Serialize};

use super::methods::{MethodRef, default_methods};
use super::ode::OdeSource;

/// `SlopeField((ode: File("problems/forced.ron"), h: 0.5, t_end: 8.0))`: a 1-D problem draws in
/// the t–x plane, more variables in the phase plane of the first two (or of `plot`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SlopeFieldSpec {
    pub ode: OdeSource,
    /// Where the paths start: (t₀, x₀) in the t–x plane, (x₀, y₀) in the phase plane. Default:
    /// the problem's `t0` and `initial`.
    #[serde(default)]
    pub start: Option<(f64, f64)>,
    #[serde(default = "default_h")]
    pub h: f64,
    /// End time of the integration (for 1-D problems, the right edge of the paths).
    pub t_end: f64,
    /// Visible window (x_min, x_max, y_min, y_max) in plot coordinates. Default: around the
    /// exact (or reference) path.
    #[serde(default)]
    pub view: Option<(f64, f64, f64, f64)>,
    #[serde(default = "default_methods")]
    pub methods: Vec<MethodRef>,
    /// Draw the exact solution (or a fine reference) too.
    #[serde(default = "yes")]
    pub exact: bool,
    /// Slope marks per axis.
    #[serde(default = "default_grid")]
    pub grid: usize,
    /// The two variables of the phase plane, e.g. `plot: Some(("x", "v"))`.
    #[serde(default)]
    pub plot: Option<(String, String)>,
    /// `aspect: Some(Equal)` for a phase plane whose axes share a unit; default `Free`: the
    /// plot fills its slot and shows exactly `view`.
    #[serde(default)]
    pub aspect: Option<super::Aspect>,
}

pub fn default_h() -> f64 {
    0.5
}

pub fn default_grid() -> usize {
    21
}

pub fn yes() -> bool {
    true
}
