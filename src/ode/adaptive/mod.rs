//! The one adaptive loop: step-size control for every embedded pair (`ode::pairs`) and for
//! step doubling of the implicit methods, on either state representation (a `[f64; N]` known
//! at compile time, or a run-time `Vec<f64>`).
//!
//! The loop (`drive`) owns what is common: the first step (Hairer's estimate unless given),
//! landing on t_end, the PI controller (`pairs::Controller`), no growth right after a rejection,
//! the step budget, step-size underflow, and divergence ("off to Neptune"). A [`Trial`] owns the
//! state and its scratch and knows how to try one step and estimate its error.

mod doubling;
mod drivers;
mod implicit_trials;
mod pair_stepper;

pub use drivers::{
    solve_adaptive, solve_embedded, solve_embedded_n, solve_embedded_n_with,
    solve_implicit_adaptive,
};

use super::pairs::Controller;
use super::solve::Outcome;
use super::stiff::ImplicitWork;

/// Default step budget of the adaptive solvers (accepted plus rejected steps).
pub const MAX_ADAPTIVE_STEPS: usize = 10_000_000;

/// Accepted steps between two stiffness tests while none is positive (Hairer's NSTIFF).
const STIFF_TEST_EVERY: usize = 1000;

/// Tolerances and limits of an adaptive run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Adaptive {
    pub rtol: f64,
    pub atol: f64,
    /// first step; `None` picks one (Hairer's estimate, two f-evaluations)
    pub h0: Option<f64>,
    /// most steps (accepted + rejected) before the run fails
    pub max_steps: usize,
    pub bound: f64,
    /// record every accepted step (else only the final state); the `[f64; N]` drivers never
    /// record and call back instead
    pub record: bool,
    /// stop with `Outcome::Stiff` when an explicit pair's stiffness test fires (Hairer's, in
    /// DOPRI5 and DOP853: h·|λ| beyond the stability boundary 15 tests running)
    pub stop_if_stiff: bool,
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
            stop_if_stiff: false,
        }
    }
}

/// The weights of the error norm: component i is scaled by `atol + rtol·max(|x_i|, |x_new,i|)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Tol {
    pub rtol: f64,
    pub atol: f64,
}

/// One way of trying steps; owns the state, the candidate and all scratch space.
pub(crate) trait Trial {
    /// the accepted state
    fn state(&self) -> &[f64];
    /// the state the last attempt proposes
    fn candidate(&self) -> &[f64];
    /// Prepares stepping from (t, state) (e.g. evaluates f there).
    fn start(&mut self, t: f64);
    /// A first step size for the span [t, t_end].
    fn initial_step(&mut self, t: f64, t_end: f64, tol: Tol) -> f64;
    /// Tries a step of h from (t, state): fills the candidate and returns the scaled error
    /// norm (≤ 1 accepts; NaN or ∞ when the step produced non-finite values).
    fn attempt(&mut self, t: f64, h: f64, tol: Tol) -> f64;
    /// Makes the candidate the state at t_new.
    fn accept(&mut self, t_new: f64);
    fn f_evals(&self) -> u64;
    /// What repeated non-finite attempts mean, for the failure message.
    const NONFINITE: &'static str;
    /// Scales the controller's safety factor after an accepted attempt (RADAU5 lowers it when
    /// Newton needed many iterations).
    fn safety_scale(&self) -> f64 {
        1.0
    }
    /// After a rejected attempt: the step-size factor the trial itself needs (Newton failed
    /// to converge), in place of the controller's.
    fn rejection_factor(&self) -> Option<f64> {
        None
    }
    /// After a rejected attempt: why the run cannot go on (a Newton matrix singular however
    /// the step is cut).
    fn fatal(&self) -> Option<String> {
        None
    }
    /// After an accepted step of h: h·|λ| of the dominant eigenvalue over the method's
    /// stability boundary along the negative axis (> 1: the step is limited by stability),
    /// for the explicit pairs that have Hairer's test.
    fn stiffness(&self, _h: f64) -> Option<f64> {
        None
    }
    /// Jacobians and LU decompositions (implicit methods).
    fn work(&self) -> ImplicitWork {
        ImplicitWork::default()
    }
}

