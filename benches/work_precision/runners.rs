//! Generic runners: every solver of the comparison on one fixed-size problem `S:
//! FixedSystem<N>` (a native right-hand side from `lectern::ode::native`), each point the minimum
//! wall time of repeated solves with its final-time error and f-evaluations.

use std::hint::black_box;

use differential_equations::prelude::{
    ControlFlag, ExplicitRungeKutta, IVP, Interpolation, ODE, Solout, Solution as DeSolution,
};
use lectern::ode::fixed::AsSystem;
use lectern::ode::study::Timing;
use lectern::ode::{
    Adaptive, FixedSystem, Method, Scheme, solve_embedded, solve_embedded_n, solve_fixed_final,
    solve_fixed_n,
};
use ode_solvers::SVector;

/// One solver run: final time, final state, f-evaluations.
pub type Run = (f64, Vec<f64>, u64);

/// A work-precision curve: (error, seconds, f-evaluations) per step size or tolerance.
pub struct Curve {
    pub label: String,
    pub ours: bool,
    /// adaptive (swept over tolerances) rather than fixed-step
    pub adaptive: bool,
    pub points: Vec<(f64, f64, u64)>,
}

/// The fastest of repeated solves, by the one timing policy of every study
/// (`ode::study::Timing::BENCH`: at least 3, until ~30 ms are spent, at most 200).
pub fn timed(f: impl FnMut() -> Run) -> (Run, f64) {
    Timing::BENCH.fastest(f)
}

/// The problem of one case, with what every runner needs.
pub struct Setup<'a, const N: usize, S> {
    pub sys: S,
    pub x0: [f64; N],
    pub t_end: f64,
    /// final-time error of a run (∞ for a run that did not end at t_end)
    pub err: &'a dyn Fn(f64, &[f64]) -> f64,
    pub hs: &'a [f64],
    pub tols: &'a [f64],
}

impl<const N: usize, S> Setup<'_, N, S> {
    fn curve(&self, label: &str, ours: bool, adaptive: bool, run: impl Fn(f64) -> Run) -> Curve {
        let params = if adaptive { self.tols } else { self.hs };
        let points = params
            .iter()
            .map(|&p| {
                let ((t, x, n), s) = timed(|| run(p));
                ((self.err)(t, &x), s, n)
            })
            .collect();
        Curve {
            label: label.to_string(),
            ours,
            adaptive,
            points,
        }
    }
}

pub const FIXED_RK4: &str = "lectern RK4 [f64; N]";
pub const GENERAL_RK4: &str = "lectern RK4 (slices)";

fn tol(t: f64) -> Adaptive {
    Adaptive {
        rtol: t,
        atol: t,
        record: false,
        ..Adaptive::default()
    }
}

/// Lectern: RK4 and every adaptive pair on the `[f64; N]` fast path, and RK4 and DOPRI5 on the
/// general (slices) driver for the cost of generality.
pub fn ours<const N: usize, S: FixedSystem<N> + Copy>(c: &Setup<'_, N, S>) -> Vec<Curve> {
    let (sys, x0, t_end) = (c.sys, c.x0, c.t_end);
    let mut curves = vec![c.curve(FIXED_RK4, true, false, |h| {
        let sol = solve_fixed_n(&sys, 0.0, black_box(x0), h, t_end, f64::INFINITY);
        (sol.t, sol.x.to_vec(), sol.f_evals)
    })];
    for m in Method::PAIRS {
        curves.push(c.curve(&format!("lectern {}", m.name()), true, true, |t| {
            let sol = solve_embedded_n(&sys, m, 0.0, black_box(x0), t_end, tol(t));
            (sol.t, sol.x.to_vec(), sol.f_evals)
        }));
    }
    let general = AsSystem::<N, S>(sys);
    curves.push(c.curve(GENERAL_RK4, true, false, |h| {
        let sol = solve_fixed_final(
            &general,
            Scheme::Method(Method::Rk4),
            0.0,
            black_box(&x0),
            h,
            t_end,
            f64::INFINITY,
        );
        let (t, x) = sol.last();
        (t, x.to_vec(), sol.f_evals)
    }));
    curves.push(c.curve("lectern dopri5 (slices)", true, true, |t| {
        let sol = solve_embedded(&general, Method::Dopri5, 0.0, black_box(&x0), t_end, tol(t));
        let (t, x) = sol.last();
        (t, x.to_vec(), sol.f_evals)
    }));
    curves
}

/// A fixed-size problem seen by both peers (one adapter, so each peer solves exactly our
/// native right-hand side).
#[derive(Clone, Copy)]
pub struct Peer<S>(pub S);

impl<const N: usize, S: FixedSystem<N>> ode_solvers::System<f64, SVector<f64, N>> for Peer<S> {
    #[inline]
    fn system(&self, t: f64, y: &SVector<f64, N>, dy: &mut SVector<f64, N>) {
        let x: [f64; N] = y.as_slice().try_into().expect("N values");
        dy.as_mut_slice().copy_from_slice(&self.0.rhs(t, &x));
    }
}

