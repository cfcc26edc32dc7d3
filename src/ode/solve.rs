//! Drivers: run a method from t0 to t_end and report the path, the work and the outcome.
//! Divergence is data: a non-finite state or one beyond `bound` stops the run and is reported
//! as `Outcome::Diverged { t }` ("off to Neptune"), never a panic.

use std::fmt;

use super::explicit::Rk4;
use super::implicit::Implicit;
use super::stiff::ImplicitWork;
use super::stiff::radau5::FixedRadau5;
use super::stiff::rodas5p::FixedRodas5p;
use super::symplectic::{SymplecticEuler, Verlet};
use super::system::Counted;
use super::{ExplicitRk, Method, System, Tableau};

pub use super::adaptive::{Adaptive, MAX_ADAPTIVE_STEPS};

/// More fixed steps than this are refused (a slider at h = 1e-12 must not hang a talk).
pub const MAX_FIXED_STEPS: f64 = 1e8;

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
    /// an explicit pair's stiffness test fired at time t (only with `Adaptive::stop_if_stiff`)
    Stiff {
        t: f64,
    },
}

impl fmt::Display for Outcome {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Outcome::Finished => f.write_str("finished"),
            Outcome::Diverged { t } => write!(f, "diverged at t = {t}"),
            Outcome::Failed { t, reason } => write!(f, "failed at t = {t}: {reason}"),
            Outcome::Stiff { t } => {
                write!(f, "looks stiff at t = {t}; try --method rodas5p or radau5")
            }
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
    /// Jacobian evaluations and LU decompositions (implicit methods)
    pub work: ImplicitWork,
    pub outcome: Outcome,
}

impl Solution {
    pub(crate) fn start(n: usize, t0: f64, x0: &[f64]) -> Self {
        Self {
            n,
            ts: vec![t0],
            xs: x0.to_vec(),
            f_evals: 0,
            steps: 0,
            rejected: 0,
            work: ImplicitWork::default(),
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

    pub(crate) fn push(&mut self, t: f64, x: &[f64], record: bool) {
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
    Rodas5p(Box<FixedRodas5p>),
    Radau5(Box<FixedRadau5>),
}

impl Stepper {
    /// An embedded pair with a fixed step uses its propagating (higher-order) weights.
    pub fn new(method: Method, n: usize) -> Self {
        match method {
            Method::Rk4 => Stepper::Rk4(Rk4::new(n)),
            Method::SymplecticEuler => Stepper::SymplecticEuler(SymplecticEuler::new(n)),
            Method::Verlet => Stepper::Verlet(Verlet::new(n)),
            Method::ImplicitEuler => Stepper::Implicit(Implicit::new(1.0, n)),
            Method::ImplicitMidpoint => Stepper::Implicit(Implicit::new(0.5, n)),
            Method::Rodas5p => Stepper::Rodas5p(Box::new(FixedRodas5p::new(n))),
            Method::Radau5 => Stepper::Radau5(Box::new(FixedRadau5::new(n))),
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
            Stepper::Rodas5p(s) => return s.step(sys, t, x, h),
            Stepper::Radau5(s) => return s.step(sys, t, x, h),
        }
        Ok(())
    }
}

fn out_of_bounds(x: &[f64], bound: f64) -> bool {
    x.iter().any(|v| !v.is_finite() || v.abs() > bound)
}

/// Checks that a symplectic method gets a second-order system: even dimension and q' = v.
fn check_second_order<S: System + ?Sized>(sys: &S, t0: f64, x0: &[f64]) -> Result<(), String> {
    let n = x0.len();
    if !n.is_multiple_of(2) {
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
