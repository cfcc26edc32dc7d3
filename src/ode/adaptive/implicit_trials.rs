//! Trying steps of the stiff solvers (`ode::stiff`) for the one adaptive loop: Rodas5P with
//! its embedded estimate, RADAU5 with simplified Newton. Both see the system through
//! [`Counted`], so the f-evaluations of difference Jacobians count with the others.

use super::{Tol, Trial, initial_step_finish, initial_step_start};
use crate::ode::System;
use crate::ode::stiff::ImplicitWork;
use crate::ode::stiff::radau5::{Attempt, NIT, Radau5, RadauTol};
use crate::ode::stiff::rodas5p::Rodas5p;
use crate::ode::system::Counted;

/// HINIT for a trial that keeps f(t, x) in `f0` (one f-evaluation).
fn hairer_initial_step<S: System + ?Sized>(
    sys: &S,
    t: f64,
    t_end: f64,
    x: &[f64],
    f0: &[f64],
    order: u32,
    tol: Tol,
) -> f64 {
    let span = t_end - t;
    let (h0, d1) = initial_step_start(x, f0, span, tol);
    let xs: Vec<f64> = x.iter().zip(f0).map(|(x, f)| x + h0 * f).collect();
    let mut f1 = vec![0.0; x.len()];
    sys.rhs(t + h0, &xs, &mut f1);
    initial_step_finish(x, f0, &f1, h0, d1, order, span, tol)
}

/// The weighted RMS norm of the adaptive loop (as the embedded pairs).
fn scaled_rms(e: &[f64], x: &[f64], x_new: &[f64], tol: Tol) -> f64 {
    let n = e.len();
    let mut sum = 0.0;
    for m in 0..n {
        let sc = tol.atol + tol.rtol * x[m].abs().max(x_new[m].abs());
        sum += (e[m] / sc).powi(2);
    }
    (sum / n as f64).sqrt()
}

/// Consecutive singular matrices before a run gives up (RADAU5's NSING limit).
const MAX_SINGULAR: u32 = 5;

pub(crate) struct RodasTrial<'a, S: ?Sized> {
    sys: Counted<'a, S>,
    core: Rodas5p,
    x: Vec<f64>,
    x_new: Vec<f64>,
    fx: Vec<f64>,
    /// J and f_t are at the current state
    prepared: bool,
    /// they have a NaN or ∞
    bad_jacobian: bool,
    singular: bool,
    singular_run: u32,
}

impl<'a, S: System + ?Sized> RodasTrial<'a, S> {
    pub fn new(sys: &'a S, x0: &[f64]) -> Self {
        let n = x0.len();
        Self {
            sys: Counted::new(sys),
            core: Rodas5p::new(n),
            x: x0.to_vec(),
            x_new: x0.to_vec(),
            fx: vec![0.0; n],
            prepared: false,
            bad_jacobian: false,
            singular: false,
            singular_run: 0,
        }
    }
}

impl<S: System + ?Sized> Trial for RodasTrial<'_, S> {
    const NONFINITE: &'static str =
        "the right-hand side or its Jacobian returned NaN or ∞ however small the step";

    fn state(&self) -> &[f64] {
        &self.x
    }

    fn candidate(&self) -> &[f64] {
        &self.x_new
    }

    fn start(&mut self, t: f64) {
        self.sys.rhs(t, &self.x, &mut self.fx);
        self.prepared = false;
    }

    fn initial_step(&mut self, t: f64, t_end: f64, tol: Tol) -> f64 {
        hairer_initial_step(&self.sys, t, t_end, &self.x, &self.fx, 4, tol)
    }

    fn attempt(&mut self, t: f64, h: f64, tol: Tol) -> f64 {
        if !self.prepared {
            self.bad_jacobian = !self.core.prepare(&self.sys, t, &self.x, &self.fx);
            self.prepared = true;
        }
        if self.bad_jacobian {
            return f64::INFINITY;
        }
        self.singular = false;
        match self
            .core
            .attempt(&self.sys, t, &self.x, &self.fx, h, &mut self.x_new)
        {
            Ok(err) => {
                self.singular_run = 0;
                let e = scaled_rms(err, &self.x, &self.x_new, tol);
                if e.is_nan() { f64::INFINITY } else { e }
            }
            Err(_) => {
                self.singular = true;
                self.singular_run += 1;
                f64::INFINITY
            }
        }
    }

    fn accept(&mut self, t_new: f64) {
        std::mem::swap(&mut self.x, &mut self.x_new);
        self.sys.rhs(t_new, &self.x, &mut self.fx);
        self.prepared = false;
    }

    fn f_evals(&self) -> u64 {
        self.sys.evals.get()
    }

    fn work(&self) -> ImplicitWork {
        self.core.work
    }

    /// A singular W = I/(γh) − J is cured by a smaller step unless J is (nearly) singular
    /// at the scale of every h: halve, and let step-size underflow end it.
    fn rejection_factor(&self) -> Option<f64> {
        self.singular.then_some(0.5)
    }

    fn fatal(&self) -> Option<String> {
        if self.bad_jacobian {
            Some("the Jacobian or ∂f/∂t has NaN or ∞ at this state".into())
        } else {
            (self.singular_run >= MAX_SINGULAR)
                .then(|| format!("the matrix I/(γh) − J was singular {MAX_SINGULAR} times running"))
        }
    }
}

