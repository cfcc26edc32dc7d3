//! Drivers: run a method from t0 to t_end and report the path, the work and the outcome.
//! Divergence is data: a non-finite state or one beyond `bound` stops the run and is reported
//! as `Outcome::Diverged { t }` ("off to Neptune"), never a panic.

use std::fmt;

use super::dopri5::Dopri5;
use super::explicit::Rk4;
use super::implicit::Implicit;
use super::symplectic::{SymplecticEuler, Verlet};
use super::system::Counted;
use super::{ExplicitRk, Method, System, Tableau};

/// More fixed steps than this are refused (a slider at h = 1e-12 must not hang a talk).
pub const MAX_FIXED_STEPS: f64 = 1e8;
/// Default step budget of the adaptive solver.
pub const MAX_ADAPTIVE_STEPS: usize = 10_000_000;

/// How a run ended.
#[derive(Debug, Clone, PartialEq)]
pub enum Outcome {
    Finished,
    /// the state became non-finite or exceeded the bound at time t
    Diverged {
        t: f64,
    },
    /// the run could not continue (bad input, Newton failure, step-size underflow)
    Failed {
        t: f64,
        reason: String,
    },
}

impl fmt::Display for Outcome {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Outcome::Finished => f.write_str("finished"),
            Outcome::Diverged { t } => write!(f, "diverged at t = {t}"),
            Outcome::Failed { t, reason } => write!(f, "failed at t = {t}: {reason}"),
        }
    }
}

/// A computed trajectory: `ts[i]` and the state `xs[i*n .. (i+1)*n]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Solution {
    pub n: usize,
    pub ts: Vec<f64>,
    /// row-major, `n` values per entry of `ts`
    pub xs: Vec<f64>,
    pub f_evals: u64,
    /// steps taken (accepted steps for adaptive runs)
    pub steps: usize,
    /// rejected steps (adaptive runs only)
    pub rejected: usize,
    pub outcome: Outcome,
}

impl Solution {
    fn start(n: usize, t0: f64, x0: &[f64]) -> Self {
        Self {
            n,
            ts: vec![t0],
            xs: x0.to_vec(),
            f_evals: 0,
            steps: 0,
            rejected: 0,
            outcome: Outcome::Finished,
        }
    }

    pub fn len(&self) -> usize {
        self.ts.len()
    }

    pub fn is_empty(&self) -> bool {
        self.ts.is_empty()
    }

    pub fn state(&self, i: usize) -> &[f64] {
        &self.xs[i * self.n..(i + 1) * self.n]
    }

    /// The last recorded time and state (the final one unless the run diverged).
    pub fn last(&self) -> (f64, &[f64]) {
        let i = self.ts.len() - 1;
        (self.ts[i], self.state(i))
    }

    pub fn finished(&self) -> bool {
        self.outcome == Outcome::Finished
    }

    fn push(&mut self, t: f64, x: &[f64], record: bool) {
        if record {
            self.ts.push(t);
            self.xs.extend_from_slice(x);
        } else {
            self.ts[0] = t;
            self.xs.copy_from_slice(x);
        }
    }
}

/// A fixed-step stepper for any method but the adaptive one; owns all scratch space.
pub enum Stepper {
    Explicit(ExplicitRk),
    Rk4(Rk4),
    SymplecticEuler(SymplecticEuler),
    Verlet(Verlet),
    Implicit(Implicit),
}

impl Stepper {
    /// Dormand–Prince with a fixed step uses its fifth-order weights.
    pub fn new(method: Method, n: usize) -> Self {
        match method {
            Method::Rk4 => Stepper::Rk4(Rk4::new(n)),
            Method::SymplecticEuler => Stepper::SymplecticEuler(SymplecticEuler::new(n)),
            Method::Verlet => Stepper::Verlet(Verlet::new(n)),
            Method::ImplicitEuler => Stepper::Implicit(Implicit::new(1.0, n)),
            Method::ImplicitMidpoint => Stepper::Implicit(Implicit::new(0.5, n)),
            m => Stepper::Explicit(ExplicitRk::new(m.tableau().expect("explicit RK"), n)),
        }
    }

    pub fn from_tableau(tableau: Tableau, n: usize) -> Self {
        Stepper::Explicit(ExplicitRk::new(tableau, n))
    }

    /// Advances x from t to t + h; an error names why the step was impossible.
    pub fn step<S: System + ?Sized>(
        &mut self,
        sys: &S,
        t: f64,
        x: &mut [f64],
        h: f64,
    ) -> Result<(), &'static str> {
        match self {
            Stepper::Explicit(s) => s.step(sys, t, x, h),
            Stepper::Rk4(s) => s.step(sys, t, x, h),
            Stepper::SymplecticEuler(s) => s.step(sys, t, x, h),
            Stepper::Verlet(s) => s.step(sys, t, x, h),
            Stepper::Implicit(s) => return s.step(sys, t, x, h).map_err(|e| e.message()),
        }
        Ok(())
    }
}

