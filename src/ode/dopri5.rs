//! Adaptive Dormand–Prince 5(4) with the standard error control of Hairer, Nørsett & Wanner
//! (I, II.4): scaled RMS error norm with `atol + rtol·max(|x|, |x_new|)`, step factor
//! 0.9·err^(−1/5) limited to [0.2, 10], no growth right after a rejection; FSAL saves one
//! evaluation per accepted step.

use super::System;
use super::tableau::{DP_A, DP_C, DP_E};

pub struct Dopri5 {
    n: usize,
    k: Vec<f64>,
    stage_x: Vec<f64>,
    x_new: Vec<f64>,
    /// whether k[0] holds f(t, x) for the current state (first same as last)
    fsal_valid: bool,
    pub rtol: f64,
    pub atol: f64,
}

/// The result of one attempted step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Attempt {
    pub accepted: bool,
    /// the step size to try next
    pub h_next: f64,
    /// scaled error norm (≤ 1 means accepted)
    pub err: f64,
}

impl Dopri5 {
    pub fn new(n: usize, rtol: f64, atol: f64) -> Self {
        Self {
            n,
            k: vec![0.0; 7 * n],
            stage_x: vec![0.0; n],
            x_new: vec![0.0; n],
            fsal_valid: false,
            rtol,
            atol,
        }
    }

    /// Forget the cached derivative (call when x is changed from outside).
    pub fn reset(&mut self) {
        self.fsal_valid = false;
    }

    /// Hairer's initial step guess (two f-evaluations).
    pub fn initial_step<S: System + ?Sized>(
        &mut self,
        sys: &S,
        t: f64,
        x: &[f64],
        t_end: f64,
    ) -> f64 {
        let n = self.n;
        let span = (t_end - t).abs();
        sys.rhs(t, x, &mut self.k[..n]);
        self.fsal_valid = true;
        let sc = |i: usize| self.atol + self.rtol * x[i].abs();
        let rms = |v: &dyn Fn(usize) -> f64| {
            ((0..n).map(|i| (v(i) / sc(i)).powi(2)).sum::<f64>() / n as f64).sqrt()
        };
        let d0 = rms(&|i| x[i]);
        let d1 = rms(&|i| self.k[i]);
        let mut h0 = if d0 < 1e-5 || d1 < 1e-5 {
            1e-6
        } else {
            0.01 * d0 / d1
        };
        h0 = h0.min(span);
        for i in 0..n {
            self.stage_x[i] = x[i] + h0 * self.k[i];
        }
        let (f0, rest) = self.k.split_at_mut(n);
        sys.rhs(t + h0, &self.stage_x, &mut rest[..n]);
        let d2 = ((0..n)
            .map(|i| ((rest[i] - f0[i]) / (self.atol + self.rtol * x[i].abs())).powi(2))
            .sum::<f64>()
            / n as f64)
            .sqrt()
            / h0;
        let m = d1.max(d2);
        let h1 = if m <= 1e-15 {
            (h0 * 1e-3).max(1e-6)
        } else {
            (0.01 / m).powf(0.2)
        };
        (100.0 * h0).min(h1).min(span)
    }

    /// Tries a step of size h from (t, x); on acceptance x is advanced in place.
    pub fn try_step<S: System + ?Sized>(
        &mut self,
        sys: &S,
        t: f64,
        x: &mut [f64],
        h: f64,
        after_reject: bool,
    ) -> Attempt {
        let n = self.n;
        if !self.fsal_valid {
            sys.rhs(t, x, &mut self.k[..n]);
            self.fsal_valid = true;
        }
        for i in 1..7 {
            self.stage_x.copy_from_slice(x);
            for (j, &a) in DP_A[i][..i].iter().enumerate() {
                if a != 0.0 {
                    let kj = &self.k[j * n..(j + 1) * n];
                    for (xs, kv) in self.stage_x.iter_mut().zip(kj) {
                        *xs += h * a * kv;
                    }
                }
            }
            if i == 6 {
                // the seventh stage is evaluated at the new solution (FSAL)
                self.x_new.copy_from_slice(&self.stage_x);
            }
            let (_, rest) = self.k.split_at_mut(i * n);
            sys.rhs(t + DP_C[i] * h, &self.stage_x, &mut rest[..n]);
        }
        let mut sum = 0.0;
        for i in 0..n {
            let mut e = 0.0;
            for (s, &w) in DP_E.iter().enumerate() {
                e += w * self.k[s * n + i];
            }
            let sc = self.atol + self.rtol * x[i].abs().max(self.x_new[i].abs());
            sum += (h * e / sc).powi(2);
        }
        let err = (sum / n as f64).sqrt();
        let fac_max = if after_reject { 1.0 } else { 10.0 };
        if err.is_finite() && err <= 1.0 {
            let fac = if err == 0.0 {
                fac_max
            } else {
                (0.9 * err.powf(-0.2)).clamp(0.2, fac_max)
            };
            x.copy_from_slice(&self.x_new);
            // FSAL: stage 7 is f at the new state
            let (k0, rest) = self.k.split_at_mut(n);
            k0.copy_from_slice(&rest[5 * n..6 * n]);
            Attempt {
                accepted: true,
                h_next: h * fac,
                err,
            }
        } else {
            let fac = if err.is_finite() {
                (0.9 * err.powf(-0.2)).clamp(0.2, 1.0)
            } else {
                0.2
            };
            Attempt {
                accepted: false,
                h_next: h * fac,
                err,
            }
        }
    }
}
