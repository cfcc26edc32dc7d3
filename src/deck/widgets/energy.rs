//! The energy widget as the deck writes it: several methods on one mechanical system, the
//! energy of each path against t, with the work each method did.

use serde::{Deserialize, Serialize};

use super::methods::MethodRef;
use super::ode::OdeSource;

/// `Energy((ode: File("problems/stiff-spring.ron"), energy: "0.5*v*v + 0.5*k*x*x", h: 0.1,
/// t_end: 10.0, methods: [Euler, Rk4, ImplicitEuler, ImplicitMidpoint, Radau5]))`: fixed-step
/// methods step with `h`, adaptive ones (`Radau5`, `Rodas5p`, the embedded pairs) choose their
/// own steps at `rtol`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnergySpec {
    pub ode: OdeSource,
    /// The energy as an expression of the variables, `t` and the equation's parameters.
    pub energy: String,
    #[serde(default = "default_h")]
    pub h: f64,
    #[serde(default = "default_t_end")]
    pub t_end: f64,
    #[serde(default = "default_methods")]
    pub methods: Vec<MethodRef>,
    /// Relative tolerance of the adaptive methods (absolute: a thousandth of it).
    #[serde(default = "default_rtol")]
    pub rtol: f64,
}

pub fn default_h() -> f64 {
    0.1
}

pub fn default_t_end() -> f64 {
    10.0
}

pub fn default_rtol() -> f64 {
    1e-6
}

pub fn default_methods() -> Vec<MethodRef> {
    use crate::ode::Method;
    [
        Method::Euler,
        Method::Rk4,
        Method::ImplicitEuler,
        Method::ImplicitMidpoint,
        Method::Radau5,
    ]
    .map(MethodRef::Builtin)
    .into()
}
