//! `lectern bench`: work-precision report of our integrators (final-time error against
//! f-evaluations and wall time) on the oscillator, Kepler and the pendulum, plus the cost of
//! an expression-defined right-hand side against the same one as a native closure.
//! The comparison with other crates lives in `benches/work_precision.rs` (dev-dependencies).

use std::fmt::Write as _;
use std::path::PathBuf;

use crate::ode::fixed::AsSystem;
use crate::ode::native;
use crate::ode::problem::Problem;
use crate::ode::study::{
    Clock, Sample, Sweep, Timing, cost_at_error, max_error, reference, tolerances, work_precision,
    work_precision_fixed_n,
};
use crate::ode::{FixedSystem, FnSystem, Method, Scheme, System, solve_fixed_final};

/// Work-precision report of the integrators.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Folder with harmonic.ron, kepler.ron and pendulum.ron.
    #[arg(long, default_value = "slides/problems")]
    pub problems: PathBuf,
    /// Write the report (Markdown) here as well as printing it.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// A labelled run of the report.
struct Point {
    method: String,
    sample: Sample,
}

/// The benchmark cases: problem file, final time.
pub const CASES: [(&str, f64); 3] = [
    ("harmonic", 10.0),
    ("kepler", std::f64::consts::TAU),
    ("pendulum", 10.0),
];

pub fn run(args: Args) -> anyhow::Result<()> {
    let mut report = String::new();
    writeln!(
        report,
        "# lectern bench: work-precision of our integrators\n"
    )?;
    writeln!(
        report,
        "Error = max-norm difference of the final state from the exact solution (oscillator), the initial state after one period (Kepler) or a Verner 9(8) rtol 1e-14 reference (pendulum). Time = the fastest of repeated runs (at least {}, until {} ms are spent, at most {}: `ode::study::Timing::BENCH`). Adaptive pairs at rtol = atol = {:e} … {:e}.\n",
        Timing::BENCH.min_repeats,
        Timing::BENCH.budget_secs * 1e3,
        Timing::BENCH.max_repeats,
        tolerances()[0],
        tolerances().last().copied().unwrap_or_default(),
    )?;
    let fixed = [
        Method::Euler,
        Method::Midpoint,
        Method::Heun,
        Method::Rk4,
        Method::Verlet,
    ];
    for (name, t_end) in CASES {
        let p = Problem::load(args.problems.join(format!("{name}.ron")))
            .map_err(|d| anyhow::anyhow!("{d}"))?;
        let exact = final_reference(&p, t_end);
        // h so that the run has 2^k steps, from 64 to 65536
        let hs: Vec<f64> = (6..=16).map(|k| t_end / (1u64 << k) as f64).collect();
        let sweeps = fixed
            .into_iter()
            .map(|m| {
                let sweep = Sweep::Steps {
                    scheme: Scheme::Method(m),
                    hs: hs.clone(),
                };
                (m, sweep)
            })
            .chain(Method::PAIRS.into_iter().map(|m| {
                (
                    m,
                    Sweep::tolerances(m, crate::ode::adaptive::MAX_ADAPTIVE_STEPS),
                )
            }));
        let mut points = Vec::new();
        for (m, sweep) in sweeps {
            let samples = work_precision(&p, p.t0, &p.initial, t_end, &exact, &sweep, CLOCK);
            points.extend(labelled(m.name(), samples));
        }
        // the same RK4 on a native right-hand side: general driver and fixed-size fast path
        let native = match name {
            "harmonic" => native_points(native::Harmonic::from_problem(&p), &p, t_end, &exact, &hs),
            "kepler" => native_points(native::Kepler, &p, t_end, &exact, &hs),
            _ => native_points(native::Pendulum::from_problem(&p), &p, t_end, &exact, &hs),
        };
        points.extend(native?);
        writeln!(report, "## {} (t_end = {t_end:.4})\n", p.name)?;
        write_equal_error(&mut report, &points)?;
        write_table(&mut report, &points)?;
    }
    writeln!(
        report,
        "## Expression right-hand side against a native closure\n"
    )?;
    let ratio = expression_vs_native(&args.problems)?;
    writeln!(report, "{ratio}")?;
    print!("{report}");
    if let Some(out) = &args.out {
        std::fs::write(out, &report)?;
        eprintln!("wrote {}", out.display());
    }
    Ok(())
}

/// The exact final state, or the initial state for the periodic Kepler orbit, or a tight
/// Dormand–Prince reference.
pub fn final_reference(p: &Problem, t_end: f64) -> Vec<f64> {
    if let Some(e) = p.exact(t_end) {
        e
    } else if p.name.starts_with("Kepler") && (t_end - std::f64::consts::TAU).abs() < 1e-12 {
        p.initial.clone()
    } else {
        reference(p, p.t0, &p.initial, t_end)
    }
}

/// Every run of the report is timed by the benchmarks' policy.
const CLOCK: Clock = Clock::Measured(Timing::BENCH);

fn labelled(label: &str, samples: Vec<Sample>) -> impl Iterator<Item = Point> + '_ {
    samples.into_iter().map(move |sample| Point {
        method: label.to_owned(),
        sample,
    })
}

