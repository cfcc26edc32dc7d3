//! The numerical heart: integrators for ẋ = f(x, t) over a state of `n` f64 values.
//!
//! No GPU or UI types here. Stepping is allocation-free: a stepper owns its scratch space,
//! sized once for the system's dimension.

pub mod explicit;
pub mod system;
pub mod tableau;

pub use explicit::ExplicitRk;
pub use system::{FnSystem, System};
pub use tableau::Tableau;
