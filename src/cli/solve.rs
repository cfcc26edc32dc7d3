//! `lectern solve`: integrate an ODE problem file and print the final state (one line
//! `t x1 x2 …`) or, with `--trajectory`, every step as CSV. Work goes to stderr.

use std::io::Write;
use std::path::PathBuf;

use anyhow::{Context, bail};

use crate::ode::problem::Problem;
use crate::ode::{
    Adaptive, Method, Outcome, Solution, Tableau, solve_embedded, solve_fixed,
    solve_implicit_adaptive, solve_tableau,
};

/// Integrate an ODE problem file.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The problem (RON: name, vars, rhs, params, initial, t0, exact).
    pub problem: PathBuf,
    /// euler, midpoint, heun, rk4, symplectic-euler, verlet, implicit-euler,
    /// implicit-midpoint, an adaptive pair: dopri5, tsit5, vern6, vern7, vern8, vern9,
    /// dop853, or an adaptive stiff solver: rodas5p, radau5.
    #[arg(long, default_value = "rk4")]
    pub method: Method,
    /// A custom explicit Runge–Kutta method as a Butcher tableau (RON); overrides --method.
    #[arg(long)]
    pub tableau: Option<PathBuf>,
    /// Fixed step size (the adaptive pairs take it as their first step).
    #[arg(long)]
    pub h: Option<f64>,
    /// Final time.
    #[arg(long)]
    pub t_end: f64,
    /// Relative tolerance of the adaptive methods (> 10 machine epsilons).
    #[arg(long, default_value_t = 1e-6)]
    pub rtol: f64,
    /// Absolute tolerance of the adaptive methods (> 0).
    #[arg(long, default_value_t = 1e-9)]
    pub atol: f64,
    /// Print every step as CSV (header `t,<vars>`) instead of the final state.
    #[arg(long)]
    pub trajectory: bool,
    /// A state component beyond this magnitude counts as divergence.
    #[arg(long, default_value_t = 1e12)]
    pub bound: f64,
    /// Go on when dopri5 or dop853 finds the problem stiff (by default the run stops there
    /// and suggests a stiff solver).
    #[arg(long)]
    pub ignore_stiffness: bool,
    /// Override a parameter of the problem, e.g. `--param w=2` (repeatable).
    #[arg(long = "param", value_name = "NAME=VALUE")]
    pub params: Vec<String>,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let mut problem = Problem::load(&args.problem).map_err(|d| anyhow::anyhow!("{d}"))?;
    for p in &args.params {
        let (name, value) = p
            .split_once('=')
            .with_context(|| format!("--param `{p}` is not NAME=VALUE"))?;
        let value: f64 = value
            .trim()
            .parse()
            .with_context(|| format!("--param `{p}`: not a number"))?;
        problem
            .set_param(name.trim(), value)
            .map_err(anyhow::Error::msg)?;
    }
    let x0 = problem.initial.clone();
    let t0 = problem.t0;
    let (label, sol) = if let Some(path) = &args.tableau {
        let tab = Tableau::load(path).map_err(|d| anyhow::anyhow!("{d}"))?;
        let h = args.h.context("--h is required with --tableau")?;
        (
            tab.name.clone(),
            solve_tableau(&problem, &tab, t0, &x0, h, args.t_end, args.bound),
        )
    } else if args.method.is_adaptive() {
        let opts = Adaptive {
            rtol: args.rtol,
            atol: args.atol,
            h0: args.h,
            bound: args.bound,
            record: args.trajectory,
            stop_if_stiff: !args.ignore_stiffness,
            ..Adaptive::default()
        };
        (
            args.method.name().to_string(),
            solve_embedded(&problem, args.method, t0, &x0, args.t_end, opts),
        )
    } else if args.method.is_implicit() && args.h.is_none() {
        // no step given: implicit methods run with step-doubling error control
        let opts = Adaptive {
            rtol: args.rtol,
            atol: args.atol,
            bound: args.bound,
            record: args.trajectory,
            ..Adaptive::default()
        };
        (
            format!("{} (adaptive)", args.method),
            solve_implicit_adaptive(&problem, args.method, t0, &x0, args.t_end, opts),
        )
    } else {
        let h = args
            .h
            .with_context(|| format!("--h is required for {}", args.method))?;
        (
            args.method.name().to_string(),
            solve_fixed(&problem, args.method, t0, &x0, h, args.t_end, args.bound),
        )
    };
    print_solution(&problem, &sol, args.trajectory)?;
    let mut err = std::io::stderr().lock();
    write!(
        err,
        "{label}: f-evaluations: {}, steps: {}",
        sol.f_evals, sol.steps
    )?;
    if sol.rejected > 0 || (args.method.is_adaptive() && args.tableau.is_none()) {
        write!(err, " (rejected: {})", sol.rejected)?;
    }
    if args.method.is_stiff_solver() && args.tableau.is_none() {
        write!(
            err,
            ", Jacobian evaluations: {}, LU decompositions: {}",
            sol.work.jac_evals, sol.work.lu_decomps
        )?;
    }
    writeln!(err)?;
    match &sol.outcome {
        Outcome::Finished => Ok(()),
        Outcome::Stiff { .. } => bail!(
            "{}: {} (or --ignore-stiffness to go on)",
            problem.name,
            sol.outcome
        ),
        other => bail!("{}: {other}", problem.name),
    }
}

fn print_solution(problem: &Problem, sol: &Solution, trajectory: bool) -> anyhow::Result<()> {
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    if trajectory {
        writeln!(out, "t,{}", problem.vars.join(","))?;
        for i in 0..sol.len() {
            write!(out, "{}", sol.ts[i])?;
            for v in sol.state(i) {
                write!(out, ",{v}")?;
            }
            writeln!(out)?;
        }
    } else {
        let (t, x) = sol.last();
        write!(out, "{t}")?;
        for v in x {
            write!(out, " {v}")?;
        }
        writeln!(out)?;
    }
    out.flush()?;
    Ok(())
}
