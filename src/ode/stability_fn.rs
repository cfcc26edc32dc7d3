//! A method's stability function R(z) as the stability widgets use it (a built-in method's or a
//! tableau's), A- and L-stability read from it, and the largest stable step for an
//! eigenvalue λ. Pure numerics: the widgets only draw what these say.

use super::stability::{Complex, cabs};
use super::{Method, Tableau};

/// A point of the complex plane, as the widgets give λ and z = hλ.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct C(pub f64, pub f64);

impl C {
    pub fn scale(self, s: f64) -> C {
        C(self.0 * s, self.1 * s)
    }
}

/// |R(z)| of a tableau, by the numerics core.
pub fn stability_abs(t: &Tableau, z: C) -> f64 {
    cabs(t.stability((z.0, z.1)))
}

/// Where a region's stability function comes from: a built-in method (explicit or implicit)
/// or a tableau (a file or written in the deck).
#[derive(Debug, Clone, PartialEq)]
pub enum StabilityFn {
    Method(Method),
    Tableau(Tableau),
}

impl StabilityFn {
    /// R(z); a method without one (never listed: see `Stability::entries`) reads as unstable.
    pub fn r(&self, z: Complex) -> Complex {
        match self {
            StabilityFn::Method(m) => m.stability(z).unwrap_or((f64::INFINITY, 0.0)),
            StabilityFn::Tableau(t) => t.stability(z),
        }
    }

    pub fn abs(&self, z: Complex) -> f64 {
        cabs(self.r(z))
    }

    /// A-stable: stable on the whole left half-plane (checked on the imaginary axis and far
    /// out to the left, where an explicit method's polynomial blows up).
    pub fn a_stable(&self) -> bool {
        let stable = |z: Complex| self.abs(z) <= 1.0 + 1e-9;
        (0..=200).all(|k| {
            let y = 1e-2 * 1.1_f64.powi(k);
            stable((0.0, y)) && stable((-y, y)) && stable((-y, 0.0))
        })
    }

    /// L-stable: A-stable and |R(z)| → 0 as z → −∞ (|R(−1e8)| < 1e-6).
    pub fn l_stable(&self) -> bool {
        self.a_stable() && self.abs((-1e8, 0.0)) < 1e-6
    }
}

/// The largest h with |R(h λ)| ≤ 1 for all smaller h (bisection after a coarse scan);
/// 0 when no positive h is stable, ∞ (capped at `h_max`) when all are.
pub fn stable_h_limit(abs_r: impl Fn(C) -> f64, lambda: C, h_max: f64) -> f64 {
    let stable = |h: f64| abs_r(lambda.scale(h)) <= 1.0 + 1e-12;
    let n = 4000;
    let mut last_ok = 0.0;
    for i in 1..=n {
        let h = h_max * i as f64 / n as f64;
        if !stable(h) {
            let (mut lo, mut hi) = (last_ok, h);
            if lo == 0.0 && !stable(h * 1e-6) {
                return 0.0;
            }
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if stable(mid) { lo = mid } else { hi = mid }
            }
            // below a thousandth of the range it is round-off at the origin, not stability
            return if lo < 1e-3 * h_max { 0.0 } else { lo };
        }
        last_ok = h;
    }
    h_max
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_stability_limits() {
        // real axis: Euler and midpoint 2, RK4 ≈ 2.785; imaginary axis: RK4 2√2, Euler 0
        let lim = |t: Tableau, l: C| stable_h_limit(|z| stability_abs(&t, z), l, 10.0);
        assert!((lim(Tableau::euler(), C(-1.0, 0.0)) - 2.0).abs() < 1e-9);
        assert!((lim(Tableau::midpoint(), C(-1.0, 0.0)) - 2.0).abs() < 1e-9);
        assert!((lim(Tableau::rk4(), C(-1.0, 0.0)) - 2.785_293_563).abs() < 1e-6);
        assert!((lim(Tableau::rk4(), C(0.0, 1.0)) - 8f64.sqrt()).abs() < 1e-9);
        assert_eq!(lim(Tableau::euler(), C(0.0, 1.0)), 0.0);
    }

    #[test]
    fn a_and_l_stability_are_read_from_r() {
        let f = |m: Method| StabilityFn::Method(m);
        for m in [Method::Euler, Method::Rk4, Method::Dopri5] {
            assert!(!f(m).a_stable(), "{m}");
        }
        assert!(f(Method::ImplicitMidpoint).a_stable());
        assert!(!f(Method::ImplicitMidpoint).l_stable(), "|R(−∞)| = 1");
        for m in [Method::ImplicitEuler, Method::Radau5, Method::Rodas5p] {
            assert!(f(m).l_stable(), "{m}");
        }
    }
}
