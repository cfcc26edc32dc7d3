//! Implicit Euler and implicit midpoint for stiff problems. Both solve
//! y = x + θh f(t + θh, y) by Newton's method (θ = 1: implicit Euler, x' = y;
//! θ = ½: implicit midpoint, x' = 2y − x). The Jacobian is the system's analytic one when it
//! has one, else forward differences; dense LU with partial pivoting (small n).

use super::System;

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
    jac: Vec<f64>,
    piv: Vec<usize>,
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
            jac: vec![0.0; n * n],
            piv: vec![0; n],
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
            if !sys.jacobian(ts, &self.y, &mut self.jac) {
                self.fd_jacobian(sys, ts);
            }
            for v in self.jac.iter_mut() {
                *v *= -th;
            }
            for i in 0..n {
                self.jac[i * n + i] += 1.0;
            }
            lu_solve(&mut self.jac, &mut self.piv, &mut self.res, n)?;
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

    /// Forward differences, column by column, around `self.y` where f is in `self.f`.
    fn fd_jacobian<S: System + ?Sized>(&mut self, sys: &S, t: f64) {
        let n = self.n;
        for j in 0..n {
            let yj = self.y[j];
            let dy = f64::EPSILON.sqrt() * yj.abs().max(1.0);
            self.y[j] = yj + dy;
            sys.rhs(t, &self.y, &mut self.fp);
            self.y[j] = yj;
            for i in 0..n {
                self.jac[i * n + j] = (self.fp[i] - self.f[i]) / dy;
            }
        }
    }
}

/// Solves M d = r in place (r becomes d); M is overwritten by its LU factors.
fn lu_solve(m: &mut [f64], piv: &mut [usize], r: &mut [f64], n: usize) -> Result<(), NewtonError> {
    for k in 0..n {
        let mut p = k;
        for i in k + 1..n {
            if m[i * n + k].abs() > m[p * n + k].abs() {
                p = i;
            }
        }
        piv[k] = p;
        if m[p * n + k] == 0.0 || !m[p * n + k].is_finite() {
            return Err(NewtonError::Singular);
        }
        if p != k {
            for j in 0..n {
                m.swap(k * n + j, p * n + j);
            }
            r.swap(k, p);
        }
        let d = m[k * n + k];
        for i in k + 1..n {
            let f = m[i * n + k] / d;
            if f != 0.0 {
                for j in k + 1..n {
                    m[i * n + j] -= f * m[k * n + j];
                }
                r[i] -= f * r[k];
            }
        }
    }
    for i in (0..n).rev() {
        let mut acc = r[i];
        for j in i + 1..n {
            acc -= m[i * n + j] * r[j];
        }
        r[i] = acc / m[i * n + i];
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ode::FnSystem;

    #[test]
    fn lu_solves_a_pivoting_system() {
        let mut m = vec![0.0, 2.0, 1.0, 1.0];
        let mut piv = vec![0; 2];
        let mut r = vec![4.0, 3.0];
        lu_solve(&mut m, &mut piv, &mut r, 2).unwrap();
        assert!((r[0] - 1.0).abs() < 1e-15 && (r[1] - 2.0).abs() < 1e-15);
    }

    #[test]
    fn implicit_euler_on_decay_is_one_over_one_minus_z() {
        let sys = FnSystem::new(1, |_t, x: &[f64], d: &mut [f64]| d[0] = -1e6 * x[0]);
        let mut s = Implicit::new(1.0, 1);
        let mut x = [1.0];
        s.step(&sys, 0.0, &mut x, 0.1).unwrap();
        assert!((x[0] - 1.0 / (1.0 + 1e5)).abs() < 1e-15);
    }
}
