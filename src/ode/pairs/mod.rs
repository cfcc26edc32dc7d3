//! Embedded Runge–Kutta pairs: two explicit formulas sharing their stages, one of order p that
//! propagates the solution and one of lower order whose difference from it estimates the local
//! error. Each pair is data (`PairCoefficients<S>`, S stages) plus the step-size controller
//! constants its authors use; the one adaptive loop (`ode::adaptive`) runs any of them.
//!
//! f-evaluations per accepted step: S − 1 for a "first same as last" (FSAL) pair, whose last
//! stage is f at the new state and so the next step's first; S for the others, which evaluate
//! f at the new state once the step is accepted.
//!
//! | method | pair | stages | f per step | controller |
//! |---|---|---:|---:|---|
//! | `dopri5` | Dormand–Prince 5(4) | 7 (FSAL) | 6 | PI, β = 0.04, h ∈ [0.2, 10]·h (Hairer's DOPRI5) |
//! | `tsit5` | Tsitouras 5(4) | 7 (FSAL) | 6 | PI, β = 0.4/5 |
//! | `vern6` | Verner 6(5) | 9 (FSAL) | 8 | PI, β = 0.2/6, safety 0.85 |
//! | `vern7` | Verner 7(6) | 10 | 10 | PI, β = 0.2/7, safety 0.85 |
//! | `vern8` | Verner 8(7) | 13 | 13 | PI, β = 0.2/8, safety 0.85 |
//! | `vern9` | Verner 9(8) | 16 | 16 | PI, β = 0.2/9, safety 0.85 |
//! | `dop853` | Dormand–Prince 8(5,3) | 12 | 12 | I (β = 0), h ∈ [1/3, 6]·h (Hairer's DOP853) |
//!
//! Tsit5's β is OrdinaryDiffEq.jl's default PI gain (2/(5p)). For Verner's pairs that gain
//! makes the step follow the error too slowly (at a steady error ε the step grows by only
//! ε^(−0.3/p) per step, 8 % for p = 9 at ε = 0.004): on Kepler e = 0.9 over ten orbits, half the
//! gain with safety 0.85 took 5–12 % fewer f-evaluations at 1e-6 … 1e-10 with equal or smaller
//! errors (measured with `tests/ode_pairs.rs`), and 897 instead of 1039 on the e = 0.6 orbit
//! at 1e-12. DOPRI5 and DOP853 keep Hairer's constants, so they reproduce his codes (and
//! scipy's DOP853 to four digits).

pub mod dop853;
pub mod dopri5;
pub mod tsit5;
pub mod verner;

use super::Tableau;

/// The coefficients of an embedded pair with `S` stages: `k_i = f(t + c_i h, x + h Σ_j a_ij k_j)`,
/// `x_new = x + h Σ b_i k_i`, local error estimate `h Σ e_i k_i` with `e = b − b̂`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PairCoefficients<const S: usize> {
    pub name: &'static str,
    /// order of the propagating formula `b`
    pub order: u32,
    /// order of the embedded formula `b̂` (DOP853: 5, with a 3rd-order one beside it)
    pub est_order: u32,
    /// the last row of `a` equals `b` and `c` ends in 1: the last stage is f(t + h, x_new)
    pub fsal: bool,
    pub c: [f64; S],
    /// full rows, zero on and above the diagonal
    pub a: [[f64; S]; S],
    pub b: [f64; S],
    pub e: [f64; S],
    /// DOP853 only: b minus its 3rd-order formula, combined with `e` as in Hairer's code,
    /// `err = err5² / √(err5² + 0.01 err3²)`
    pub e3: Option<[f64; S]>,
}

impl<const S: usize> PairCoefficients<S> {
    /// f-evaluations per accepted step.
    pub const fn evals_per_step(&self) -> usize {
        if self.fsal { S - 1 } else { S }
    }