/// Hairer's HINIT (Solving ODEs I, II.4), first half: h₀ from |x|/|f(x)| (f0 = f(t, x)),
/// and d₁ = ‖f0‖ for the second half, [`initial_step_finish`], which needs f at
/// x + h₀·f0.
pub(crate) fn initial_step_start(x: &[f64], f0: &[f64], span: f64, tol: Tol) -> (f64, f64) {
    let n = x.len() as f64;
    let sc = |i: usize| tol.atol + tol.rtol * x[i].abs();
    let (mut d0, mut d1) = (0.0, 0.0);
    for i in 0..x.len() {
        d0 += (x[i] / sc(i)).powi(2);
        d1 += (f0[i] / sc(i)).powi(2);
    }
    let (d0, d1) = ((d0 / n).sqrt(), (d1 / n).sqrt());
    let h0 = if d0 < 1e-5 || d1 < 1e-5 {
        1e-6
    } else {
        0.01 * d0 / d1
    }
    .min(span);
    (h0, d1)
}

/// HINIT, second half: with f1 = f(t + h₀, x + h₀·f0), the second derivative's size d₂ and
/// h = min(100 h₀, (0.01 / max(d₁, d₂))^(1/p)), for an error estimate of order p.
#[allow(clippy::too_many_arguments)]
pub(crate) fn initial_step_finish(
    x: &[f64],
    f0: &[f64],
    f1: &[f64],
    h0: f64,
    d1: f64,
    order: u32,
    span: f64,
    tol: Tol,
) -> f64 {
    let n = x.len() as f64;
    let mut d2 = 0.0;
    for i in 0..x.len() {
        let sc = tol.atol + tol.rtol * x[i].abs();
        d2 += ((f1[i] - f0[i]) / sc).powi(2);
    }
    let d2 = (d2 / n).sqrt() / h0;
    let m = d1.max(d2);
    let h1 = if m <= 1e-15 {
        (h0 * 1e-3).max(1e-6)
    } else {
        (0.01 / m).powf(1.0 / order as f64)
    };
    let h = (100.0 * h0).min(h1).min(span);
    if h.is_finite() && h > 0.0 { h } else { span }
}

/// How a run of [`drive`] went.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Run {
    /// time of the last finite state reached (the trial's state, or its candidate when
    /// `ended_on_candidate`)
    pub t: f64,
    pub ended_on_candidate: bool,
    pub steps: usize,
    pub rejected: usize,
    pub outcome: Outcome,
}

#[allow(clippy::neg_cmp_op_on_partial_ord)] // deliberately true for NaN
fn beyond(x: &[f64], bound: f64) -> bool {
    let lim = bound.min(f64::MAX);
    let mut bad = false;
    for v in x {
        // NaN fails `<=`; ±∞ exceeds f64::MAX
        bad |= !(v.abs() <= lim);
    }
    bad
}

/// Hairer's conditions on the arguments (dop853.f: `ATOL > 0`, `RTOL > 10·UROUND`), a finite
/// span t0 ≤ t_end and a state of the system's size; a start already beyond the bound is
/// divergence at t0.
pub(crate) fn check(
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
    let min_rtol = 10.0 * f64::EPSILON;
    if !(rtol.is_finite() && atol.is_finite() && atol > 0.0 && rtol > min_rtol) {
        return fail(format!(
            "tolerances rtol = {rtol}, atol = {atol}: need finite atol > 0 and rtol > {min_rtol:.1e} (10 × machine epsilon)"
        ));
    }
    if !(t0.is_finite() && t_end.is_finite() && t_end >= t0) {
        return fail(format!(
            "need finite t0 ≤ t_end, got t0 = {t0}, t_end = {t_end}"
        ));
    }
    if beyond(x0, opts.bound) {
        return Err(Outcome::Diverged { t: t0 });
    }
    Ok(())
}

