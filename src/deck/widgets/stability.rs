//! The stability-region widget as the deck writes it.

use serde::{Deserialize, Serialize};

use super::methods::MethodId;
use crate::ode::Tableau;

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StabilitySpec {
    #[serde(default = "default_methods")]
    pub methods: Vec<MethodId>,
    /// Further methods, e.g. written out in the deck: `(name: "Ralston", a: [...], b: [...], c: [...])`.
    #[serde(default)]
    pub tableaux: Vec<Tableau>,
    /// Tableau files (RON, as `lectern solve` reads them), relative to the deck's folder,
    /// e.g. `["tableaux/rk4-typo.ron"]`.
    #[serde(default)]
    pub files: Vec<String>,
    /// Visible window (re_min, re_max, im_min, im_max).
    #[serde(default = "default_view")]
    pub view: (f64, f64, f64, f64),
    /// Show z = hλ for this λ (e.g. the oscillator's ±i) as a marker moving with h.
    #[serde(default)]
    pub lambda: Option<(f64, f64)>,
    #[serde(default = "default_h")]
    pub h: f64,
}

pub fn default_methods() -> Vec<MethodId> {
    vec![MethodId::Euler, MethodId::Midpoint, MethodId::Rk4]
}

pub fn default_view() -> (f64, f64, f64, f64) {
    (-3.5, 1.5, -3.0, 3.0)
}

pub fn default_h() -> f64 {
    1.0
}
