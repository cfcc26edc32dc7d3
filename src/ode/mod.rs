//! The numerical heart: integrators for ẋ = f(x, t) over a state of `n` f64 values.
//!
//! No GPU or UI types here. Stepping is allocation-free: a stepper owns its scratch space,
//! sized once for the system's dimension.

pub mod adaptive;
pub mod explicit;
pub mod expr;
pub mod fixed;
pub mod implicit;
pub mod linalg;
pub mod method;
pub mod native;
pub mod pairs;
pub mod problem;
pub mod solve;
pub mod stability;
pub mod stability_box;
pub mod stability_fn;
pub mod stability_region;
pub mod stiff;
pub mod study;
pub mod symplectic;
pub mod system;
pub mod tableau;
pub mod trees;

pub use adaptive::{
    Adaptive, solve_adaptive, solve_embedded, solve_embedded_n, solve_embedded_n_with,
    solve_implicit_adaptive,
};
pub use explicit::ExplicitRk;
pub use fixed::{FixedFn, FixedSolution, FixedSystem, rk4_step, solve_fixed_n, solve_fixed_n_with};
pub use method::Method;
pub use solve::{
    Outcome, Scheme, Solution, Stepper, solve_fixed, solve_fixed_final, solve_tableau,
};
pub use stability::{Complex, real_axis_limit};
pub use system::{Counted, FnSystem, System};
pub use tableau::{OrderCondition, Tableau};