/// Runs `trial` from t0 to t_end under `ctrl`, calling `on_accept(t, x)` after every accepted
/// step (and for a final candidate that left the bound while finite). Arguments must have
/// passed [`check`].
pub(crate) fn drive<T: Trial>(
    trial: &mut T,
    t0: f64,
    t_end: f64,
    opts: &Adaptive,
    ctrl: Controller,
    mut on_accept: impl FnMut(f64, &[f64]),
) -> Run {
    let tol = Tol {
        rtol: opts.rtol,
        atol: opts.atol,
    };
    let mut run = Run {
        t: t0,
        ended_on_candidate: false,
        steps: 0,
        rejected: 0,
        outcome: Outcome::Finished,
    };
    if t_end == t0 {
        return run;
    }
    trial.start(t0);
    let span = t_end - t0;
    let mut h = match opts.h0 {
        Some(h) if h.is_finite() && h > 0.0 => h.min(span),
        _ => trial.initial_step(t0, t_end, tol),
    };
    let mut t = t0;
    // Hairer's FACOLD (the previous accepted error, at least 1e-4), kept as its logarithm so a
    // step costs one ln and one exp rather than two powf
    let ln_floor = 1e-4f64.ln();
    let mut ln_err_prev = ln_floor;
    let mut after_reject = false;
    let mut nonfinite = false;
    // Gustafsson's predictive controller: the last accepted step and its error
    let (mut h_acc, mut err_acc) = (f64::NAN, 0.0f64);
    // Hairer's stiffness test: positive tests running, negative ones since the last positive
    let (mut stiff_tests, mut calm_tests) = (0u32, 0u32);
    while t < t_end {
        if run.steps + run.rejected >= opts.max_steps {
            run.outcome = Outcome::Failed {
                t,
                reason: format!("more than {} steps", opts.max_steps),
            };
            return run;
        }
        // stretch the last step by up to 1 % rather than leave a sliver (as dop853.f)
        let last = t + 1.01 * h >= t_end;
        let h_try = if last { t_end - t } else { h };
        let too_small = h_try <= f64::EPSILON * 4.0 * t.abs().max(1e-300);
        if too_small || h_try.is_nan() {
            let reason = if nonfinite {
                format!("{} (step size underflow, h = {h_try:e})", T::NONFINITE)
            } else {
                format!("step size underflow (h = {h_try:e})")
            };
            run.outcome = Outcome::Failed { t, reason };
            return run;
        }
        let err = trial.attempt(t, h_try, tol);
        if err <= 1.0 {
            let t_new = if last { t_end } else { t + h_try };
            run.steps += 1;
            if beyond(trial.candidate(), opts.bound) {
                if trial.candidate().iter().all(|v| v.is_finite()) {
                    on_accept(t_new, trial.candidate());
                    run.t = t_new;
                    run.ended_on_candidate = true;
                }
                run.outcome = Outcome::Diverged { t: t_new };
                return run;
            }
            trial.accept(t_new);
            on_accept(t_new, trial.state());
            t = t_new;
            run.t = t;
            let fac_max = if after_reject { 1.0 } else { ctrl.fac_max };
            // safety · err^(−α) · err_prev^β (err = 0 gives +∞, clamped to fac_max)
            let ln_err = err.ln();
            let safety = ctrl.safety * trial.safety_scale();
            let mut fac = safety * (ctrl.beta * ln_err_prev - ctrl.alpha * ln_err).exp();
            if ctrl.predictive {
                // Gustafsson (1994), as RADAU5: safety · (h/h_acc) · (err_acc / err²)^α
                if h_acc.is_finite() {
                    let ln_gus = (h_try / h_acc).ln() + ctrl.alpha * (err_acc.ln() - 2.0 * ln_err);
                    fac = fac.min(ctrl.safety * ln_gus.exp());
                }
                h_acc = h_try;
                err_acc = err.max(1e-2);
            }
            let mut fac = fac.clamp(ctrl.fac_min, fac_max);
            // a step kept unchanged keeps an implicit method's factorisations
            if (1.0..=ctrl.hold).contains(&fac) {
                fac = 1.0;
            }
            h = h_try * fac;
            ln_err_prev = ln_err.max(ln_floor);
            after_reject = false;
            nonfinite = false;
            if opts.stop_if_stiff && (run.steps % STIFF_TEST_EVERY == 0 || stiff_tests > 0) {
                match trial.stiffness(h_try) {
                    Some(r) if r > 1.0 => {
                        calm_tests = 0;
                        stiff_tests += 1;
                        if stiff_tests == 15 {
                            run.outcome = Outcome::Stiff { t };
                            return run;
                        }
                    }
                    Some(_) => {
                        calm_tests += 1;
                        if calm_tests == 6 {
                            stiff_tests = 0;
                        }
                    }
                    None => {}
                }
            }
        } else {
            run.rejected += 1;
            after_reject = true;
            nonfinite = !err.is_finite();
            if let Some(reason) = trial.fatal() {
                run.outcome = Outcome::Failed { t, reason };
                return run;
            }
            let fac = if let Some(f) = trial.rejection_factor() {
                f
            } else if nonfinite {
                ctrl.fac_min
            } else {
                let safety = ctrl.safety * trial.safety_scale();
                (safety * err.powf(-ctrl.alpha)).clamp(ctrl.fac_min, 1.0)
            };
            h = h_try * fac;
        }
    }
    run
}
