//! Butcher tableaux of explicit Runge–Kutta methods.

use serde::{Deserialize, Serialize};

/// An explicit Runge–Kutta method: `k_i = f(x + h Σ_j<i a_ij k_j, t + c_i h)`,
/// `x(t+h) = x + h Σ b_i k_i`. `a` is stored as full rows; entries on or above the diagonal
/// must be zero (explicit).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Tableau {
    pub name: String,
    pub a: Vec<Vec<f64>>,
    pub b: Vec<f64>,
    pub c: Vec<f64>,
}

impl Tableau {
    pub fn stages(&self) -> usize {
        self.b.len()
    }

    /// Forward Euler: one stage, order 1.
    pub fn euler() -> Self {
        Self {
            name: "Euler".into(),
            a: vec![vec![0.0]],
            b: vec![1.0],
            c: vec![0.0],
        }
    }

    /// The midpoint method, x + h f(x + h/2 f(x), t + h/2) (ERRATA 3): order 2.
    pub fn midpoint() -> Self {
        Self {
            name: "Midpoint".into(),
            a: vec![vec![0.0, 0.0], vec![0.5, 0.0]],
            b: vec![0.0, 1.0],
            c: vec![0.0, 0.5],
        }
    }

    /// Heun's method (explicit trapezoid): order 2.
    pub fn heun() -> Self {
        Self {
            name: "Heun".into(),
            a: vec![vec![0.0, 0.0], vec![1.0, 0.0]],
            b: vec![0.5, 0.5],
            c: vec![0.0, 1.0],
        }
    }

    /// Classical RK4 (ERRATA 1: the last stage samples at x + k3, t + h).
    pub fn rk4() -> Self {
        Self {
            name: "RK4".into(),
            a: vec![
                vec![0.0, 0.0, 0.0, 0.0],
                vec![0.5, 0.0, 0.0, 0.0],
                vec![0.0, 0.5, 0.0, 0.0],
                vec![0.0, 0.0, 1.0, 0.0],
            ],
            b: vec![1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0],
            c: vec![0.0, 0.5, 0.5, 1.0],
        }
    }
}
