//! Error control by step doubling for the implicit methods: each step is taken once with h and
//! twice with h/2; their difference / (2^p − 1) estimates the error of the two-half-step
//! result, which is kept. This is what lets an implicit method cross the jumps of a stiff
//! relaxation oscillation (Van der Pol) with few steps elsewhere.

use super::{Tol, Trial};
use crate::ode::pairs::Controller;
use crate::ode::solve::Stepper;
use crate::ode::system::Counted;
use crate::ode::{Method, System};

pub(crate) struct Doubling<'a, S: ?Sized> {
    sys: Counted<'a, S>,
    stepper: Stepper,
    x: Vec<f64>,
    full: Vec<f64>,
    half: Vec<f64>,
    /// 1 / (2^p − 1)
    richardson: f64,
}

impl<'a, S: System + ?Sized> Doubling<'a, S> {
    pub fn new(sys: &'a S, method: Method, x0: &[f64]) -> Self {
        let n = x0.len();
        Self {
            sys: Counted::new(sys),
            stepper: Stepper::new(method, n),
            x: x0.to_vec(),
            full: vec![0.0; n],
            half: x0.to_vec(),
            richardson: (2f64.powi(method.order() as i32) - 1.0).recip(),
        }
    }

    /// Safety 0.9, exponent 1/(p + 1) (the two-half-step error is O(h^(p+1))), step ratio in
    /// [0.2, 4].
    pub fn controller(method: Method) -> Controller {
        Controller {
            safety: 0.9,
            fac_min: 0.2,
            fac_max: 4.0,
            alpha: 1.0 / (method.order() as f64 + 1.0),
            beta: 0.0,
            predictive: false,
            hold: 1.0,
        }
    }
}

impl<S: System + ?Sized> Trial for Doubling<'_, S> {
    const NONFINITE: &'static str =
        "no step converged (Newton failed, or f returned NaN or ∞) however small the step";

    fn state(&self) -> &[f64] {
        &self.x
    }

    fn candidate(&self) -> &[f64] {
        &self.half
    }

    fn start(&mut self, _t: f64) {}

    /// A ten-thousandth of the span: a stiff problem's f says little about a good first step.
    fn initial_step(&mut self, t: f64, t_end: f64, _tol: Tol) -> f64 {
        ((t_end - t) * 1e-4).max(1e-12).min(t_end - t)
    }

    fn attempt(&mut self, t: f64, h: f64, tol: Tol) -> f64 {
        self.full.copy_from_slice(&self.x);
        self.half.copy_from_slice(&self.x);
        let sys = &self.sys;
        let ok = self.stepper.step(sys, t, &mut self.full, h).is_ok()
            && self.stepper.step(sys, t, &mut self.half, 0.5 * h).is_ok()
            && self
                .stepper
                .step(sys, t + 0.5 * h, &mut self.half, 0.5 * h)
                .is_ok();
        if !ok {
            return f64::INFINITY;
        }
        let n = self.x.len();
        let sum: f64 = (0..n)
            .map(|i| {
                let sc = tol.atol + tol.rtol * self.x[i].abs().max(self.half[i].abs());
                ((self.half[i] - self.full[i]) * self.richardson / sc).powi(2)
            })
            .sum();
        (sum / n as f64).sqrt()
    }

    fn accept(&mut self, _t_new: f64) {
        std::mem::swap(&mut self.x, &mut self.half);
    }

    fn f_evals(&self) -> u64 {
        self.sys.evals.get()
    }
}
