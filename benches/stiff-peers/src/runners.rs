//! Every solver of the comparison on one [`Case`], each handed the same hand-written
//! right-hand side and exact Jacobian. A run returns the final state (None on failure) and the
//! f-evaluations counted at the right-hand side itself, the same way for everyone.

use std::cell::Cell;

use crate::ode::{self, Adaptive, Method, System};
use crate::problems::Case;

thread_local! {
    /// Calls of a case's right-hand side on this thread (non-atomic: cheap, and the benchmark
    /// runs on one thread).
    static F_EVALS: Cell<u64> = const { Cell::new(0) };
}

#[inline(always)]
fn f(case: &Case, y: &[f64], dy: &mut [f64]) {
    F_EVALS.with(|c| c.set(c.get() + 1));
    (case.f)(y, dy)
}

thread_local! {
    /// Why the last failed run failed, for the page.
    static WHY: std::cell::RefCell<Option<String>> = const { std::cell::RefCell::new(None) };
}

/// Keeps a peer's error message (its first sentence, without the state it prints).
fn why<T, E: std::fmt::Debug>(what: &str, r: Result<T, E>) -> Option<T> {
    r.map_err(|e| {
        let text = format!("{e:?}");
        let text = text.split(" at (t, y)").next().unwrap_or(&text);
        let text = text.split(". ").next().unwrap_or(text).trim_matches('"');
        WHY.with(|w| *w.borrow_mut() = Some(format!("{what}: {text}")));
    })
    .ok()
}

/// The reason of the last failure on this thread, taken.
pub fn take_why() -> Option<String> {
    WHY.with(|w| w.borrow_mut().take())
}

/// One solve: final state (None if the solver failed) and f-evaluations.
pub type Run = (Option<Vec<f64>>, u64);

fn counted(solve: impl FnOnce() -> Option<Vec<f64>>) -> Run {
    F_EVALS.with(|c| c.set(0));
    let y = solve();
    (y, F_EVALS.with(Cell::get))
}

/// A solver of the comparison.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Solver {
    LecternRodas5p,
    LecternRadau5,
    DeRadau5,
    DeBdf,
    DeKvaerno745,
    RussellRadau5,
    DiffsolBdf,
    DiffsolEsdirk34,
}

impl Solver {
    pub const ALL: [Solver; 8] = [
        Solver::LecternRodas5p,
        Solver::LecternRadau5,
        Solver::DeRadau5,
        Solver::DeBdf,
        Solver::DeKvaerno745,
        Solver::RussellRadau5,
        Solver::DiffsolBdf,
        Solver::DiffsolEsdirk34,
    ];

    pub fn label(self) -> &'static str {
        match self {
            Solver::LecternRodas5p => "lectern rodas5p",
            Solver::LecternRadau5 => "lectern radau5",
            Solver::DeRadau5 => "differential-equations Radau5",
            Solver::DeBdf => "differential-equations BDF",
            Solver::DeKvaerno745 => "differential-equations Kvaerno745",
            Solver::RussellRadau5 => "russell_ode Radau5",
            Solver::DiffsolBdf => "diffsol BDF",
            Solver::DiffsolEsdirk34 => "diffsol ESDIRK34",
        }
    }

    pub fn ours(self) -> bool {
        matches!(self, Solver::LecternRodas5p | Solver::LecternRadau5)
    }

    /// Solves `case` at rtol, atol = case.atol_over_rtol · rtol.
    pub fn run(self, case: &Case, rtol: f64) -> Run {
        let atol = rtol * case.atol_over_rtol;
        counted(|| match self {
            Solver::LecternRodas5p => lectern(case, Method::Rodas5p, rtol, atol),
            Solver::LecternRadau5 => lectern(case, Method::Radau5, rtol, atol),
            Solver::DeRadau5 | Solver::DeBdf | Solver::DeKvaerno745 => match case.dim() {
                2 => de::<2>(self, case, rtol, atol),
                3 => de::<3>(self, case, rtol, atol),
                8 => de::<8>(self, case, rtol, atol),
                _ => None,
            },
            Solver::RussellRadau5 => russell(case, rtol, atol),
            Solver::DiffsolBdf | Solver::DiffsolEsdirk34 => diffsol(self, case, rtol, atol),
        })
    }
}

