//! Adaptive implicit methods for stiff problems, both run by the one adaptive loop
//! (`ode::adaptive`):
//!
//! | method | scheme | per step | error estimate |
//! |---|---|---|---|
//! | `rodas5p` | Rosenbrock (linearly implicit), 8 stages, order 5, stiffly accurate, L-stable | 1 Jacobian + ∂f/∂t, 1 real LU, 8 f | embedded order 4 |
//! | `radau5` | Radau IIA collocation, 3 stages, order 5, L-stable | simplified Newton: 1 real + 1 complex LU per new matrix, Jacobian reused across steps | Hairer's ESTRAD |
//!
//! Jacobians come from the system (`System::jacobian`: exact for problem files and inline
//! ODEs, differentiated from their compiled program; native problems give theirs), else
//! forward differences, whose n f-evaluations are counted with the others.

pub mod radau5;
pub mod rodas5p;

use super::System;
use super::implicit::forward_difference_jacobian;

/// ∂f/∂x at (t, x) into `jac` (row-major), where `fx` = f(t, x): the system's own, else forward
/// differences (`x` is restored; `fp` is scratch).
pub(crate) fn jacobian_at<S: System + ?Sized>(
    sys: &S,
    t: f64,
    x: &mut [f64],
    fx: &[f64],
    fp: &mut [f64],
    jac: &mut [f64],
) {
    if !sys.jacobian(t, x, jac) {
        forward_difference_jacobian(sys, t, x, fx, fp, jac);
    }
}

/// ∂f/∂t at (t, x) into `out`: the system's own, else a forward difference in t (one
/// f-evaluation).
pub(crate) fn time_derivative_at<S: System + ?Sized>(
    sys: &S,
    t: f64,
    x: &[f64],
    fx: &[f64],
    out: &mut [f64],
) {
    if !sys.time_derivative(t, x, out) {
        let dt0 = (f64::EPSILON * t.abs().max(1e-5)).sqrt();
        let dt = (t + dt0) - t;
        sys.rhs(t + dt, x, out);
        for (o, f) in out.iter_mut().zip(fx) {
            *o = (*o - f) / dt;
        }
    }
}

/// Work of an implicit method beyond f-evaluations.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ImplicitWork {
    /// Jacobian evaluations (analytic or by differences)
    pub jac_evals: u64,
    /// LU decompositions (RADAU5: a real and a complex one count as one new matrix each)
    pub lu_decomps: u64,
}
