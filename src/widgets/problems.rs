//! The built-in right-hand sides the plot widgets draw, each with its exact solution where one
//! exists (the error the widgets print is against it; otherwise against a fine RK4 reference).

use super::methods::{fixed_path, steps_for};
use crate::deck::widgets::{Field1, Field2, MethodId};
use crate::ode::{FnSystem, System};

impl Field1 {
    pub fn f(&self, t: f64, x: f64) -> f64 {
        match *self {
            Field1::Decay { k } => -k * x,
            Field1::Logistic => x * (1.0 - x),
            Field1::Forced => t.cos() - x,
            Field1::Riccati => t - x * x,
        }
    }

    pub fn exact(&self, t0: f64, x0: f64, t: f64) -> Option<f64> {
        let dt = t - t0;
        Some(match *self {
            Field1::Decay { k } => x0 * (-k * dt).exp(),
            Field1::Logistic => x0 / (x0 + (1.0 - x0) * (-dt).exp()),
            Field1::Forced => {
                // x = (cos t + sin t)/2 + C e^{−t}
                let p = |s: f64| 0.5 * (s.cos() + s.sin());
                p(t) + (x0 - p(t0)) * (-dt).exp()
            }
            Field1::Riccati => return None,
        })
    }

    pub fn system(self) -> impl System {
        FnSystem::new(1, move |t, x: &[f64], d: &mut [f64]| d[0] = self.f(t, x[0]))
    }

    pub fn label(&self) -> String {
        match self {
            Field1::Decay { k } => format!("ẋ = −{k}·x"),
            Field1::Logistic => "ẋ = x(1 − x)".into(),
            Field1::Forced => "ẋ = cos t − x".into(),
            Field1::Riccati => "ẋ = t − x²".into(),
        }
    }
}

impl Field2 {
    pub fn f(&self, p: [f64; 2]) -> [f64; 2] {
        let [x, y] = p;
        match *self {
            Field2::Circle => [-y, x],
            Field2::Damped { c } => [y, -x - c * y],
            Field2::Pendulum => [y, -x.sin()],
            Field2::VanDerPol { mu } => [y, mu * (1.0 - x * x) * y - x],
        }
    }

    pub fn exact(&self, p0: [f64; 2], t: f64) -> Option<[f64; 2]> {
        match *self {
            Field2::Circle => {
                let (s, c) = t.sin_cos();
                Some([p0[0] * c - p0[1] * s, p0[0] * s + p0[1] * c])
            }
            _ => None,
        }
    }

    pub fn system(self) -> impl System {
        FnSystem::new(2, move |_t, x: &[f64], d: &mut [f64]| {
            let v = self.f([x[0], x[1]]);
            d[0] = v[0];
            d[1] = v[1];
        })
    }

    pub fn label(&self) -> String {
        match self {
            Field2::Circle => "(ẋ, ẏ) = (−y, x)".into(),
            Field2::Damped { c } => format!("ẍ = −x − {c}·ẋ"),
            Field2::Pendulum => "ẍ = −sin x".into(),
            Field2::VanDerPol { mu } => format!("ẍ = {mu}(1 − x²)ẋ − x"),
        }
    }
}

/// The exact (or reference) path of a system, sampled finely for drawing.
pub fn reference_path<S: System>(sys: &S, t0: f64, x0: &[f64], t_end: f64) -> super::methods::Path {
    let h = ((t_end - t0) / 2000.0).max(1e-6);
    let n = steps_for(t0, t_end, h, 4000);
    fixed_path(sys, MethodId::Rk4.scheme().unwrap(), t0, x0, h, n, 1e12)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_solutions_satisfy_their_equations() {
        for f in [Field1::Decay { k: 0.7 }, Field1::Logistic, Field1::Forced] {
            let (t0, x0, t) = (0.3, 0.4, 1.7);
            let e = 1e-6;
            let dxdt =
                (f.exact(t0, x0, t + e).unwrap() - f.exact(t0, x0, t - e).unwrap()) / (2.0 * e);
            let x = f.exact(t0, x0, t).unwrap();
            assert!((dxdt - f.f(t, x)).abs() < 1e-6, "{f:?}");
            assert!((f.exact(t0, x0, t0).unwrap() - x0).abs() < 1e-12);
        }
    }
}