/// The case as lectern's `System`: exact Jacobian, ∂f/∂t = 0.
struct Native<'a>(&'a Case);

impl System for Native<'_> {
    fn dim(&self) -> usize {
        self.0.dim()
    }
    #[inline]
    fn rhs(&self, _t: f64, x: &[f64], dxdt: &mut [f64]) {
        f(self.0, x, dxdt)
    }
    fn jacobian(&self, _t: f64, x: &[f64], jac: &mut [f64]) -> bool {
        (self.0.jac)(x, jac);
        true
    }
    fn time_derivative(&self, _t: f64, _x: &[f64], dfdt: &mut [f64]) -> bool {
        dfdt.fill(0.0);
        true
    }
}

fn lectern(case: &Case, method: Method, rtol: f64, atol: f64) -> Option<Vec<f64>> {
    let opts = Adaptive {
        rtol,
        atol,
        record: false,
        ..Adaptive::default()
    };
    let sol = ode::solve_embedded(&Native(case), method, 0.0, case.y0, case.t_end, opts);
    if !sol.finished() {
        return why(&format!("lectern {method}"), Err(sol.outcome.to_string()));
    }
    Some(sol.last().1.to_vec())
}

mod de_impl {
    use differential_equations::prelude::{
        ControlFlag, Interpolation, Matrix, ODE, Solout, Solution as DeSolution,
    };

    use crate::problems::Case;

    pub struct De<'a, const N: usize>(pub &'a Case);

    impl<const N: usize> ODE<f64, [f64; N]> for De<'_, N> {
        #[inline]
        fn diff(&self, _t: f64, y: &[f64; N], dydt: &mut [f64; N]) {
            super::f(self.0, y, dydt)
        }
        fn jacobian(&self, _t: f64, y: &[f64; N], j: &mut Matrix<f64>) {
            let mut dense = [0.0; 64];
            (self.0.jac)(y, &mut dense[..N * N]);
            for r in 0..N {
                for c in 0..N {
                    j[(r, c)] = dense[r * N + c];
                }
            }
        }
    }

    /// Keeps only the latest point (the peer's default records every step; lectern records
    /// nothing here either).
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
}

fn de<const N: usize>(solver: Solver, case: &Case, rtol: f64, atol: f64) -> Option<Vec<f64>> {
    use differential_equations::prelude::{
        BackwardDifferentiationFormula, DiagonallyImplicitRungeKutta, IVP, ImplicitRungeKutta,
    };
    let sys = de_impl::De::<N>(case);
    let y0: [f64; N] = case.y0.try_into().ok()?;
    let ivp = IVP::ode(&sys, 0.0, case.t_end, y0).solout(de_impl::KeepLast);
    let sol = match solver {
        Solver::DeRadau5 => ivp
            .method(
                ImplicitRungeKutta::radau5()
                    .rtol(rtol)
                    .atol(atol)
                    .max_steps(10_000_000),
            )
            .solve(),
        Solver::DeBdf => ivp
            .method(
                BackwardDifferentiationFormula::adaptive()
                    .rtol(rtol)
                    .atol(atol)
                    .max_steps(10_000_000),
            )
            .solve(),
        _ => ivp
            .method(
                // its default gives up after 10 rejections in a row ("Stiffness detected"),
                // which stopped it on every case here: more patience, as RADAU5's
                DiagonallyImplicitRungeKutta::kvaerno745()
                    .rtol(rtol)
                    .atol(atol)
                    .max_rejects(1000)
                    .max_steps(10_000_000),
            )
            .solve(),
    };
    let sol = why(solver.label(), sol)?;
    let (t, y) = why(solver.label(), sol.last())?;
    if (t - case.t_end).abs() > 1e-9 * case.t_end {
        let _ = why::<(), _>(solver.label(), Err(format!("ended at t = {t}")));
        return None;
    }
    Some(y.to_vec())
}

