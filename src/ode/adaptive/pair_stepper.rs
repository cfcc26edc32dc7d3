//! Trying steps of an embedded pair, written once for both state representations: `[f64; N]`
//! (the fast path: every length a compile-time constant, f inlined) and `Vec<f64>` (any n,
//! f behind [`System`]). The pair is a type, so its coefficients are constants: each stage is
//! its own instance of [`PairStepper::stage`] (const index), and zero coefficients drop out of
//! the sums at compile time.

use std::marker::PhantomData;

use super::{Tol, Trial, initial_step_finish, initial_step_start};
use crate::ode::System;
use crate::ode::fixed::FixedSystem;
use crate::ode::pairs::Pair;

/// Evaluates f for one state representation.
pub(crate) trait Rhs<V> {
    fn eval(&self, t: f64, x: &V, out: &mut V);
}

/// A [`FixedSystem`] over `[f64; N]`.
pub(crate) struct Fast<'a, S: ?Sized>(pub &'a S);

impl<const N: usize, S: FixedSystem<N> + ?Sized> Rhs<[f64; N]> for Fast<'_, S> {
    #[inline(always)]
    fn eval(&self, t: f64, x: &[f64; N], out: &mut [f64; N]) {
        *out = self.0.rhs(t, x);
    }
}

/// A [`System`] over `Vec<f64>`.
pub(crate) struct Slices<'a, S: ?Sized>(pub &'a S);

impl<S: System + ?Sized> Rhs<Vec<f64>> for Slices<'_, S> {
    #[inline(always)]
    fn eval(&self, t: f64, x: &Vec<f64>, out: &mut Vec<f64>) {
        self.0.rhs(t, x, out);
    }
}

/// `out = x + h Σ_{j<upto} w_j k_j` (Hairer's order of operations: the weighted sum first).
#[inline(always)]
fn combine<const S: usize, V: AsRef<[f64]>>(
    x: &[f64],
    h: f64,
    w: &[f64; S],
    upto: usize,
    k: &[V; S],
    out: &mut [f64],
) {
    for m in 0..out.len() {
        let mut acc = 0.0;
        for j in 0..upto {
            if w[j] != 0.0 {
                acc += w[j] * k[j].as_ref()[m];
            }
        }
        out[m] = x[m] + h * acc;
    }
}

/// State, candidate and stage derivatives of one pair on one representation.
pub(crate) struct PairStepper<const S: usize, P, V, F> {
    f: F,
    x: V,
    x_new: V,
    xs: V,
    k: [V; S],
    evals: u64,
    _pair: PhantomData<P>,
}

impl<const S: usize, P, V, F> PairStepper<S, P, V, F>
where
    P: Pair<S>,
    V: AsRef<[f64]> + AsMut<[f64]> + Clone,
    F: Rhs<V>,
{
    pub fn new(_pair: P, f: F, x0: V) -> Self {
        Self {
            f,
            x_new: x0.clone(),
            xs: x0.clone(),
            k: std::array::from_fn(|_| x0.clone()),
            x: x0,
            evals: 0,
            _pair: PhantomData,
        }
    }

    /// Stage I (1 ≤ I < S): k_I = f(t + c_I h, x + h Σ_j a_Ij k_j). The FSAL pairs' last stage
    /// is taken at the candidate itself, which it equals.
    #[inline(always)]
    fn stage<const I: usize>(&mut self, t: f64, h: f64) {
        if I >= S {
            return;
        }
        let coef = &P::COEF;
        let target = if coef.fsal && I == S - 1 {
            &mut self.x_new
        } else {
            &mut self.xs
        };
        combine(self.x.as_ref(), h, &coef.a[I], I, &self.k, target.as_mut());
        let (_, rest) = self.k.split_at_mut(I);
        self.f.eval(t + coef.c[I] * h, target, &mut rest[0]);
    }

    /// The scaled RMS norm of the error estimate (DOP853: Hairer's blend of its 5th- and
    /// 3rd-order estimates, `err5² / √(err5² + 0.01 err3²)`).
    #[inline(always)]
    fn error_norm(&self, h: f64, tol: Tol) -> f64 {
        let coef = &P::COEF;
        let (x, x_new) = (self.x.as_ref(), self.x_new.as_ref());
        let n = x.len();
        let (mut sum5, mut sum3) = (0.0, 0.0);
        for m in 0..n {
            let sc = tol.atol + tol.rtol * x[m].abs().max(x_new[m].abs());
            let mut e = 0.0;
            for j in 0..S {
                if coef.e[j] != 0.0 {
                    e += coef.e[j] * self.k[j].as_ref()[m];
                }
            }
            sum5 += (e / sc) * (e / sc);
            if let Some(e3) = &coef.e3 {
                let mut e = 0.0;
                for (w, k) in e3.iter().zip(&self.k) {
                    if *w != 0.0 {
                        e += w * k.as_ref()[m];
                    }
                }
                sum3 += (e / sc) * (e / sc);
            }
        }
        if coef.e3.is_some() {
            let deno = sum5 + 0.01 * sum3;
            let deno = if deno > 0.0 { deno } else { 1.0 };
            h.abs() * sum5 * (1.0 / (n as f64 * deno)).sqrt()
        } else {
            h.abs() * (sum5 / n as f64).sqrt()
        }
    }
}

