//! Implicit Euler and implicit midpoint for stiff problems. Both solve
//! y = x + θh f(t + θh, y) by Newton's method (θ = 1: implicit Euler, x' = y;
//! θ = ½: implicit midpoint, x' = 2y − x). The Jacobian is the system's analytic one when it
//! has one, else forward differences; dense LU with partial pivoting (`ode::linalg`).

use super::System;
use super::linalg::Lu;

/// Why an implicit step could not be taken.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NewtonError {
    Singular,
    NoConvergence,
}

impl NewtonError {
    pub fn message(self) -> &'static str {
        match self {
            NewtonError::Singular => "Newton matrix I − θh J is singular",
            NewtonError::NoConvergence => "Newton iteration did not converge",
        }
    }
}

pub struct Implicit {
    theta: f64,
    n: usize,
    y: Vec<f64>,
    f: Vec<f64>,
    fp: Vec<f64>,
    res: Vec<f64>,
    lu: Lu,
    pub max_iter: usize,
}

impl Implicit {
    /// `theta = 1.0`: implicit Euler; `theta = 0.5`: implicit midpoint.
    pub fn new(theta: f64, n: usize) -> Self {
        Self {
            theta,
            n,
            y: vec![0.0; n],
            f: vec![0.0; n],
            fp: vec![0.0; n],
            res: vec![0.0; n],
            lu: Lu::new(n),
            max_iter: 30,
        }
    }

    /// One step of size h. Where Newton fails (e.g. at a fold of the slow manifold, where
    /// Van der Pol jumps), the rest of the step is covered by substeps, halved until Newton
    /// converges (at most 2^30 of them) and never grown again within this step: a large
    /// step started in the middle of a fast transient finds a spurious root. The evaluations
    /// of failed attempts count too.
    pub fn step<S: System + ?Sized>(
        &mut self,
        sys: &S,
        t: f64,
        x: &mut [f64],
        h: f64,
    ) -> Result<(), NewtonError> {
        let mut done = 0.0;
        let mut sub = h;
        let min_sub = h * (0.5f64).powi(30);
        while done < h {
            let this = sub.min(h - done);
            match self.newton_step(sys, t + done, x, this) {
                Ok(()) => done += this,
                Err(e) => {
                    sub *= 0.5;
                    if sub < min_sub {
                        return Err(e);
                    }
                }
            }
        }
        Ok(())
    }

    /// A single Newton solve; leaves x untouched on failure.
    fn newton_step<S: System + ?Sized>(
        &mut self,
        sys: &S,
        t: f64,
        x: &mut [f64],
        h: f64,
    ) -> Result<(), NewtonError> {
        let n = self.n;
        let th = self.theta * h;
        let ts = t + th;
        self.y.copy_from_slice(x);
        let mut converged = false;
        let mut prev_size = f64::INFINITY;
        for _ in 0..self.max_iter {
            // residual G(y) = y − x − θh f(y); Newton matrix M = I − θh J(y)
            sys.rhs(ts, &self.y, &mut self.f);
            for i in 0..n {
                self.res[i] = self.y[i] - x[i] - th * self.f[i];
            }
            if !sys.jacobian(ts, &self.y, &mut self.lu.m) {
                forward_difference_jacobian(
                    sys,
                    ts,
                    &mut self.y,
                    &self.f,
                    &mut self.fp,
                    &mut self.lu.m,
                );
            }
            for v in self.lu.m.iter_mut() {
                *v *= -th;
            }
            for i in 0..n {
                self.lu.m[i * n + i] += 1.0;
            }
            self.lu.factor().map_err(|_| NewtonError::Singular)?;
            self.lu.solve(&mut self.res);
            let mut size = 0.0f64;
            for i in 0..n {
                self.y[i] -= self.res[i];
                size = size.max(self.res[i].abs() / (1.0 + self.y[i].abs()));
            }
            if !size.is_finite() {
                break;
            }
            // done at 1e-12, or when the updates stop shrinking at round-off level (an
            // ill-conditioned Newton matrix leaves noise well above machine epsilon)
            if size <= 1e-12 || (size <= 1e-8 && size >= 0.5 * prev_size) {
                converged = true;
                break;
            }
            prev_size = size;
        }
        if !converged {
            return Err(NewtonError::NoConvergence);
        }
        let inv = 1.0 / self.theta;
        for i in 0..n {
            x[i] += (self.y[i] - x[i]) * inv;
        }
        Ok(())
    }
}

/// Forward differences ∂f/∂x column by column around `y`, where `f` = f(t, y); n extra
/// f-evaluations (counted by a [`Counted`](super::Counted) system). `y` is restored.
pub(crate) fn forward_difference_jacobian<S: System + ?Sized>(
    sys: &S,
    t: f64,
    y: &mut [f64],
    f: &[f64],
    fp: &mut [f64],
    jac: &mut [f64],
) {
    let n = y.len();
    for j in 0..n {
        let yj = y[j];
        // Hairer's increment (radau5.f): √(ε · max(1e-5, |y_j|))
        let dy = (f64::EPSILON * yj.abs().max(1e-5)).sqrt();
        y[j] = yj + dy;
        // the step actually taken, after rounding
        let dy = y[j] - yj;
        sys.rhs(t, y, fp);
        y[j] = yj;
        for i in 0..n {
            jac[i * n + j] = (fp[i] - f[i]) / dy;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ode::FnSystem;

    #[test]
    fn implicit_euler_on_decay_is_one_over_one_minus_z() {
        let sys = FnSystem::new(1, |_t, x: &[f64], d: &mut [f64]| d[0] = -1e6 * x[0]);
        let mut s = Implicit::new(1.0, 1);
        let mut x = [1.0];
        s.step(&sys, 0.0, &mut x, 0.1).unwrap();
        assert!((x[0] - 1.0 / (1.0 + 1e5)).abs() < 1e-15);
    }
}
