//! The step-construction widget as the deck writes it.

use serde::{Deserialize, Serialize};

use super::methods::MethodRef;
use super::ode::OdeSource;

/// `StepConstruction((ode: File("problems/forced.ron"), method: Rk4, h: 1.5, stage: 2))`, for a
/// 1-D problem.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StepSpec {
    pub ode: OdeSource,
    /// (t₀, x₀); default: the problem's `t0` and `initial`.
    #[serde(default)]
    pub start: Option<(f64, f64)>,
    #[serde(default = "default_h")]
    pub h: f64,
    /// Euler, Midpoint or Rk4 (others are drawn as RK4's construction).
    #[serde(default = "default_method")]
    pub method: MethodRef,
    /// How far the construction is shown: 0 = just the start, `stages(method)` = complete.
    #[serde(default)]
    pub stage: usize,
}

pub fn default_h() -> f64 {
    1.5
}

pub fn default_method() -> MethodRef {
    MethodRef::Builtin(crate::ode::Method::Rk4)
}
