//! The methods a widget can compare, by name (the widgets map them onto the numerics core).

use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum MethodId {
    Euler,
    Midpoint,
    Heun,
    Rk4,
    /// The lecture notes' RK4 with the typo `k4 = h f(x0 + k3/2)` (ERRATA 1): order drops.
    Rk4Typo,
    /// The exact solution (or a fine reference), drawn for comparison.
    Exact,
}