impl<const N: usize, S: FixedSystem<N>> ODE<f64, [f64; N]> for Peer<S> {
    #[inline]
    fn diff(&self, t: f64, y: &[f64; N], dy: &mut [f64; N]) {
        *dy = self.0.rhs(t, y);
    }
}

/// A `differential-equations` output strategy that keeps only the latest point, so that the
/// peer, like lectern, does no per-step recording (its default records every step).
#[derive(Clone, Copy)]
pub struct KeepLast;

impl<const N: usize> Solout<f64, [f64; N]> for KeepLast {
    fn solout<I>(
        &mut self,
        t_curr: f64,
        _t_prev: f64,
        y_curr: &[f64; N],
        _y_prev: &[f64; N],
        _interpolator: &mut I,
        solution: &mut DeSolution<f64, [f64; N]>,
    ) -> ControlFlag<f64, [f64; N]>
    where
        I: Interpolation<f64, [f64; N]> + ?Sized,
    {
        if solution.t.is_empty() {
            solution.push(t_curr, *y_curr);
        } else {
            solution.t[0] = t_curr;
            solution.y[0] = *y_curr;
        }
        ControlFlag::Continue
    }
}

/// One `differential-equations` solve with the given method builder.
macro_rules! de_solve {
    ($sys:expr, $x0:expr, $t_end:expr, $method:expr) => {{
        let sol = IVP::ode(&$sys, 0.0, $t_end, $x0)
            .method($method.max_steps(10_000_000))
            .solout(KeepLast)
            .solve()
            .expect("peer solve");
        let (t, y) = sol.last().expect("a point");
        (*t, y.to_vec(), sol.evals.function as u64)
    }};
}

/// `ode_solvers` 0.6 (RK4, Dopri5, Dop853 with its default controller constants) and
/// `differential-equations` 0.7 (RK4, DOPRI5, DOP853 and Verner's efficient 6(5) … 9(8)).
pub fn peers<const N: usize, S: FixedSystem<N> + Copy>(c: &Setup<'_, N, S>) -> Vec<Curve> {
    let (sys, x0, t_end) = (Peer(c.sys), c.x0, c.t_end);
    let y0 = SVector::<f64, N>::from(x0);
    let os_last = |y: &[SVector<f64, N>], x: &[f64], n: u32| {
        let last = y.last().expect("a point");
        (
            *x.last().expect("a point"),
            last.as_slice().to_vec(),
            n as u64,
        )
    };
    let mut curves = vec![
        c.curve("ode_solvers RK4", false, false, |h| {
            let mut st = ode_solvers::Rk4::new(sys, 0.0, black_box(y0), t_end, h);
            let stats = st.integrate().expect("peer solve");
            os_last(st.y_out(), st.x_out(), stats.num_eval)
        }),
        c.curve("ode_solvers Dopri5", false, true, |tol| {
            let mut st = ode_solvers::Dopri5::from_param(
                sys,
                0.0,
                t_end,
                t_end,
                black_box(y0),
                tol,
                tol,
                0.9,
                0.04,
                0.2,
                10.0,
                t_end,
                0.0,
                10_000_000,
                1000,
                ode_solvers::OutputType::Sparse,
            );
            let stats = st.integrate().expect("peer solve");
            os_last(st.y_out(), st.x_out(), stats.num_eval)
        }),
        c.curve("ode_solvers Dop853", false, true, |tol| {
            let mut st = ode_solvers::Dop853::from_param(
                sys,
                0.0,
                t_end,
                t_end,
                black_box(y0),
                tol,
                tol,
                0.9,
                0.0,
                0.333,
                6.0,
                t_end,
                0.0,
                10_000_000,
                1000,
                ode_solvers::OutputType::Sparse,
            );
            let stats = st.integrate().expect("peer solve");
            os_last(st.y_out(), st.x_out(), stats.num_eval)
        }),
        c.curve("diff-eq RK4", false, false, |h| {
            de_solve!(sys, black_box(x0), t_end, ExplicitRungeKutta::rk4(h))
        }),
    ];
    macro_rules! de_adaptive {
        ($label:expr, $ctor:ident) => {
            curves.push(c.curve($label, false, true, |tol| {
                de_solve!(
                    sys,
                    black_box(x0),
                    t_end,
                    ExplicitRungeKutta::$ctor().rtol(tol).atol(tol)
                )
            }))
        };
    }
    de_adaptive!("diff-eq DOPRI5", dopri5);
    de_adaptive!("diff-eq DOP853", dop853);
    de_adaptive!("diff-eq RKV655e", rkv655e);
    de_adaptive!("diff-eq RKV766e", rkv766e);
    de_adaptive!("diff-eq RKV877e", rkv877e);
    de_adaptive!("diff-eq RKV988e", rkv988e);
    curves
}
