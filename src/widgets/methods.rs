//! The methods the widgets compare, mapped onto the numerics core (`ode::Method`, or a
//! `Tableau` through `ode::solve_tableau`), and drawable fixed-step paths that stop cleanly when
//! a solution blows up (`Outcome::Diverged`).

use std::sync::OnceLock;

pub use crate::deck::widgets::MethodId;
use crate::ode::{Method, Outcome, Scheme, Solution, System, Tableau, solve_fixed, solve_tableau};

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
            MethodId::Rk4Typo => rk4_typo().clone(),
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

/// RK4 as the notes print it: the last stage samples at `x0 + k3/2` (ERRATA 1), from the
/// numerics core (`slides/tableaux/rk4-typo.ron` is the same tableau as a file).
pub fn rk4_typo() -> &'static Tableau {
    static TYPO: OnceLock<Tableau> = OnceLock::new();
    TYPO.get_or_init(Tableau::rk4_typo)
}

impl MethodId {
    /// The integrator in the numerics core; `None` for `Exact`.
    pub fn scheme(self) -> Option<Scheme<'static>> {
        Some(match self {
            MethodId::Euler => Scheme::Method(Method::Euler),
            MethodId::Midpoint => Scheme::Method(Method::Midpoint),
            MethodId::Heun => Scheme::Method(Method::Heun),
            MethodId::Rk4 => Scheme::Method(Method::Rk4),
            MethodId::Rk4Typo => Scheme::Tableau(rk4_typo()),
            MethodId::Exact => return None,
        })
    }
}

/// A fixed-step path for drawing: `ts[i]` and the state `xs[i]`; `diverged_at` is set when
/// the run reported `Outcome::Diverged` (the state left `|x| ≤ bound` or became non-finite).
/// The path stops at the last state inside the bound, so nothing draws NaN or 1e300.
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

    /// The drawable part of a solution from `ode::solve_fixed` / `solve_tableau`.
    pub fn from_solution(sol: &Solution, bound: f64) -> Self {
        let inside = |x: &[f64]| x.iter().all(|v| v.is_finite() && v.abs() <= bound);
        let mut path = Path {
            f_evals: sol.f_evals as usize,
            diverged_at: match sol.outcome {
                Outcome::Finished => None,
                Outcome::Diverged { t } | Outcome::Failed { t, .. } => Some(t),
            },
            ..Default::default()
        };
        for (i, &t) in sol.ts.iter().enumerate() {
            let x = sol.state(i);
            if !inside(x) {
                break;
            }
            path.ts.push(t);
            path.xs.push(x.to_vec());
        }
        path
    }
}

/// Integrates from `(t0, x0)` with `steps` steps of size `h` by the numerics core's fixed-step
/// driver, stopping at the bound.
pub fn fixed_path<S: System + ?Sized>(
    sys: &S,
    scheme: Scheme<'_>,
    t0: f64,
    x0: &[f64],
    h: f64,
    steps: usize,
    bound: f64,
) -> Path {
    let t_end = t0 + steps as f64 * h;
    let sol = match scheme {
        Scheme::Method(m) => solve_fixed(sys, m, t0, x0, h, t_end, bound),
        Scheme::Tableau(t) => solve_tableau(sys, t, t0, x0, h, t_end, bound),
    };
    Path::from_solution(&sol, bound)
}

/// At most this many points of a path are drawn: a plot line is a few hundred pixels wide, and
/// tessellating 20 000 points every frame stalls the software renderer.
pub const MAX_DRAWN_POINTS: usize = 2048;

/// Step markers are drawn only up to this many steps; beyond it they merge into the line.
pub const MAX_STEP_MARKERS: usize = 200;

/// Every k-th point of `pts` (k chosen so at most `max` remain), always keeping the first and
/// last, so a long path draws at bounded cost and still ends where the solve ended.
pub fn decimate(pts: &[[f64; 2]], max: usize) -> Vec<[f64; 2]> {
    let max = max.max(2);
    if pts.len() <= max {
        return pts.to_vec();
    }
    let stride = (pts.len() - 1).div_ceil(max - 1);
    let mut out: Vec<[f64; 2]> = pts.iter().step_by(stride).copied().collect();
    if (pts.len() - 1) % stride != 0 {
        out.push(*pts.last().expect("non-empty"));
    }
    out
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
    fn decimate_bounds_the_count_and_keeps_both_ends() {
        let pts: Vec<[f64; 2]> = (0..20_001).map(|i| [i as f64, 0.0]).collect();
        for max in [2, 3, 2000, 20_001, 30_000] {
            let d = decimate(&pts, max);
            assert!(d.len() <= max.max(2), "{max}: {}", d.len());
            assert_eq!(d[0], pts[0]);
            assert_eq!(d.last(), pts.last());
        }
        assert_eq!(decimate(&pts[..10], 2000), pts[..10].to_vec());
        let d = decimate(&pts[..10_000], 2000);
        // an integer stride keeps at least half the budget
        assert!(d.len() <= 2000 && d.len() > 1000, "{}", d.len());
    }

    #[test]
    fn typo_rk4_is_only_second_order() {
        // Error ratio when halving h on x' = x: 2^order.
        let sys = FnSystem::new(1, |_t, x: &[f64], d: &mut [f64]| d[0] = x[0]);
        let err = |m: MethodId, h: f64| {
            let n = steps_for(0.0, 1.0, h, 1 << 20);
            let p = fixed_path(&sys, m.scheme().unwrap(), 0.0, &[1.0], h, n, 1e9);
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
        let p = fixed_path(
            &sys,
            MethodId::Euler.scheme().unwrap(),
            0.0,
            &[1.0],
            0.1,
            1000,
            1e6,
        );
        assert!(p.diverged_at.is_some());
        assert!(
            p.xs.iter()
                .flatten()
                .all(|v| v.is_finite() && v.abs() <= 1e6)
        );
    }
}
