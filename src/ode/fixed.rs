//! The fast path for small systems: a state of `N` f64 values known at compile time.
//!
//! The general steppers work on slices of run-time length behind `&dyn`-friendly traits; here
//! everything is monomorphised over `N` and the right-hand side's type, so the compiler keeps
//! the state in registers, inlines f and drops every bounds check (indices are `< N` by
//! construction). The arithmetic is the general [`Rk4`](super::explicit::Rk4)'s, operation for
//! operation, and the driver takes the same steps as [`solve_fixed`](super::solve_fixed), so
//! both paths give bit-identical trajectories (tested).

use super::System;
use super::solve::{Outcome, fixed_step_count};

/// A first-order system ẋ = f(t, x) whose state has exactly `N` values.
pub trait FixedSystem<const N: usize> {
    fn rhs(&self, t: f64, x: &[f64; N]) -> [f64; N];
    /// ∂f/∂x row-major into `jac` (N² values) and true, or false where there is none (the
    /// stiff solvers then use differences), as [`System::jacobian`].
    fn jacobian(&self, _t: f64, _x: &[f64; N], _jac: &mut [f64]) -> bool {
        false
    }
    /// ∂f/∂t into `dfdt` and true, or false where there is none, as
    /// [`System::time_derivative`].
    fn time_derivative(&self, _t: f64, _x: &[f64; N], _dfdt: &mut [f64; N]) -> bool {
        false
    }
}

impl<const N: usize, S: FixedSystem<N> + ?Sized> FixedSystem<N> for &S {
    #[inline(always)]
    fn rhs(&self, t: f64, x: &[f64; N]) -> [f64; N] {
        (**self).rhs(t, x)
    }
    fn jacobian(&self, t: f64, x: &[f64; N], jac: &mut [f64]) -> bool {
        (**self).jacobian(t, x, jac)
    }
    fn time_derivative(&self, t: f64, x: &[f64; N], dfdt: &mut [f64; N]) -> bool {
        (**self).time_derivative(t, x, dfdt)
    }
}

/// A fixed-size system from a closure `|t, &[f64; N]| -> [f64; N]`.
#[derive(Clone, Copy)]
pub struct FixedFn<F>(pub F);

impl<const N: usize, F: Fn(f64, &[f64; N]) -> [f64; N]> FixedSystem<N> for FixedFn<F> {
    #[inline(always)]
    fn rhs(&self, t: f64, x: &[f64; N]) -> [f64; N] {
        (self.0)(t, x)
    }
}

/// Any fixed-size system seen through the general [`System`] trait (for the general drivers,
/// the implicit methods and comparisons with the fast path).
pub struct AsSystem<const N: usize, S>(pub S);

impl<const N: usize, S: FixedSystem<N>> System for AsSystem<N, S> {
    fn dim(&self) -> usize {
        N
    }
    #[inline]
    fn rhs(&self, t: f64, x: &[f64], dxdt: &mut [f64]) {
        let x: &[f64; N] = x.try_into().expect("state of length N");
        dxdt.copy_from_slice(&self.0.rhs(t, x));
    }
    fn jacobian(&self, t: f64, x: &[f64], jac: &mut [f64]) -> bool {
        let x: &[f64; N] = x.try_into().expect("state of length N");
        self.0.jacobian(t, x, jac)
    }
    fn time_derivative(&self, t: f64, x: &[f64], dfdt: &mut [f64]) -> bool {
        let x: &[f64; N] = x.try_into().expect("state of length N");
        let out: &mut [f64; N] = dfdt.try_into().expect("derivative of length N");
        self.0.time_derivative(t, x, out)
    }
}

/// One classical RK4 step from t to t + h in place: four evaluations of f.
#[inline(always)]
pub fn rk4_step<const N: usize, S: FixedSystem<N> + ?Sized>(
    sys: &S,
    t: f64,
    x: &mut [f64; N],
    h: f64,
) {
    // same expressions, in the same order, as the general Rk4: bit-identical results
    let h2 = 0.5 * h;
    let k1 = sys.rhs(t, x);
    let xs: [f64; N] = std::array::from_fn(|i| x[i] + h2 * k1[i]);
    let k2 = sys.rhs(t + h2, &xs);
    let xs: [f64; N] = std::array::from_fn(|i| x[i] + h2 * k2[i]);
    let k3 = sys.rhs(t + h2, &xs);
    let xs: [f64; N] = std::array::from_fn(|i| x[i] + h * k3[i]);
    let k4 = sys.rhs(t + h, &xs);
    let h6 = h / 6.0;
    for i in 0..N {
        x[i] += h6 * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]);
    }
}

/// The result of a fixed-size run: the last state reached, the work and how it ended.
#[derive(Debug, Clone, PartialEq)]
pub struct FixedSolution<const N: usize> {
    pub t: f64,
    pub x: [f64; N],
    /// evaluations of f (four per RK4 step)
    pub f_evals: u64,
    /// steps taken (accepted steps for adaptive runs)
    pub steps: usize,
    /// rejected steps (adaptive runs only)
    pub rejected: usize,
    pub outcome: Outcome,
}

