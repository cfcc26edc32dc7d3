//! The methods the widgets compare, mapped onto the project's integrators (`ode::Tableau` +
//! `ode::ExplicitRk`), and fixed-step paths that stop cleanly when a solution blows up.

use serde::{Deserialize, Serialize};

use crate::ode::{ExplicitRk, System, Tableau};

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

impl MethodId {
    pub const INTEGRATORS: [MethodId; 3] = [MethodId::Euler, MethodId::Midpoint, MethodId::Rk4];

    pub fn name(self) -> &'static str {
        match self {
            MethodId::Euler => "Euler",
            MethodId::Midpoint => "Midpoint",
            MethodId::Heun => "Heun",
            MethodId::Rk4 => "RK4",
            MethodId::Rk4Typo => "RK4 (notes' typo)",
            MethodId::Exact => "exact",
        }
    }

    /// The Butcher tableau; `None` for `Exact`.
    pub fn tableau(self) -> Option<Tableau> {
        Some(match self {
            MethodId::Euler => Tableau::euler(),
            MethodId::Midpoint => Tableau::midpoint(),
            MethodId::Heun => Tableau::heun(),
            MethodId::Rk4 => Tableau::rk4(),
            MethodId::Rk4Typo => rk4_typo(),
            MethodId::Exact => return None,
        })
    }

    /// Theoretical order of accuracy.
    pub fn order(self) -> u32 {
        match self {
            MethodId::Euler => 1,
            MethodId::Midpoint | MethodId::Heun => 2,
            MethodId::Rk4 => 4,
            // Σ bᵢcᵢ = 5/12 ≠ 1/2 with the typo: not even second order.
            MethodId::Rk4Typo => 1,
            MethodId::Exact => u32::MAX,
        }
    }
}

/// RK4 as the notes print it: the last stage samples at `x0 + k3/2` (ERRATA 1).
pub fn rk4_typo() -> Tableau {
    let mut t = Tableau::rk4();
    t.name = "RK4 (typo)".into();
    t.a[3] = vec![0.0, 0.0, 0.5, 0.0];
    t.c[3] = 0.5;
    t
}

/// A fixed-step path: `ts[i]` and the state `xs[i]`; `diverged_at` is set when the state left
/// `|x| ≤ bound` or became non-finite (the path stops there, so nothing draws NaN).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Path {
    pub ts: Vec<f64>,
    pub xs: Vec<Vec<f64>>,
    pub f_evals: usize,
    pub diverged_at: Option<f64>,
}

impl Path {
    pub fn last(&self) -> &[f64] {
        self.xs.last().map(|v| v.as_slice()).unwrap_or(&[])
    }
}

/// Integrates from `(t0, x0)` with `steps` steps of size `h` (capped at `max_steps`).
pub fn fixed_path<S: System + ?Sized>(
    sys: &S,
    tableau: Tableau,
    t0: f64,
    x0: &[f64],
    h: f64,
    steps: usize,
    bound: f64,
) -> Path {
    let stages = tableau.stages();
    let mut rk = ExplicitRk::new(tableau, x0.len());
    let mut x = x0.to_vec();
    let mut path = Path {
        ts: vec![t0],
        xs: vec![x.clone()],
        ..Default::default()
    };
    for i in 0..steps {
        let t = t0 + i as f64 * h;
        rk.step(sys, t, &mut x, h);
        path.f_evals += stages;
        let t_new = t0 + (i + 1) as f64 * h;
        if x.iter().any(|v| !v.is_finite() || v.abs() > bound) {
            path.diverged_at = Some(t_new);
            break;
        }
        path.ts.push(t_new);
        path.xs.push(x.clone());
    }
    path
}

/// Steps needed to reach `t_end` from `t0` with step `h`, capped so a tiny `h` cannot stall
/// a frame.
pub fn steps_for(t0: f64, t_end: f64, h: f64, cap: usize) -> usize {
    if !(h > 0.0) || !(t_end > t0) {
        return 0;
    }
    (((t_end - t0) / h).round() as usize).clamp(1, cap)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ode::FnSystem;

    #[test]
    fn typo_rk4_is_only_second_order() {
        // Error ratio when halving h on x' = x: 2^order.
        let sys = FnSystem::new(1, |_t, x: &[f64], d: &mut [f64]| d[0] = x[0]);
        let err = |m: MethodId, h: f64| {
            let n = steps_for(0.0, 1.0, h, 1 << 20);
            let p = fixed_path(&sys, m.tableau().unwrap(), 0.0, &[1.0], h, n, 1e9);
            (p.last()[0] - 1f64.exp()).abs()
        };
        for m in [
            MethodId::Euler,
            MethodId::Midpoint,
            MethodId::Rk4,
            MethodId::Rk4Typo,
        ] {
            let order = (err(m, 0.02) / err(m, 0.01)).log2();
            assert!((order - m.order() as f64).abs() < 0.2, "{m:?}: {order}");
        }
    }

    #[test]
    fn divergence_stops_the_path() {
        let sys = FnSystem::new(1, |_t, x: &[f64], d: &mut [f64]| d[0] = -50.0 * x[0]);
        let p = fixed_path(&sys, Tableau::euler(), 0.0, &[1.0], 0.1, 1000, 1e6);
        assert!(p.diverged_at.is_some());
        assert!(
            p.xs.iter()
                .flatten()
                .all(|v| v.is_finite() && v.abs() <= 1e6)
        );
    }
}