pub(crate) struct RadauTrial<'a, S: ?Sized> {
    sys: Counted<'a, S>,
    core: Radau5,
    x: Vec<f64>,
    x_new: Vec<f64>,
    tol: Option<(Tol, RadauTol)>,
    /// an attempt from this state failed before (Newton or error)
    rejected: bool,
    last: Option<Attempt>,
    singular_run: u32,
    h: f64,
}

impl<'a, S: System + ?Sized> RadauTrial<'a, S> {
    pub fn new(sys: &'a S, x0: &[f64]) -> Self {
        Self {
            sys: Counted::new(sys),
            core: Radau5::new(x0.len()),
            x: x0.to_vec(),
            x_new: x0.to_vec(),
            tol: None,
            rejected: false,
            last: None,
            singular_run: 0,
            h: 0.0,
        }
    }

    fn radau_tol(&mut self, tol: Tol) -> RadauTol {
        match self.tol {
            Some((t, r)) if t == tol => r,
            _ => {
                let r = RadauTol::from_user(tol.rtol, tol.atol);
                self.tol = Some((tol, r));
                r
            }
        }
    }
}

impl<S: System + ?Sized> Trial for RadauTrial<'_, S> {
    const NONFINITE: &'static str =
        "Newton did not converge (or f returned NaN or ∞) however small the step";

    fn state(&self) -> &[f64] {
        &self.x
    }

    fn candidate(&self) -> &[f64] {
        &self.x_new
    }

    fn start(&mut self, t: f64) {
        self.core.start(&self.sys, t, &self.x);
    }

    /// HINIT for the order-3 estimate (as scipy's Radau); RADAU5 itself starts at 1e-6.
    fn initial_step(&mut self, t: f64, t_end: f64, tol: Tol) -> f64 {
        hairer_initial_step(&self.sys, t, t_end, &self.x, &self.core.fx, 3, tol)
    }

    fn attempt(&mut self, t: f64, h: f64, tol: Tol) -> f64 {
        let rtol = self.radau_tol(tol);
        if self.rejected {
            self.core.reject();
        }
        self.h = h;
        let a = self.core.attempt(
            &self.sys,
            t,
            &self.x,
            h,
            rtol,
            self.rejected,
            &mut self.x_new,
        );
        self.last = Some(a);
        // until accept() says otherwise, this attempt counts as rejected
        self.rejected = true;
        match a {
            Attempt::Converged { err, .. } => {
                self.singular_run = 0;
                err
            }
            Attempt::Retry { .. } => {
                self.singular_run = 0;
                f64::INFINITY
            }
            Attempt::Singular => {
                self.singular_run += 1;
                f64::INFINITY
            }
            Attempt::JacobianNotFinite => f64::INFINITY,
        }
    }

    fn accept(&mut self, t_new: f64) {
        std::mem::swap(&mut self.x, &mut self.x_new);
        self.core.accept(&self.sys, t_new, &self.x, self.h);
        self.rejected = false;
    }

    fn f_evals(&self) -> u64 {
        self.sys.evals.get()
    }

    fn work(&self) -> ImplicitWork {
        self.core.work
    }

    /// RADAU5's FAC = min(SAFE, CFAC/(NEWT + 2·NIT)), CFAC = SAFE·(1 + 2·NIT).
    fn safety_scale(&self) -> f64 {
        match self.last {
            Some(Attempt::Converged {
                newton_iterations, ..
            }) => {
                let nit = NIT as f64;
                ((1.0 + 2.0 * nit) / (newton_iterations as f64 + 2.0 * nit)).min(1.0)
            }
            _ => 1.0,
        }
    }

    /// Newton's own factor; a rejected first step shrinks tenfold (radau5.f).
    fn rejection_factor(&self) -> Option<f64> {
        match self.last {
            Some(Attempt::Retry { factor }) => Some(factor),
            Some(Attempt::Singular) => Some(0.5),
            Some(Attempt::Converged { .. }) if self.core.is_first() => Some(0.1),
            _ => None,
        }
    }

    fn fatal(&self) -> Option<String> {
        if self.last == Some(Attempt::JacobianNotFinite) {
            return Some("the Jacobian has NaN or ∞ at this state".into());
        }
        (self.singular_run >= MAX_SINGULAR).then(|| {
            format!(
                "the Newton matrix was singular {MAX_SINGULAR} times running (step h = {:e})",
                self.h
            )
        })
    }
}
