//! The stability-region widget as the deck writes it.

use serde::{Deserialize, Serialize};

use super::methods::{MethodRef, default_methods};
use crate::ode::Tableau;

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StabilitySpec {
    #[serde(default = "default_methods")]
    /// Built-ins and tableau files: `[Euler, Midpoint, Rk4, Tableau("tableaux/rk4-typo.ron")]`.
    pub methods: Vec<MethodRef>,
    /// Further methods, e.g. written out in the deck: `(name: "Ralston", a: [...], b: [...], c: [...])`.
    #[serde(default)]
    pub tableaux: Vec<Tableau>,
    /// Visible window (re_min, re_max, im_min, im_max). Default: fitted to the regions (each
    /// computed whole, `ode::stability_region`; an implicit method's unbounded region by its
    /// boundary curve), with the origin.
    #[serde(default)]
    pub view: Option<(f64, f64, f64, f64)>,
    /// Show z = hλ for this λ (e.g. the oscillator's ±i) as a marker moving with h.
    #[serde(default)]
    pub lambda: Option<(f64, f64)>,
    #[serde(default = "default_h")]
    pub h: f64,
    /// Default `Equal`: one unit is as long on both axes (circles stay round); the fitted
    /// box's short side is padded to the plot's shape at most up to its long side, and the
    /// plot leaves the rest of its slot blank. `Free`: the plot fills its slot showing exactly
    /// the fitted box (or `view`).
    #[serde(default)]
    pub aspect: Option<super::Aspect>,
}

pub fn default_h() -> f64 {
    1.0
}
