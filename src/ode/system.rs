//! What an integrator integrates: a right-hand side f(t, x) written into a caller's buffer.

/// A first-order system ẋ = f(x, t) of fixed dimension.
pub trait System {
    /// Number of f64 values in the state.
    fn dim(&self) -> usize;
    /// Writes f(t, x) into `dxdt` (both of length `dim()`).
    fn rhs(&self, t: f64, x: &[f64], dxdt: &mut [f64]);
}

/// A system from a closure, for tests, widgets and native benchmarks.
pub struct FnSystem<F> {
    pub dim: usize,
    pub f: F,
}

impl<F: Fn(f64, &[f64], &mut [f64])> FnSystem<F> {
    pub fn new(dim: usize, f: F) -> Self {
        Self { dim, f }
    }
}

impl<F: Fn(f64, &[f64], &mut [f64])> System for FnSystem<F> {
    fn dim(&self) -> usize {
        self.dim
    }
    fn rhs(&self, t: f64, x: &[f64], dxdt: &mut [f64]) {
        (self.f)(t, x, dxdt)
    }
}

impl<S: System + ?Sized> System for &S {
    fn dim(&self) -> usize {
        (**self).dim()
    }
    fn rhs(&self, t: f64, x: &[f64], dxdt: &mut [f64]) {
        (**self).rhs(t, x, dxdt)
    }
}
