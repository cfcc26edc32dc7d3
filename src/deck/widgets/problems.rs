//! The built-in right-hand sides the plot widgets draw (the widgets give them their maths).

use serde::{Deserialize, Serialize};

/// A 1-D problem ẋ = f(x, t), drawn in the t–x plane.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Field1 {
    /// ẋ = −k x: decay, x = x₀ e^{−k(t−t₀)}.
    Decay { k: f64 },
    /// ẋ = x (1 − x): logistic growth.
    Logistic,
    /// ẋ = cos t − x: a forced, damped response (the classic textbook slope field).
    Forced,
    /// ẋ = t − x² (no closed form; reference is fine RK4).
    Riccati,
}

/// A 2-D problem (ẋ, ẏ) = f(x, y), drawn in the phase plane.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Field2 {
    /// (ẋ, ẏ) = (−y, x): circles, the picture Euler turns into a spiral.
    Circle,
    /// x'' = −x − c x': a damped oscillator.
    Damped { c: f64 },
    /// x'' = −sin x: the pendulum (reference is fine RK4).
    Pendulum,
    /// Van der Pol, μ: a limit cycle (reference is fine RK4).
    VanDerPol { mu: f64 },
}
