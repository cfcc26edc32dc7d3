//! The convergence widget as the deck writes it.

use serde::{Deserialize, Serialize};

use super::methods::MethodId;
use super::problems::Field1;

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConvergenceSpec {
    #[serde(default = "default_field")]
    pub field: Field1,
    #[serde(default = "default_x0")]
    pub x0: f64,
    #[serde(default = "default_t_end")]
    pub t_end: f64,
    /// Largest step; each further point halves it.
    #[serde(default = "default_h_max")]
    pub h_max: f64,
    #[serde(default = "default_levels")]
    pub levels: usize,
    #[serde(default = "default_methods")]
    pub methods: Vec<MethodId>,
    /// Also show the notes' RK4 with the k4 typo.
    #[serde(default)]
    pub typo: bool,
}

pub fn default_field() -> Field1 {
    Field1::Forced
}

pub fn default_x0() -> f64 {
    1.5
}

pub fn default_t_end() -> f64 {
    4.0
}

pub fn default_h_max() -> f64 {
    0.5
}

pub fn default_levels() -> usize {
    8
}

pub fn default_methods() -> Vec<MethodId> {
    vec![MethodId::Euler, MethodId::Midpoint, MethodId::Rk4]
}