fn out_of_bounds(x: &[f64], bound: f64) -> bool {
    x.iter().any(|v| !v.is_finite() || v.abs() > bound)
}

/// The argument checks both adaptive drivers share: dimension, tolerances, time span, and a
/// start already out of bounds (reported as divergence at t0, like the fixed-step drivers).
fn check_adaptive(
    dim: usize,
    t0: f64,
    x0: &[f64],
    t_end: f64,
    opts: &Adaptive,
) -> Result<(), Outcome> {
    let fail = |reason: String| Err(Outcome::Failed { t: t0, reason });
    let n = x0.len();
    if n != dim {
        return fail(format!("initial state has {n} values, the system {dim}"));
    }
    let (rtol, atol) = (opts.rtol, opts.atol);
    if !(rtol >= 0.0 && atol >= 0.0 && rtol + atol > 0.0 && rtol.is_finite() && atol.is_finite()) {
        return fail(format!(
            "tolerances rtol = {rtol}, atol = {atol} must be finite, ≥ 0 and not both 0"
        ));
    }
    if !(t0.is_finite() && t_end.is_finite() && t_end >= t0) {
        return fail(format!(
            "need finite t0 ≤ t_end, got t0 = {t0}, t_end = {t_end}"
        ));
    }
    if out_of_bounds(x0, opts.bound) {
        return Err(Outcome::Diverged { t: t0 });
    }
    Ok(())
}

/// Checks that a symplectic method gets a second-order system: even dimension and q' = v.
fn check_second_order<S: System + ?Sized>(sys: &S, t0: f64, x0: &[f64]) -> Result<(), String> {
    let n = x0.len();
    if n % 2 != 0 {
        return Err(format!(
            "symplectic methods need a state (q, v) of even length, got {n}"
        ));
    }
    let mut f = vec![0.0; n];
    sys.rhs(t0, x0, &mut f);
    let m = n / 2;
    if (0..m).any(|i| (f[i] - x0[m + i]).abs() > 1e-12 * (1.0 + x0[m + i].abs())) {
        return Err("symplectic methods need x = (q, v) with q' = v (the first half of f must equal the second half of x)".into());
    }
    Ok(())
}

/// Integrates with a fixed step h from t0 to t_end (the last step is shortened to land on
/// t_end), recording every step. Stops at the first state that is non-finite or has a
/// component with |x| > bound.
pub fn solve_fixed<S: System + ?Sized>(
    sys: &S,
    method: Method,
    t0: f64,
    x0: &[f64],
    h: f64,
    t_end: f64,
    bound: f64,
) -> Solution {
    run_fixed(sys, Scheme::Method(method), t0, x0, h, t_end, bound, true)
}

/// [`solve_fixed`] for any explicit Butcher tableau (e.g. one loaded from RON).
pub fn solve_tableau<S: System + ?Sized>(
    sys: &S,
    tableau: &Tableau,
    t0: f64,
    x0: &[f64],
    h: f64,
    t_end: f64,
    bound: f64,
) -> Solution {
    run_fixed(sys, Scheme::Tableau(tableau), t0, x0, h, t_end, bound, true)
}

/// Like [`solve_fixed`] but keeps only the final state (for benchmarks and studies).
pub fn solve_fixed_final<S: System + ?Sized>(
    sys: &S,
    scheme: Scheme<'_>,
    t0: f64,
    x0: &[f64],
    h: f64,
    t_end: f64,
    bound: f64,
) -> Solution {
    run_fixed(sys, scheme, t0, x0, h, t_end, bound, false)
}

/// A method by name or an explicit tableau.
#[derive(Debug, Clone, Copy)]
pub enum Scheme<'a> {
    Method(Method),
    Tableau(&'a Tableau),
}

impl Scheme<'_> {
    pub fn label(&self) -> String {
        match self {
            Scheme::Method(m) => m.label().to_string(),
            Scheme::Tableau(t) => t.name.clone(),
        }
    }
}

/// The number of fixed steps of size h from t0 to t_end (the last one may be shorter), or why
/// there can be none. Shared with the fixed-size path so both take identical steps.
pub(crate) fn fixed_step_count(t0: f64, t_end: f64, h: f64) -> Result<usize, String> {
    if !(h.is_finite() && h > 0.0) {
        return Err(format!("step size h = {h} must be positive and finite"));
    }
    if !(t0.is_finite() && t_end.is_finite() && t_end >= t0) {
        return Err(format!(
            "need finite t0 ≤ t_end, got t0 = {t0}, t_end = {t_end}"
        ));
    }
    let ratio = (t_end - t0) / h;
    if ratio > MAX_FIXED_STEPS {
        return Err(format!(
            "{ratio:.3e} steps of h = {h} exceed the limit of {MAX_FIXED_STEPS:e}"
        ));
    }
    // a whole number of steps when (t_end − t0)/h is one up to rounding
    Ok(if (ratio - ratio.round()).abs() < 1e-9 * ratio.max(1.0) {
        ratio.round() as usize
    } else {
        ratio.ceil() as usize
    })
}

