//! The step-construction widget as the deck writes it.

use serde::{Deserialize, Serialize};

use super::methods::MethodId;
use super::problems::Field1;

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StepSpec {
    #[serde(default = "default_field")]
    pub field: Field1,
    #[serde(default = "default_start")]
    pub start: (f64, f64),
    #[serde(default = "default_h")]
    pub h: f64,
    /// Euler, Midpoint or Rk4.
    #[serde(default = "default_method")]
    pub method: MethodId,
    /// How far the construction is shown: 0 = just the start, `stages(method)` = complete.
    #[serde(default)]
    pub stage: usize,
}

pub fn default_field() -> Field1 {
    Field1::Forced
}

pub fn default_start() -> (f64, f64) {
    (0.0, 1.5)
}

pub fn default_h() -> f64 {
    1.5
}

pub fn default_method() -> MethodId {
    MethodId::Rk4
}
