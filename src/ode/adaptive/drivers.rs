//! The public adaptive drivers: any embedded pair on a `System` (recording a `Solution`) or on
//! a fixed-size system (the fast path, final state and a per-step callback), and step doubling
//! for the implicit methods. All of them run [`drive`].

use super::doubling::Doubling;
use super::implicit_trials::{RadauTrial, RodasTrial};
use super::pair_stepper::{Fast, PairStepper, Slices};
use super::{Adaptive, Run, Trial, check, drive};
use crate::ode::fixed::{AsSystem, FixedSolution, FixedSystem};
use crate::ode::pairs::{Controller, Pair, with_pair};
use crate::ode::solve::{Outcome, Solution};
use crate::ode::{Method, System};

/// Adaptive Dormand–Prince 5(4) from t0 to t_end (the default pair; see [`solve_embedded`]).
pub fn solve_adaptive<S: System + ?Sized>(
    sys: &S,
    t0: f64,
    x0: &[f64],
    t_end: f64,
    opts: Adaptive,
) -> Solution {
    solve_embedded(sys, Method::Dopri5, t0, x0, t_end, opts)
}

/// Integrates from t0 to t_end with an adaptive method: an embedded pair (`dopri5`, `tsit5`,
/// `vern6` … `vern9`, `dop853`) or a stiff solver (`rodas5p`, `radau5`). f-evaluations,
/// accepted and rejected steps (and Jacobians and LUs) are counted in the solution; bad
/// tolerances, a non-finite f, a failing Newton iteration and a step-size underflow end in
/// `Failed`, a state beyond `opts.bound` in `Diverged`, a fired stiffness test in `Stiff`
/// (with `opts.stop_if_stiff`), and `opts.max_steps` bounds the work.
pub fn solve_embedded<S: System + ?Sized>(
    sys: &S,
    method: Method,
    t0: f64,
    x0: &[f64],
    t_end: f64,
    opts: Adaptive,
) -> Solution {
    let mut sol = Solution::start(x0.len(), t0, x0);
    if let Err(outcome) = check(sys.dim(), t0, x0, t_end, &opts) {
        sol.outcome = outcome;
        return sol;
    }
    match method {
        Method::Rodas5p => {
            let mut trial = RodasTrial::new(sys, x0);
            recorded(&mut trial, t0, t_end, &opts, RODAS_CONTROL, sol)
        }
        Method::Radau5 => {
            let mut trial = RadauTrial::new(sys, x0);
            recorded(&mut trial, t0, t_end, &opts, RADAU_CONTROL, sol)
        }
        _ => with_pair!(
            method,
            |pair| {
                let mut trial = PairStepper::new(pair, Slices(sys), x0.to_vec());
                recorded(&mut trial, t0, t_end, &opts, control_of(pair), sol)
            },
            {
                sol.outcome = not_a_pair(t0, method);
                sol
            }
        ),
    }
}

/// RODAS's controller: exponent 1/5 for the order-4 embedded estimate.
const RODAS_CONTROL: Controller = Controller::predictive(5, 6.0, 1.0);
/// radau5.f: err^(1/4), ratio in [1/5, 8], steps kept within 1 … 1.2.
const RADAU_CONTROL: Controller = Controller::predictive(4, 8.0, 1.2);

fn control_of<const S: usize, P: Pair<S>>(_: P) -> Controller {
    P::CONTROL
}

fn not_a_pair(t: f64, method: Method) -> Outcome {
    Outcome::Failed {
        t,
        reason: format!("{method} is not an adaptive method"),
    }
}

/// Runs the loop, recording into `sol` (every accepted step, or only the last).
fn recorded<T: Trial>(
    trial: &mut T,
    t0: f64,
    t_end: f64,
    opts: &Adaptive,
    ctrl: Controller,
    mut sol: Solution,
) -> Solution {
    let record = opts.record;
    let run = drive(trial, t0, t_end, opts, ctrl, |t, x| sol.push(t, x, record));
    sol.f_evals = trial.f_evals();
    sol.steps = run.steps;
    sol.rejected = run.rejected;
    sol.work = trial.work();
    sol.outcome = run.outcome;
    sol
}

