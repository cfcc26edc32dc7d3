//! What an integrator integrates: a right-hand side f(t, x) written into a caller's buffer.

/// A first-order system ẋ = f(x, t) of fixed dimension.
pub trait System {
    /// Number of f64 values in the state.
    fn dim(&self) -> usize;
    /// Writes f(t, x) into `dxdt` (both of length `dim()`).
    fn rhs(&self, t: f64, x: &[f64], dxdt: &mut [f64]);
    /// Writes the Jacobian ∂f_i/∂x_j row-major into `jac` (`dim()²` values) and returns true,
    /// or returns false when there is no analytic one (implicit methods then use differences).
    fn jacobian(&self, _t: f64, _x: &[f64], _jac: &mut [f64]) -> bool {
        false
    }
    /// Writes ∂f/∂t into `dfdt` and returns true, or returns false when there is no analytic
    /// one (Rosenbrock methods then take a forward difference in t, one counted f-evaluation).
    fn time_derivative(&self, _t: f64, _x: &[f64], _dfdt: &mut [f64]) -> bool {
        false
    }
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
    fn jacobian(&self, t: f64, x: &[f64], jac: &mut [f64]) -> bool {
        (**self).jacobian(t, x, jac)
    }
    fn time_derivative(&self, t: f64, x: &[f64], dfdt: &mut [f64]) -> bool {
        (**self).time_derivative(t, x, dfdt)
    }
}

/// Counts the f-evaluations and analytic Jacobian evaluations of a wrapped system (`Cell`s,
/// so stepping stays `&self`).
pub struct Counted<'a, S: ?Sized> {
    pub sys: &'a S,
    pub evals: std::cell::Cell<u64>,
    pub jac_evals: std::cell::Cell<u64>,
}

impl<'a, S: System + ?Sized> Counted<'a, S> {
    pub fn new(sys: &'a S) -> Self {
        Self {
            sys,
            evals: std::cell::Cell::new(0),
            jac_evals: std::cell::Cell::new(0),
        }
    }
}

impl<S: System + ?Sized> System for Counted<'_, S> {
    fn dim(&self) -> usize {
        self.sys.dim()
    }
    #[inline]
    fn rhs(&self, t: f64, x: &[f64], dxdt: &mut [f64]) {
        self.evals.set(self.evals.get() + 1);
        self.sys.rhs(t, x, dxdt)
    }
    fn jacobian(&self, t: f64, x: &[f64], jac: &mut [f64]) -> bool {
        let analytic = self.sys.jacobian(t, x, jac);
        if analytic {
            self.jac_evals.set(self.jac_evals.get() + 1);
        }
        analytic
    }
    fn time_derivative(&self, t: f64, x: &[f64], dfdt: &mut [f64]) -> bool {
        self.sys.time_derivative(t, x, dfdt)
    }
}
