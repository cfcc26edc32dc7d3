//! The convergence widget as the deck writes it.

use serde::{Deserialize, Serialize};

use super::methods::{MethodRef, default_methods};
use super::ode::OdeSource;

/// `Convergence((ode: File("problems/forced.ron"), t_end: 4.0, methods: [Euler, Midpoint, Rk4,
/// Tableau("tableaux/rk4-typo.ron")]))`: error at `t_end` from the problem's start.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConvergenceSpec {
    pub ode: OdeSource,
    #[serde(default = "default_t_end")]
    pub t_end: f64,
    /// Largest step; each further point halves it.
    #[serde(default = "default_h_max")]
    pub h_max: f64,
    #[serde(default = "default_levels")]
    pub levels: usize,
    #[serde(default = "default_methods")]
    pub methods: Vec<MethodRef>,
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