#[allow(clippy::too_many_arguments)]
fn run_fixed<S: System + ?Sized>(
    sys: &S,
    scheme: Scheme<'_>,
    t0: f64,
    x0: &[f64],
    h: f64,
    t_end: f64,
    bound: f64,
    record: bool,
) -> Solution {
    let n = x0.len();
    let mut sol = Solution::start(n, t0, x0);
    let fail = |mut sol: Solution, t: f64, reason: String| {
        sol.outcome = Outcome::Failed { t, reason };
        sol
    };
    if n != sys.dim() {
        return fail(
            sol,
            t0,
            format!("initial state has {n} values, the system {}", sys.dim()),
        );
    }
    let steps = match fixed_step_count(t0, t_end, h) {
        Ok(steps) => steps,
        Err(reason) => return fail(sol, t0, reason),
    };
    if out_of_bounds(x0, bound) {
        sol.outcome = Outcome::Diverged { t: t0 };
        return sol;
    }
    let counted = Counted::new(sys);
    let mut stepper = match scheme {
        Scheme::Method(m) if m.needs_second_order_system() => {
            if let Err(e) = check_second_order(&counted, t0, x0) {
                return fail(sol, t0, e);
            }
            Stepper::new(m, n)
        }
        Scheme::Method(m) => Stepper::new(m, n),
        Scheme::Tableau(t) => {
            if let Err(e) = t.validate() {
                return fail(sol, t0, e);
            }
            Stepper::from_tableau(t.clone(), n)
        }
    };
    let mut x = x0.to_vec();
    if record {
        sol.ts.reserve(steps);
        sol.xs.reserve(steps * n);
    }
    for i in 0..steps {
        let t = t0 + i as f64 * h;
        let t_next = if i + 1 == steps {
            t_end
        } else {
            t0 + (i + 1) as f64 * h
        };
        if let Err(reason) = stepper.step(&counted, t, &mut x, t_next - t) {
            sol.f_evals = counted.evals.get();
            return fail(sol, t, reason.to_string());
        }
        sol.steps += 1;
        if out_of_bounds(&x, bound) {
            if x.iter().all(|v| v.is_finite()) {
                sol.push(t_next, &x, record);
            }
            sol.outcome = Outcome::Diverged { t: t_next };
            break;
        }
        sol.push(t_next, &x, record);
    }
    sol.f_evals = counted.evals.get();
    sol
}

/// Tolerances and limits of an adaptive run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Adaptive {
    pub rtol: f64,
    pub atol: f64,
    /// first step; `None` picks one (Hairer's estimate, two f-evaluations)
    pub h0: Option<f64>,
    pub max_steps: usize,
    pub bound: f64,
    /// record every accepted step (else only the final state)
    pub record: bool,
}

impl Default for Adaptive {
    fn default() -> Self {
        Self {
            rtol: 1e-6,
            atol: 1e-9,
            h0: None,
            max_steps: MAX_ADAPTIVE_STEPS,
            bound: 1e12,
            record: true,
        }
    }
}

/// Adaptive Dormand–Prince 5(4) from t0 to t_end.
pub fn solve_adaptive<S: System + ?Sized>(
    sys: &S,
    t0: f64,
    x0: &[f64],
    t_end: f64,
    opts: Adaptive,
) -> Solution {
    let n = x0.len();
    let mut sol = Solution::start(n, t0, x0);
    let fail = |mut sol: Solution, t: f64, reason: String| {
        sol.outcome = Outcome::Failed { t, reason };
        sol
    };
    if let Err(outcome) = check_adaptive(sys.dim(), t0, x0, t_end, &opts) {
        sol.outcome = outcome;
        return sol;
    }
    let counted = Counted::new(sys);
    let mut dp = Dopri5::new(n, opts.rtol, opts.atol);
    let mut x = x0.to_vec();
    let mut t = t0;
    let mut h = match opts.h0 {
        Some(h) if h.is_finite() && h > 0.0 => h,
        _ => dp.initial_step(&counted, t, &x, t_end),
    };
    let mut after_reject = false;
    while t < t_end {
        if sol.steps + sol.rejected >= opts.max_steps {
            sol.f_evals = counted.evals.get();
            return fail(sol, t, format!("more than {} steps", opts.max_steps));
        }
        let last = t + h >= t_end;
        let h_try = if last { t_end - t } else { h };
        if h_try <= f64::EPSILON * 4.0 * t.abs().max(1e-300) {
            sol.f_evals = counted.evals.get();
            return fail(sol, t, format!("step size underflow (h = {h_try:e})"));
        }
        let att = dp.try_step(&counted, t, &mut x, h_try, after_reject);
        if att.accepted {
            t = if last { t_end } else { t + h_try };
            sol.steps += 1;
            after_reject = false;
            if out_of_bounds(&x, opts.bound) {
                sol.push(t, &x, opts.record);
                sol.outcome = Outcome::Diverged { t };
                break;
            }
            sol.push(t, &x, opts.record);
            // keep a good step size across the final, shortened step
            h = if last { h.max(att.h_next) } else { att.h_next };
        } else {
            sol.rejected += 1;
            after_reject = true;
            h = att.h_next;
            if !h.is_finite() {
                sol.outcome = Outcome::Diverged { t };
                break;
            }
        }
    }
    sol.f_evals = counted.evals.get();
    sol
}

