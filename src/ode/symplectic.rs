//! Symplectic methods for second-order systems: the state is (q, v), both of length n/2, and
//! the right-hand side is f(q, v) = (v, a(q, v, t)). They keep the energy error of a
//! Hamiltonian system bounded for all time instead of letting it drift.

use super::System;

/// Semi-implicit (symplectic) Euler: v ← v + h a(q, v), then q ← q + h v (the new v).
/// One f-evaluation per step.
pub struct SymplecticEuler {
    f: Vec<f64>,
}

impl SymplecticEuler {
    pub fn new(n: usize) -> Self {
        Self { f: vec![0.0; n] }
    }

    pub fn step<S: System + ?Sized>(&mut self, sys: &S, t: f64, x: &mut [f64], h: f64) {
        let m = x.len() / 2;
        sys.rhs(t, x, &mut self.f);
        let (q, v) = x.split_at_mut(m);
        for (vi, ai) in v.iter_mut().zip(&self.f[m..]) {
            *vi += h * ai;
        }
        for (qi, vi) in q.iter_mut().zip(v.iter()) {
            *qi += h * vi;
        }
    }
}

/// Velocity Verlet (Störmer–Verlet, kick-drift-kick), second order:
/// v½ = v + h/2 a(q), q ← q + h v½, v ← v½ + h/2 a(q_new).
/// The acceleration at the end of a step is cached for the next one, so a run of steps
/// costs one f-evaluation per step (plus one at the start).
pub struct Verlet {
    f: Vec<f64>,
    /// state and time at which `f` was last evaluated; the cache is valid while x matches
    cached_x: Vec<f64>,
    cached_t: f64,
    cache_valid: bool,
}

impl Verlet {
    pub fn new(n: usize) -> Self {
        Self {
            f: vec![0.0; n],
            cached_x: vec![0.0; n],
            cached_t: f64::NAN,
            cache_valid: false,
        }
    }

    pub fn step<S: System + ?Sized>(&mut self, sys: &S, t: f64, x: &mut [f64], h: f64) {
        let m = x.len() / 2;
        let reuse = self.cache_valid
            && self.cached_x.as_slice() == &*x
            && (self.cached_t - t).abs() <= 1e-12 * (1.0 + t.abs());
        if !reuse {
            sys.rhs(t, x, &mut self.f);
        }
        {
            let (q, v) = x.split_at_mut(m);
            for (vi, ai) in v.iter_mut().zip(&self.f[m..]) {
                *vi += 0.5 * h * ai;
            }
            for (qi, vi) in q.iter_mut().zip(v.iter()) {
                *qi += h * vi;
            }
        }
        sys.rhs(t + h, x, &mut self.f);
        let (_, v) = x.split_at_mut(m);
        for (vi, ai) in v.iter_mut().zip(&self.f[m..]) {
            *vi += 0.5 * h * ai;
        }
        self.cached_x.copy_from_slice(x);
        self.cached_t = t + h;
        self.cache_valid = true;
    }
}