/// [`solve_embedded`] on the fixed-size fast path: state `[f64; N]`, f inlined, nothing
/// recorded (`opts.record` is ignored); the final state and the work come back.
pub fn solve_embedded_n<const N: usize, S: FixedSystem<N> + ?Sized>(
    sys: &S,
    method: Method,
    t0: f64,
    x0: [f64; N],
    t_end: f64,
    opts: Adaptive,
) -> FixedSolution<N> {
    solve_embedded_n_with(sys, method, t0, x0, t_end, opts, |_, _| {})
}

/// [`solve_embedded_n`] calling `on_step(t, &x)` after every accepted step; a no-op closure
/// compiles away. The stiff solvers (`rodas5p`, `radau5`) take the same path through the
/// general system view ([`AsSystem`]): their Newton matrices are sized at run time anyway, and
/// the system's own Jacobian ([`FixedSystem::jacobian`]) is used where it has one.
pub fn solve_embedded_n_with<const N: usize, S: FixedSystem<N> + ?Sized>(
    sys: &S,
    method: Method,
    t0: f64,
    x0: [f64; N],
    t_end: f64,
    opts: Adaptive,
    mut on_step: impl FnMut(f64, &[f64; N]),
) -> FixedSolution<N> {
    let mut sol = FixedSolution {
        t: t0,
        x: x0,
        f_evals: 0,
        steps: 0,
        rejected: 0,
        outcome: Outcome::Finished,
    };
    if let Err(outcome) = check(N, t0, &x0, t_end, &opts) {
        sol.outcome = outcome;
        return sol;
    }
    let general = AsSystem::<N, &S>(sys);
    match method {
        Method::Rodas5p => {
            let mut trial = RodasTrial::new(&general, &x0);
            let run = drive(&mut trial, t0, t_end, &opts, RODAS_CONTROL, |t, x| {
                on_step(t, as_array(x))
            });
            return finish_fixed(&trial, run, sol);
        }
        Method::Radau5 => {
            let mut trial = RadauTrial::new(&general, &x0);
            let run = drive(&mut trial, t0, t_end, &opts, RADAU_CONTROL, |t, x| {
                on_step(t, as_array(x))
            });
            return finish_fixed(&trial, run, sol);
        }
        _ => {}
    }
    with_pair!(
        method,
        |pair| {
            let mut trial = PairStepper::new(pair, Fast(sys), x0);
            let run = drive(&mut trial, t0, t_end, &opts, control_of(pair), |t, x| {
                on_step(t, as_array(x))
            });
            finish_fixed(&trial, run, sol)
        },
        {
            sol.outcome = not_a_pair(t0, method);
            sol
        }
    )
}

#[inline(always)]
fn as_array<const N: usize>(x: &[f64]) -> &[f64; N] {
    x.try_into().expect("a state of N values")
}

fn finish_fixed<const N: usize, T: Trial>(
    trial: &T,
    run: Run,
    mut sol: FixedSolution<N>,
) -> FixedSolution<N> {
    sol.t = run.t;
    sol.x = *as_array(if run.ended_on_candidate {
        trial.candidate()
    } else {
        trial.state()
    });
    sol.f_evals = trial.f_evals();
    sol.steps = run.steps;
    sol.rejected = run.rejected;
    sol.outcome = run.outcome;
    sol
}

/// Implicit Euler or implicit midpoint with step-size control by step doubling (see
/// `adaptive::doubling`); `rodas5p` and `radau5` run with their own error estimates
/// ([`solve_embedded`]).
pub fn solve_implicit_adaptive<S: System + ?Sized>(
    sys: &S,
    method: Method,
    t0: f64,
    x0: &[f64],
    t_end: f64,
    opts: Adaptive,
) -> Solution {
    if method.is_stiff_solver() {
        return solve_embedded(sys, method, t0, x0, t_end, opts);
    }
    let mut sol = Solution::start(x0.len(), t0, x0);
    if !method.is_implicit() {
        sol.outcome = Outcome::Failed {
            t: t0,
            reason: format!("{method} is not an implicit method"),
        };
        return sol;
    }
    if let Err(outcome) = check(sys.dim(), t0, x0, t_end, &opts) {
        sol.outcome = outcome;
        return sol;
    }
    let mut trial = Doubling::new(sys, method, x0);
    recorded(
        &mut trial,
        t0,
        t_end,
        &opts,
        Doubling::<S>::controller(method),
        sol,
    )
}