/// Labels of the native-RHS rows.
const RK4_NATIVE: &str = "rk4 native (slices)";
const RK4_FIXED: &str = "rk4 native [f64; N]";

/// RK4 on a native RHS through the general driver and through the fixed-size fast path.
fn native_points<const N: usize, S: FixedSystem<N> + Copy>(
    sys: S,
    p: &Problem,
    t_end: f64,
    exact: &[f64],
    hs: &[f64],
) -> anyhow::Result<Vec<Point>> {
    let x0: [f64; N] = p
        .initial
        .as_slice()
        .try_into()
        .map_err(|_| anyhow::anyhow!("{}: expected {N} initial values", p.path.display()))?;
    let sweep = Sweep::Steps {
        scheme: Scheme::Method(Method::Rk4),
        hs: hs.to_vec(),
    };
    let general = &AsSystem::<N, S>(sys);
    let samples = work_precision(general, p.t0, &p.initial, t_end, exact, &sweep, CLOCK);
    let mut out: Vec<Point> = labelled(RK4_NATIVE, samples).collect();
    let samples = work_precision_fixed_n(&sys, p.t0, x0, t_end, exact, hs, CLOCK);
    out.extend(labelled(RK4_FIXED, samples));
    Ok(out)
}

/// Time at equal error along each curve (log-log interpolation) and the speed-ups of the
/// fixed-size fast path.
fn write_equal_error(out: &mut String, points: &[Point]) -> std::fmt::Result {
    let curve = |m: &str| -> Vec<(f64, f64)> {
        points
            .iter()
            .filter(|p| p.method == m)
            .map(|p| (p.sample.error, p.sample.secs))
            .collect()
    };
    let (expr, slices, fixed, dp) = (
        curve("rk4"),
        curve(RK4_NATIVE),
        curve(RK4_FIXED),
        curve("dopri5"),
    );
    writeln!(
        out,
        "Time at equal error (µs; ratios are that time ÷ the fast path's, > 1 means the fast path is faster):\n"
    )?;
    writeln!(
        out,
        "| error | rk4 native [f64; N] | rk4 native (slices) | ÷ | rk4 expression | ÷ | dopri5 expression | ÷ |"
    )?;
    writeln!(out, "|---:|---:|---:|---:|---:|---:|---:|---:|")?;
    for k in [3, 5, 7, 9, 11] {
        let e = 10f64.powi(-k);
        let Some(tf) = cost_at_error(&fixed, e) else {
            continue;
        };
        let cell = |c: &[(f64, f64)]| match cost_at_error(c, e) {
            Some(t) => format!("{:.2} | {:.2}×", t * 1e6, t / tf),
            None => "– | –".into(),
        };
        writeln!(
            out,
            "| 1e-{k} | {:.2} | {} | {} | {} |",
            tf * 1e6,
            cell(&slices),
            cell(&expr),
            cell(&dp)
        )?;
    }
    writeln!(out)
}

fn write_table(out: &mut String, points: &[Point]) -> std::fmt::Result {
    writeln!(out, "| method | h or tol | error | f-evals | time (µs) |")?;
    writeln!(out, "|---|---:|---:|---:|---:|")?;
    for p in points {
        writeln!(
            out,
            "| {} | {:.3e} | {:.3e} | {} | {:.1} |",
            p.method,
            p.sample.h_or_tol,
            p.sample.error,
            p.sample.f_evals,
            p.sample.secs * 1e6
        )?;
    }
    writeln!(out)
}

/// The Kepler right-hand side written by hand, as the expression file has it.
pub fn kepler_native() -> FnSystem<impl Fn(f64, &[f64], &mut [f64])> {
    FnSystem::new(4, |_t, x: &[f64], d: &mut [f64]| {
        let r2 = x[0] * x[0] + x[1] * x[1];
        let r3 = r2 * r2.sqrt();
        d[0] = x[2];
        d[1] = x[3];
        d[2] = -x[0] / r3;
        d[3] = -x[1] / r3;
    })
}

/// Time of RK4 over one Kepler period (h = 2π/20000) with the expression RHS and with the
/// native closure; returns a Markdown line with both and their ratio.
fn expression_vs_native(dir: &std::path::Path) -> anyhow::Result<String> {
    let p = Problem::load(dir.join("kepler.ron")).map_err(|d| anyhow::anyhow!("{d}"))?;
    let native = kepler_native();
    let h = std::f64::consts::TAU / 20000.0;
    let time = |sys: &dyn System| {
        let (s, best) = Timing::BENCH.fastest(|| {
            solve_fixed_final(
                sys,
                Scheme::Method(Method::Rk4),
                0.0,
                &p.initial,
                h,
                std::f64::consts::TAU,
                f64::INFINITY,
            )
        });
        (best, s.last().1.to_vec())
    };
    let (t_expr, x_expr) = time(&p);
    let (t_native, x_native) = time(&native);
    let diff = max_error(&x_expr, &x_native);
    Ok(format!(
        "RK4, Kepler, 20000 steps: expression {:.3} ms, native closure {:.3} ms, ratio {:.2}× (final states differ by {diff:.1e}).\n",
        t_expr * 1e3,
        t_native * 1e3,
        t_expr / t_native
    ))
}