impl<const S: usize, P, V, F> Trial for PairStepper<S, P, V, F>
where
    P: Pair<S>,
    V: AsRef<[f64]> + AsMut<[f64]> + Clone,
    F: Rhs<V>,
{
    const NONFINITE: &'static str = "the right-hand side returned NaN or ∞ however small the step";

    fn state(&self) -> &[f64] {
        self.x.as_ref()
    }

    fn candidate(&self) -> &[f64] {
        self.x_new.as_ref()
    }

    fn start(&mut self, t: f64) {
        self.f.eval(t, &self.x, &mut self.k[0]);
        self.evals += 1;
    }

    /// Hairer's HINIT (`adaptive::initial_step_start`): one f-evaluation (k₁ is there).
    fn initial_step(&mut self, t: f64, t_end: f64, tol: Tol) -> f64 {
        let span = t_end - t;
        let (h0, d1) = initial_step_start(self.x.as_ref(), self.k[0].as_ref(), span, tol);
        {
            let (x, f0) = (self.x.as_ref(), self.k[0].as_ref());
            let xs = self.xs.as_mut();
            for i in 0..xs.len() {
                xs[i] = x[i] + h0 * f0[i];
            }
        }
        let (first, rest) = self.k.split_at_mut(1);
        self.f.eval(t + h0, &self.xs, &mut rest[0]);
        self.evals += 1;
        let (f0, f1) = (first[0].as_ref(), rest[0].as_ref());
        initial_step_finish(self.x.as_ref(), f0, f1, h0, d1, P::COEF.order, span, tol)
    }

    #[inline]
    fn attempt(&mut self, t: f64, h: f64, tol: Tol) -> f64 {
        // one const-indexed instance per stage; those ≥ S return at once (compile time)
        self.stage::<1>(t, h);
        self.stage::<2>(t, h);
        self.stage::<3>(t, h);
        self.stage::<4>(t, h);
        self.stage::<5>(t, h);
        self.stage::<6>(t, h);
        self.stage::<7>(t, h);
        self.stage::<8>(t, h);
        self.stage::<9>(t, h);
        self.stage::<10>(t, h);
        self.stage::<11>(t, h);
        self.stage::<12>(t, h);
        self.stage::<13>(t, h);
        self.stage::<14>(t, h);
        self.stage::<15>(t, h);
        const { assert!(S <= 16, "stage list above covers pairs of up to 16 stages") };
        self.evals += S as u64 - 1;
        if !P::COEF.fsal {
            combine(
                self.x.as_ref(),
                h,
                &P::COEF.b,
                S,
                &self.k,
                self.x_new.as_mut(),
            );
        }
        self.error_norm(h, tol)
    }

    #[inline]
    fn accept(&mut self, t_new: f64) {
        std::mem::swap(&mut self.x, &mut self.x_new);
        if P::COEF.fsal {
            // the last stage was f(t + h, x_new)
            self.k.swap(0, S - 1);
        } else {
            self.f.eval(t_new, &self.x, &mut self.k[0]);
            self.evals += 1;
        }
    }

    fn f_evals(&self) -> u64 {
        self.evals
    }

    /// Hairer's test (dopri5.f, dop853.f): after the step, h·|λ| ≈ h·‖f(x_new) − f(y)‖ / ‖x_new
    /// − y‖, y the argument of the last stage before the new state that is also at t + h.
    fn stiffness(&self, h: f64) -> Option<f64> {
        let limit = P::STIFF_LIMIT?;
        let coef = &P::COEF;
        // after accept: k[0] = f(x_new); that stage's f (an FSAL pair swapped its last into
        // k[0] and keeps the one before) and argument (xs) are untouched
        let idx = if coef.fsal { S - 2 } else { S - 1 };
        if coef.c[idx] != 1.0 {
            return None;
        }
        let (x, xs, f_new, f_stage) = (
            self.x.as_ref(),
            self.xs.as_ref(),
            self.k[0].as_ref(),
            self.k[idx].as_ref(),
        );
        let (mut num, mut den) = (0.0, 0.0);
        for m in 0..x.len() {
            num += (f_new[m] - f_stage[m]).powi(2);
            den += (x[m] - xs[m]).powi(2);
        }
        (den > 0.0).then(|| h.abs() * (num / den).sqrt() / limit)
    }
}
