//! The table of cases: the three shipped problems as their native right-hand sides
//! (`lectern::ode::native`, the same equations as `slides/problems/*.ron`, tested equal), each
//! with its span, exact final state and sweep.

use std::f64::consts::TAU;

use lectern::ode::FixedSystem;
use lectern::ode::native::{Harmonic, Kepler, Pendulum};
use lectern::ode::study::max_error;

use super::runners::{self, Curve, Setup};

#[derive(Clone, Copy)]
pub enum Problem {
    Harmonic,
    Kepler,
    Pendulum,
}

pub struct CaseSpec {
    pub name: &'static str,
    pub title: &'static str,
    pub problem: Problem,
    pub t_end: f64,
    /// fixed steps t_end / 2^k for k in this range
    pub halvings: std::ops::RangeInclusive<i32>,
}

pub const CASES: [CaseSpec; 3] = [
    CaseSpec {
        name: "harmonic",
        title: "Harmonic oscillator, t = 10",
        problem: Problem::Harmonic,
        t_end: 10.0,
        halvings: 3..=14,
    },
    CaseSpec {
        name: "kepler",
        title: "Kepler e = 0.6, one period",
        problem: Problem::Kepler,
        t_end: TAU,
        halvings: 5..=14,
    },
    CaseSpec {
        name: "pendulum",
        title: "Pendulum from 179°, t = 10",
        problem: Problem::Pendulum,
        t_end: 10.0,
        halvings: 3..=14,
    },
];

/// The pendulum from 179° at t = 10, exact to 40 digits (Jacobi elliptic functions, computed
/// by `scripts/scipy_reference.py`), and its start as the problem file writes it.
fn pendulum_reference() -> ([f64; 2], [f64; 2]) {
    let text = std::fs::read_to_string("tests/data/ode_reference.json").expect("reference file");
    let json: serde_json::Value = serde_json::from_str(&text).expect("reference JSON");
    let p = &json["pendulum"];
    let num = |v: &serde_json::Value| v.as_f64().expect("number");
    let exact = [num(&p["exact"][0]), num(&p["exact"][1])];
    ([num(&p["theta0"]), 0.0], exact)
}

/// Every curve of one case: lectern's and the peers'.
pub fn run(spec: &CaseSpec) -> Vec<Curve> {
    let hs: Vec<f64> = spec
        .halvings
        .clone()
        .map(|k| spec.t_end / 2f64.powi(k))
        .collect();
    let tols = lectern::ode::study::tolerances();
    match spec.problem {
        Problem::Harmonic => {
            let exact = [spec.t_end.cos(), -spec.t_end.sin()];
            sweep(
                Harmonic { w: 1.0 },
                [1.0, 0.0],
                spec.t_end,
                &exact,
                &hs,
                &tols,
            )
        }
        Problem::Kepler => {
            let x0 = [0.4, 0.0, 0.0, 2.0];
            // one period returns to the start
            sweep(Kepler, x0, spec.t_end, &x0, &hs, &tols)
        }
        Problem::Pendulum => {
            let (x0, exact) = pendulum_reference();
            let sys = Pendulum { g: 1.0, l: 1.0 };
            sweep(sys, x0, spec.t_end, &exact, &hs, &tols)
        }
    }
}

fn sweep<const N: usize, S: FixedSystem<N> + Copy>(
    sys: S,
    x0: [f64; N],
    t_end: f64,
    exact: &[f64],
    hs: &[f64],
    tols: &[f64],
) -> Vec<Curve> {
    let err = |t: f64, x: &[f64]| {
        if (t - t_end).abs() <= 1e-12 * t_end {
            max_error(x, exact)
        } else {
            // a run that did not end at t_end has no comparable error
            f64::INFINITY
        }
    };
    let setup = Setup {
        sys,
        x0,
        t_end,
        err: &err,
        hs,
        tols,
    };
    let mut curves = runners::ours(&setup);
    curves.extend(runners::peers(&setup));
    curves
}
