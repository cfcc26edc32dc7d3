//! Stepping any explicit Runge–Kutta tableau, allocation-free.

use super::{System, Tableau};

/// A stepper for one tableau and one state dimension; owns its stage buffers.
pub struct ExplicitRk {
    tableau: Tableau,
    n: usize,
    /// stage derivatives, `stages × n`, row-major
    k: Vec<f64>,
    stage_x: Vec<f64>,
}

impl ExplicitRk {
    pub fn new(tableau: Tableau, n: usize) -> Self {
        let s = tableau.stages();
        Self {
            tableau,
            n,
            k: vec![0.0; s * n],
            stage_x: vec![0.0; n],
        }
    }

    pub fn tableau(&self) -> &Tableau {
        &self.tableau
    }

    /// Advances `x` from `t` to `t + h` in place. Costs `stages()` evaluations of f.
    pub fn step<S: System + ?Sized>(&mut self, sys: &S, t: f64, x: &mut [f64], h: f64) {
        let n = self.n;
        debug_assert_eq!(x.len(), n);
        let tab = &self.tableau;
        for i in 0..tab.stages() {
            self.stage_x.copy_from_slice(x);
            for j in 0..i {
                let a = tab.a[i][j];
                if a != 0.0 {
                    let kj = &self.k[j * n..(j + 1) * n];
                    for (xs, kv) in self.stage_x.iter_mut().zip(kj) {
                        *xs += h * a * kv;
                    }
                }
            }
            let (_, rest) = self.k.split_at_mut(i * n);
            sys.rhs(t + tab.c[i] * h, &self.stage_x, &mut rest[..n]);
        }
        for (i, &b) in tab.b.iter().enumerate() {
            if b != 0.0 {
                let ki = &self.k[i * n..(i + 1) * n];
                for (xv, kv) in x.iter_mut().zip(ki) {
                    *xv += h * b * kv;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ode::FnSystem;

    #[test]
    fn rk4_matches_exp_on_decay() {
        let sys = FnSystem::new(1, |_t, x: &[f64], d: &mut [f64]| d[0] = -x[0]);
        let mut rk = ExplicitRk::new(Tableau::rk4(), 1);
        let mut x = [1.0];
        for i in 0..10 {
            rk.step(&sys, i as f64 * 0.1, &mut x, 0.1);
        }
        assert!((x[0] - (-1.0f64).exp()).abs() < 1e-6);
    }
}

/// Classical RK4 written out stage by stage: the same method as `Tableau::rk4()` in
/// [`ExplicitRk`], without the tableau loops (the hot path of benchmarks and widgets).
pub struct Rk4 {
    k1: Vec<f64>,
    k2: Vec<f64>,
    k3: Vec<f64>,
    k4: Vec<f64>,
    xs: Vec<f64>,
}

impl Rk4 {
    pub fn new(n: usize) -> Self {
        Self {
            k1: vec![0.0; n],
            k2: vec![0.0; n],
            k3: vec![0.0; n],
            k4: vec![0.0; n],
            xs: vec![0.0; n],
        }
    }

    #[inline]
    pub fn step<S: System + ?Sized>(&mut self, sys: &S, t: f64, x: &mut [f64], h: f64) {
        let n = x.len();
        let (k1, k2, k3, k4, xs) = (
            &mut self.k1[..n],
            &mut self.k2[..n],
            &mut self.k3[..n],
            &mut self.k4[..n],
            &mut self.xs[..n],
        );
        let h2 = 0.5 * h;
        sys.rhs(t, x, k1);
        for i in 0..n {
            xs[i] = x[i] + h2 * k1[i];
        }
        sys.rhs(t + h2, xs, k2);
        for i in 0..n {
            xs[i] = x[i] + h2 * k2[i];
        }
        sys.rhs(t + h2, xs, k3);
        for i in 0..n {
            xs[i] = x[i] + h * k3[i];
        }
        sys.rhs(t + h, xs, k4);
        let h6 = h / 6.0;
        for i in 0..n {
            x[i] += h6 * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]);
        }
    }
}
