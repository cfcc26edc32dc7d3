//! The named integration methods a slide, the CLI or a benchmark can ask for.

use std::fmt;
use std::str::FromStr;

use super::Tableau;
use super::pairs::{Pair, with_pair};
use super::stability::{Complex, cdiv};

fn propagating<const S: usize, P: Pair<S>>(_: P) -> Tableau {
    P::COEF.tableau()
}

/// Every method by its CLI name. Explicit Runge–Kutta methods also exist as any
/// [`Tableau`]; this enum names the built-in ones plus those that are not explicit RK.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Method {
    Euler,
    Midpoint,
    Heun,
    Rk4,
    SymplecticEuler,
    Verlet,
    ImplicitEuler,
    ImplicitMidpoint,
    Dopri5,
    Tsit5,
    Vern6,
    Vern7,
    Vern8,
    Vern9,
    Dop853,
    Rodas5p,
    Radau5,
}

impl Method {
    pub const ALL: [Method; 17] = [
        Method::Euler,
        Method::Midpoint,
        Method::Heun,
        Method::Rk4,
        Method::SymplecticEuler,
        Method::Verlet,
        Method::ImplicitEuler,
        Method::ImplicitMidpoint,
        Method::Dopri5,
        Method::Tsit5,
        Method::Vern6,
        Method::Vern7,
        Method::Vern8,
        Method::Vern9,
        Method::Dop853,
        Method::Rodas5p,
        Method::Radau5,
    ];

    /// The adaptive solvers for stiff problems (`ode::stiff`).
    pub const STIFF: [Method; 2] = [Method::Rodas5p, Method::Radau5];

    /// The adaptive embedded pairs, by order.
    pub const PAIRS: [Method; 7] = [
        Method::Dopri5,
        Method::Tsit5,
        Method::Vern6,
        Method::Vern7,
        Method::Vern8,
        Method::Dop853,
        Method::Vern9,
    ];

    /// The CLI name: `euler`, `midpoint`, `heun`, `rk4`, `symplectic-euler`, `verlet`,
    /// `implicit-euler`, `implicit-midpoint`, `dopri5`, `tsit5`, `vern6` … `vern9`, `dop853`,
    /// `rodas5p`, `radau5`.
    pub fn name(self) -> &'static str {
        match self {
            Method::Euler => "euler",
            Method::Midpoint => "midpoint",
            Method::Heun => "heun",
            Method::Rk4 => "rk4",
            Method::SymplecticEuler => "symplectic-euler",
            Method::Verlet => "verlet",
            Method::ImplicitEuler => "implicit-euler",
            Method::ImplicitMidpoint => "implicit-midpoint",
            Method::Dopri5 => "dopri5",
            Method::Tsit5 => "tsit5",
            Method::Vern6 => "vern6",
            Method::Vern7 => "vern7",
            Method::Vern8 => "vern8",
            Method::Vern9 => "vern9",
            Method::Dop853 => "dop853",
            Method::Rodas5p => "rodas5p",
            Method::Radau5 => "radau5",
        }
    }

    /// A label for plots and tables.
    pub fn label(self) -> &'static str {
        match self {
            Method::Euler => "Euler",
            Method::Midpoint => "Midpoint",
            Method::Heun => "Heun",
            Method::Rk4 => "RK4",
            Method::SymplecticEuler => "Symplectic Euler",
            Method::Verlet => "Velocity Verlet",
            Method::ImplicitEuler => "Implicit Euler",
            Method::ImplicitMidpoint => "Implicit midpoint",
            Method::Dopri5 => "Dormand–Prince 5(4)",
            Method::Tsit5 => "Tsitouras 5(4)",
            Method::Vern6 => "Verner 6(5)",
            Method::Vern7 => "Verner 7(6)",
            Method::Vern8 => "Verner 8(7)",
            Method::Vern9 => "Verner 9(8)",
            Method::Dop853 => "Dormand–Prince 8(5,3)",
            Method::Rodas5p => "Rodas5P",
            Method::Radau5 => "Radau IIA 5",
        }
    }

    pub fn from_name(name: &str) -> Option<Method> {
        Method::ALL.into_iter().find(|m| m.name() == name)
    }

    /// Global order of accuracy.
    pub fn order(self) -> u32 {
        match self {
            Method::Euler | Method::SymplecticEuler | Method::ImplicitEuler => 1,
            Method::Midpoint | Method::Heun | Method::Verlet | Method::ImplicitMidpoint => 2,
            Method::Rk4 => 4,
            Method::Dopri5 | Method::Tsit5 | Method::Rodas5p | Method::Radau5 => 5,
            Method::Vern6 => 6,
            Method::Vern7 => 7,
            Method::Vern8 | Method::Dop853 => 8,
            Method::Vern9 => 9,
        }
    }

    /// Symplectic methods need a second-order system: state (q, v) with q' = v.
    pub fn needs_second_order_system(self) -> bool {
        matches!(self, Method::SymplecticEuler | Method::Verlet)
    }

    /// Implicit (or linearly implicit) methods: they solve with the Jacobian and stay stable
    /// on stiff problems.
    pub fn is_implicit(self) -> bool {
        matches!(self, Method::ImplicitEuler | Method::ImplicitMidpoint) || self.is_stiff_solver()
    }

    /// The adaptive stiff solvers, `rodas5p` and `radau5`.
    pub fn is_stiff_solver(self) -> bool {
        Method::STIFF.contains(&self)
    }

    /// Whether the method chooses its own step (rtol/atol) rather than taking a fixed h.
    pub fn is_adaptive(self) -> bool {
        Method::PAIRS.contains(&self) || self.is_stiff_solver()
    }

    /// The Butcher tableau of an explicit Runge–Kutta method (for an embedded pair, its
    /// propagating, higher-order formula), or `None`.
    pub fn tableau(self) -> Option<Tableau> {
        match self {
            Method::Euler => Some(Tableau::euler()),
            Method::Midpoint => Some(Tableau::midpoint()),
            Method::Heun => Some(Tableau::heun()),
            Method::Rk4 => Some(Tableau::rk4()),
            m => with_pair!(m, |p| Some(propagating(p)), None),
        }
    }

    /// The stability function R(z), z = hλ, for the methods where y' = λy defines one
    /// (symplectic methods split the state and have none).
    pub fn stability(self, z: Complex) -> Option<Complex> {
        match self {
            Method::ImplicitEuler => Some(cdiv((1.0, 0.0), (1.0 - z.0, -z.1))),
            Method::ImplicitMidpoint => Some(cdiv(
                (1.0 + 0.5 * z.0, 0.5 * z.1),
                (1.0 - 0.5 * z.0, -0.5 * z.1),
            )),
            Method::Rodas5p => Some(super::stiff::rodas5p::stability(z)),
            Method::Radau5 => Some(super::stiff::radau5::stability(z)),
            m => m.tableau().map(|t| t.stability(z)),
        }
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Method {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Method::from_name(s).ok_or_else(|| {
            let names: Vec<_> = Method::ALL.iter().map(|m| m.name()).collect();
            format!("unknown method `{s}`; expected one of {}", names.join(", "))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for m in Method::ALL {
            assert_eq!(Method::from_name(m.name()), Some(m));
        }
        assert!("rk5".parse::<Method>().unwrap_err().contains("dopri5"));
    }

    #[test]
    fn implicit_euler_is_a_stable() {
        for z in [(-1e6, 0.0), (-0.1, 50.0), (-3.0, -3.0)] {
            let r = Method::ImplicitEuler.stability(z).unwrap();
            assert!(r.0.hypot(r.1) <= 1.0);
        }
    }
}