    /// The propagating formula as a fixed-step method: the stages up to the last one `b`
    /// uses (the trailing stages feed only the error estimate).
    pub fn tableau(&self) -> Tableau {
        let used = (0..S)
            .rev()
            .find(|&i| self.b[i] != 0.0)
            .map_or(S, |i| i + 1);
        Tableau {
            name: self.name.to_string(),
            a: self.a[..used]
                .iter()
                .map(|row| row[..used].to_vec())
                .collect(),
            b: self.b[..used].to_vec(),
            c: self.c[..used].to_vec(),
        }
    }

    /// The embedded (lower-order) formula b̂ = b − e as a tableau over all S stages.
    pub fn embedded_tableau(&self) -> Tableau {
        Tableau {
            name: format!("{} (embedded)", self.name),
            a: self.a.iter().map(|row| row.to_vec()).collect(),
            b: (0..S).map(|i| self.b[i] - self.e[i]).collect(),
            c: self.c.to_vec(),
        }
    }
}

/// How the next step size follows from the error: Hairer's PI controller with Lund
/// stabilisation, `h_new = h · safety · err^(−α) · err_prev^β` limited to
/// `[fac_min, fac_max]·h` (no growth right after a rejection), `α = 1/p − 0.75 β` for an error
/// estimate of order p (err ~ h^p).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Controller {
    pub safety: f64,
    pub fac_min: f64,
    pub fac_max: f64,
    pub alpha: f64,
    pub beta: f64,
    /// also apply Gustafsson's predictive controller and keep the smaller step (RADAU5,
    /// RODAS): it anticipates the error's trend where stiff components switch on and off
    pub predictive: bool,
    /// keep h when the new one would be 1 … `hold` times it (1: never), so an implicit method
    /// keeps its LU factors (RADAU5: 1.2)
    pub hold: f64,
}

impl Controller {
    /// The PI controller for an error estimate of order p with gain β, safety 0.9, step
    /// ratio in [0.2, 10].
    pub const fn pi(p: u32, beta: f64) -> Self {
        Self {
            safety: 0.9,
            fac_min: 0.2,
            fac_max: 10.0,
            alpha: 1.0 / p as f64 - 0.75 * beta,
            beta,
            predictive: false,
            hold: 1.0,
        }
    }

    /// The stiff solvers' controller, as Hairer's RADAU5 and RODAS: err^(−1/q) for an
    /// error estimate of order q, Gustafsson's predictive term, step ratio in
    /// [0.2, `fac_max`], steps kept within `hold`.
    pub const fn predictive(q: u32, fac_max: f64, hold: f64) -> Self {
        Self {
            fac_max,
            predictive: true,
            hold,
            ..Self::pi(q, 0.0)
        }
    }
}

impl Controller {
    /// Verner's pairs: PI with gain β = 0.2/p and safety 0.85 (see the module notes).
    pub const fn verner(p: u32) -> Self {
        Self {
            safety: 0.85,
            ..Self::pi(p, 0.2 / p as f64)
        }
    }
}

/// A pair known at compile time, so the adaptive loop is monomorphised over its coefficients
/// (zero entries vanish from the stage sums).
pub trait Pair<const S: usize>: Copy {
    const COEF: PairCoefficients<S>;
    const CONTROL: Controller;
    /// Hairer's stiffness test: the stability boundary on the negative real axis beyond
    /// which h·|λ| (estimated from the two stages at c = 1) means the step is limited by
    /// stability (DOPRI5: 3.25, DOP853: 6.1); `None`: no test.
    const STIFF_LIMIT: Option<f64> = None;
}

