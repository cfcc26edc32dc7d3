//! The "off to Neptune" widget as the deck writes it.

use serde::{Deserialize, Serialize};

use super::methods::MethodRef;
use super::ode::OdeSource;

/// `Neptune((ode: File("problems/decay.ron"), h: 0.3, t_end: 4.0, methods: [Euler, Rk4]))`: the
/// first variable against t, with the axes held at the true solution's scale.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NeptuneSpec {
    pub ode: OdeSource,
    #[serde(default = "default_h")]
    pub h: f64,
    #[serde(default = "default_t_end")]
    pub t_end: f64,
    #[serde(default = "default_methods")]
    pub methods: Vec<MethodRef>,
}

pub fn default_h() -> f64 {
    0.3
}

pub fn default_t_end() -> f64 {
    6.0
}

pub fn default_methods() -> Vec<MethodRef> {
    vec![MethodRef::Builtin(crate::ode::Method::Euler)]
}