fn russell(case: &Case, rtol: f64, atol: f64) -> Option<Vec<f64>> {
    use russell_lab::Vector;
    use russell_ode::prelude::{Method as RMethod, NoArgs, OdeSolver, Params, System as RSystem};
    use russell_sparse::{CooMatrix, Sym};
    let n = case.dim();
    let mut system = RSystem::new(
        n,
        move |fy: &mut Vector, _x: f64, y: &Vector, _a: &mut NoArgs| {
            f(case, y.as_data(), fy.as_mut_data());
            Ok(())
        },
    );
    system
        .set_jacobian(
            Some(n * n),
            Sym::No,
            move |jj: &mut CooMatrix, alpha: f64, _x: f64, y: &Vector, _a: &mut NoArgs| {
                let mut dense = [0.0; 64];
                (case.jac)(y.as_data(), &mut dense[..n * n]);
                jj.reset();
                for r in 0..n {
                    for c in 0..n {
                        jj.put(r, c, alpha * dense[r * n + c])?;
                    }
                }
                Ok(())
            },
        )
        .ok()?;
    let mut params = Params::new(RMethod::Radau5);
    why(
        "russell_ode tolerances",
        params.set_tolerances(atol, rtol, None),
    )?;
    params.step.n_step_max = 10_000_000;
    let mut solver = OdeSolver::new(params, system).ok()?;
    let mut y = Vector::from(&case.y0);
    let mut args = 0;
    why(
        "russell_ode Radau5",
        solver.solve(&mut y, 0.0, case.t_end, None, &mut args, None),
    )?;
    Some(y.as_data().to_vec())
}

fn diffsol(solver: Solver, case: &Case, rtol: f64, atol: f64) -> Option<Vec<f64>> {
    use diffsol::{
        NalgebraLU, NalgebraMat, OdeBuilder, OdeSolverMethod, OdeSolverStopReason, Vector,
    };
    type M = NalgebraMat<f64>;
    let n = case.dim();
    let problem = OdeBuilder::<M>::new()
        .rtol(rtol)
        .atol(vec![atol; n])
        .rhs_implicit(
            move |x: &[f64], _p: &[f64], _t: f64, y: &mut [f64]| f(case, x, y),
            // J·v from the same hand-written Jacobian (diffsol builds J from these products)
            move |x: &[f64], _p: &[f64], _t: f64, v: &[f64], y: &mut [f64]| {
                let mut dense = [0.0; 64];
                (case.jac)(x, &mut dense[..n * n]);
                for r in 0..n {
                    y[r] = (0..n).map(|c| dense[r * n + c] * v[c]).sum();
                }
            },
        )
        .init(
            move |_p: &[f64], _t: f64, y: &mut [f64]| y.copy_from_slice(case.y0),
            n,
        )
        .build();
    let mut problem = why(solver.label(), problem)?;
    // its default stops a solve after 5000 steps; everyone else gets 1e7
    problem.ode_options.max_number_timesteps = 10_000_000;
    fn finish<'a, S: OdeSolverMethod<'a, E>, E>(
        label: &str,
        mut s: S,
        t_end: f64,
    ) -> Option<Vec<f64>>
    where
        E: diffsol::OdeEquations<T = f64> + 'a,
    {
        why(label, s.set_stop_time(t_end))?;
        loop {
            match why(label, s.step())? {
                OdeSolverStopReason::TstopReached => break,
                _ => continue,
            }
        }
        let y = s.state().y;
        Some((0..y.len()).map(|i| y.get_index(i)).collect())
    }
    match solver {
        Solver::DiffsolBdf => {
            let s = why(solver.label(), problem.bdf::<NalgebraLU<f64>>())?;
            finish(solver.label(), s, case.t_end)
        }
        _ => {
            let s = why(solver.label(), problem.esdirk34::<NalgebraLU<f64>>())?;
            finish(solver.label(), s, case.t_end)
        }
    }
}