macro_rules! pair {
    ($(#[$doc:meta])* $ty:ident, $s:literal, $coef:path, $control:expr $(, stiff = $lim:expr)?) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, Default)]
        pub struct $ty;
        impl Pair<$s> for $ty {
            const COEF: PairCoefficients<$s> = $coef;
            const CONTROL: Controller = $control;
            $(const STIFF_LIMIT: Option<f64> = Some($lim);)?
        }
    };
}

pair!(
    /// Dormand–Prince 5(4), Hairer's DOPRI5 controller.
    Dopri5Pair, 7, dopri5::DOPRI5, Controller::pi(5, 0.04), stiff = 3.25
);
pair!(
    /// Tsitouras 5(4).
    Tsit5Pair, 7, tsit5::TSIT5, Controller::pi(5, 0.4 / 5.0)
);
pair!(
    /// Verner's efficient 6(5).
    Vern6Pair, 9, verner::VERN6, Controller::verner(6)
);
pair!(
    /// Verner's efficient 7(6).
    Vern7Pair, 10, verner::VERN7, Controller::verner(7)
);
pair!(
    /// Verner's efficient 8(7).
    Vern8Pair, 13, verner::VERN8, Controller::verner(8)
);
pair!(
    /// Verner's efficient 9(8).
    Vern9Pair, 16, verner::VERN9, Controller::verner(9)
);
pair!(
    /// Dormand–Prince 8(5,3) with Hairer's DOP853 controller (β = 0, ratio in [1/3, 6]).
    Dop853Pair,
    12,
    dop853::DOP853,
    Controller {
        fac_min: 1.0 / 3.0,
        fac_max: 6.0,
        ..Controller::pi(8, 0.0)
    },
    stiff = 6.1
);

/// Runs `$body` with `$pair` bound to the pair of an adaptive [`Method`](super::Method) (a
/// different type in each arm, so the body is monomorphised per pair), or evaluates
/// `$otherwise` for a method that is not an embedded pair.
macro_rules! with_pair {
    ($method:expr, |$pair:ident| $body:expr, $otherwise:expr) => {{
        use $crate::ode::Method as M;
        use $crate::ode::pairs::*;
        match $method {
            M::Dopri5 => {
                let $pair = Dopri5Pair;
                $body
            }
            M::Tsit5 => {
                let $pair = Tsit5Pair;
                $body
            }
            M::Vern6 => {
                let $pair = Vern6Pair;
                $body
            }
            M::Vern7 => {
                let $pair = Vern7Pair;
                $body
            }
            M::Vern8 => {
                let $pair = Vern8Pair;
                $body
            }
            M::Vern9 => {
                let $pair = Vern9Pair;
                $body
            }
            M::Dop853 => {
                let $pair = Dop853Pair;
                $body
            }
            _ => $otherwise,
        }
    }};
}
pub(crate) use with_pair;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ode::Method;

    fn evals<const S: usize, P: Pair<S>>(_: P) -> usize {
        P::COEF.evals_per_step()
    }

    #[test]
    fn evaluations_per_step_are_the_textbook_ones() {
        let expect = [
            (Method::Dopri5, 6),
            (Method::Tsit5, 6),
            (Method::Vern6, 8),
            (Method::Vern7, 10),
            (Method::Vern8, 13),
            (Method::Vern9, 16),
            (Method::Dop853, 12),
        ];
        for (m, n) in expect {
            assert_eq!(with_pair!(m, |p| evals(p), 0), n, "{m}");
        }
        assert_eq!(with_pair!(Method::Rk4, |p| evals(p), 0), 0);
    }

    fn check_shape<const S: usize, P: Pair<S>>(_: P) {
        let c = P::COEF;
        for i in 0..S {
            let row: f64 = c.a[i].iter().sum();
            assert!((row - c.c[i]).abs() < 1e-13, "{}: c[{i}]", c.name);
            assert!(
                c.a[i][i..].iter().all(|&v| v == 0.0),
                "{}: explicit",
                c.name
            );
        }
        if c.fsal {
            assert_eq!(c.a[S - 1], c.b, "{}", c.name);
            assert_eq!(c.c[S - 1], 1.0, "{}", c.name);
        }
        let ctl = P::CONTROL;
        assert!(ctl.fac_min < 1.0 && ctl.fac_max > 1.0 && ctl.alpha > 0.0);
    }

    #[test]
    fn pairs_are_explicit_with_consistent_nodes() {
        for m in Method::ALL {
            with_pair!(m, |p| check_shape(p), ());
        }
    }
}