/// Implicit Euler or implicit midpoint with step-size control by step doubling: each step is
/// taken once with h and twice with h/2; their difference / (2^p − 1) estimates the error
/// of the two-half-step result, which is kept. This is what lets an implicit method cross the
/// jumps of a stiff relaxation oscillation (Van der Pol) with few steps elsewhere.
pub fn solve_implicit_adaptive<S: System + ?Sized>(
    sys: &S,
    method: Method,
    t0: f64,
    x0: &[f64],
    t_end: f64,
    opts: Adaptive,
) -> Solution {
    let n = x0.len();
    let mut sol = Solution::start(n, t0, x0);
    let fail = |mut sol: Solution, t: f64, reason: String| {
        sol.outcome = Outcome::Failed { t, reason };
        sol
    };
    if !method.is_implicit() {
        return fail(sol, t0, format!("{method} is not an implicit method"));
    }
    if let Err(outcome) = check_adaptive(sys.dim(), t0, x0, t_end, &opts) {
        sol.outcome = outcome;
        return sol;
    }
    let counted = Counted::new(sys);
    let mut stepper = Stepper::new(method, n);
    let p = method.order() as i32;
    let mut x = x0.to_vec();
    let mut full = vec![0.0; n];
    let mut half = vec![0.0; n];
    let mut t = t0;
    let mut h = opts
        .h0
        .filter(|h| h.is_finite() && *h > 0.0)
        .unwrap_or(((t_end - t0) * 1e-4).max(1e-12));
    while t < t_end {
        if sol.steps + sol.rejected >= opts.max_steps {
            sol.f_evals = counted.evals.get();
            return fail(sol, t, format!("more than {} steps", opts.max_steps));
        }
        let last = t + h >= t_end;
        let h_try = if last { t_end - t } else { h };
        if h_try <= f64::EPSILON * 4.0 * t.abs().max(1e-300) {
            sol.f_evals = counted.evals.get();
            return fail(sol, t, format!("step size underflow (h = {h_try:e})"));
        }
        full.copy_from_slice(&x);
        half.copy_from_slice(&x);
        let ok = stepper.step(&counted, t, &mut full, h_try).is_ok()
            && stepper.step(&counted, t, &mut half, 0.5 * h_try).is_ok()
            && stepper
                .step(&counted, t + 0.5 * h_try, &mut half, 0.5 * h_try)
                .is_ok();
        let err = if ok {
            let k = (2f64.powi(p) - 1.0).recip();
            let sum: f64 = (0..n)
                .map(|i| {
                    let sc = opts.atol + opts.rtol * x[i].abs().max(half[i].abs());
                    ((half[i] - full[i]) * k / sc).powi(2)
                })
                .sum();
            (sum / n as f64).sqrt()
        } else {
            f64::INFINITY
        };
        let fac = if err.is_finite() && err > 0.0 {
            (0.9 * err.powf(-1.0 / (p as f64 + 1.0))).clamp(0.2, 4.0)
        } else if err == 0.0 {
            4.0
        } else {
            0.2
        };
        if err <= 1.0 {
            x.copy_from_slice(&half);
            t = if last { t_end } else { t + h_try };
            sol.steps += 1;
            if out_of_bounds(&x, opts.bound) {
                if x.iter().all(|v| v.is_finite()) {
                    sol.push(t, &x, opts.record);
                }
                sol.outcome = Outcome::Diverged { t };
                break;
            }
            sol.push(t, &x, opts.record);
            h = if last { h } else { h_try * fac };
        } else {
            sol.rejected += 1;
            h = h_try * fac.min(0.9);
        }
    }
    sol.f_evals = counted.evals.get();
    sol
}