impl<const N: usize> FixedSolution<N> {
    pub fn finished(&self) -> bool {
        self.outcome == Outcome::Finished
    }
}

/// True when a component is NaN, infinite or beyond `bound` (one compare per component:
/// NaN fails `<=`, and ±∞ exceeds `f64::MAX`).
#[inline(always)]
fn beyond<const N: usize>(x: &[f64; N], bound: f64) -> bool {
    let lim = bound.min(f64::MAX);
    let mut bad = false;
    for v in x {
        bad |= !(v.abs() <= lim);
    }
    bad
}

/// RK4 with fixed step h from t0 to t_end (the last step shortened to land on t_end), keeping
/// only the final state. Stops at the first state that is non-finite or has a component with
/// |x| > bound, reported as `Outcome::Diverged`.
pub fn solve_fixed_n<const N: usize, S: FixedSystem<N> + ?Sized>(
    sys: &S,
    t0: f64,
    x0: [f64; N],
    h: f64,
    t_end: f64,
    bound: f64,
) -> FixedSolution<N> {
    solve_fixed_n_with(sys, t0, x0, h, t_end, bound, |_, _| {})
}

/// [`solve_fixed_n`] calling `on_step(t, &x)` after every step (for trajectories); a no-op
/// closure compiles away.
pub fn solve_fixed_n_with<const N: usize, S: FixedSystem<N> + ?Sized>(
    sys: &S,
    t0: f64,
    x0: [f64; N],
    h: f64,
    t_end: f64,
    bound: f64,
    mut on_step: impl FnMut(f64, &[f64; N]),
) -> FixedSolution<N> {
    let mut sol = FixedSolution {
        t: t0,
        x: x0,
        f_evals: 0,
        steps: 0,
        rejected: 0,
        outcome: Outcome::Finished,
    };
    let steps = match fixed_step_count(t0, t_end, h) {
        Ok(steps) => steps,
        Err(reason) => {
            sol.outcome = Outcome::Failed { t: t0, reason };
            return sol;
        }
    };
    if beyond(&x0, bound) {
        sol.outcome = Outcome::Diverged { t: t0 };
        return sol;
    }
    let mut x = x0;
    for i in 0..steps {
        // times computed as in the general driver (no accumulated t += h drift)
        let t = t0 + i as f64 * h;
        let t_next = if i + 1 == steps {
            t_end
        } else {
            t0 + (i + 1) as f64 * h
        };
        rk4_step(sys, t, &mut x, t_next - t);
        if beyond(&x, bound) {
            sol.steps = i + 1;
            sol.f_evals = 4 * sol.steps as u64;
            sol.outcome = Outcome::Diverged { t: t_next };
            // keep the last finite state, as the general driver does
            if x.iter().all(|v| v.is_finite()) {
                sol.t = t_next;
                sol.x = x;
                on_step(t_next, &x);
            }
            return sol;
        }
        on_step(t_next, &x);
        sol.t = t_next;
        sol.x = x;
    }
    sol.steps = steps;
    sol.f_evals = 4 * steps as u64;
    sol
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::Cell;

    #[test]
    fn decay_matches_exp_and_counts_evaluations() {
        let calls = Cell::new(0u64);
        let sys = FixedFn(|_t: f64, x: &[f64; 1]| {
            calls.set(calls.get() + 1);
            [-x[0]]
        });
        let sol = solve_fixed_n(&sys, 0.0, [1.0], 0.1, 1.0, f64::INFINITY);
        assert!(sol.finished());
        assert_eq!(sol.steps, 10);
        assert_eq!(sol.f_evals, calls.get());
        assert_eq!(sol.f_evals, 40);
        assert!((sol.x[0] - (-1.0f64).exp()).abs() < 1e-6);
    }

    #[test]
    fn divergence_is_data() {
        let grow = FixedFn(|_t: f64, x: &[f64; 2]| [x[1], -x[0]]);
        // hω = 1e9: RK4's amplification is ~h⁴/24, so the state leaves any bound at once
        let sol = solve_fixed_n(&grow, 0.0, [1.0, 0.0], 1e9, 1e10, 1e12);
        assert!(matches!(sol.outcome, Outcome::Diverged { .. }), "{sol:?}");
        let sol = solve_fixed_n(&grow, 0.0, [f64::NAN, 0.0], 0.1, 1.0, f64::INFINITY);
        assert_eq!(sol.outcome, Outcome::Diverged { t: 0.0 });
        let sol = solve_fixed_n(&grow, 0.0, [1.0, 0.0], -0.1, 1.0, f64::INFINITY);
        assert!(matches!(sol.outcome, Outcome::Failed { .. }));
        // a state that reaches ±∞ with an infinite bound is still divergence
        let blow = FixedFn(|_t: f64, x: &[f64; 1]| [x[0] * x[0]]);
        let sol = solve_fixed_n(&blow, 0.0, [1.0], 0.5, 100.0, f64::INFINITY);
        assert!(matches!(sol.outcome, Outcome::Diverged { .. }), "{sol:?}");
    }
}
