//! The stiff benchmark (issue #26): lectern's rodas5p and radau5 against the Rust peers'
//! stiff solvers on Robertson, Van der Pol μ = 1000, HIRES and OREGO, error against the test
//! set's reference solutions vs wall time and vs f-evaluations, every solver with the same
//! hand-written exact Jacobian. Writes `stiff.md` and its plots into the folder given (run by
//! `scripts/bench-stiff`, which passes `docs/benchmarks`).
//!
//! lectern's numerics core is compiled in from the main tree by `#[path]` (no path dependency:
//! that would build the whole app, typst and wgpu included); the timing policy and the
//! tolerance list are lectern's own (`ode::study::Timing::BENCH`, `ode::study::tolerances`).

#[allow(dead_code, unused_imports)]
#[path = "../../../src/diag.rs"]
mod diag;
#[allow(dead_code, unused_imports, clippy::all)]
#[path = "../../../src/ode/mod.rs"]
mod ode;
#[allow(dead_code)]
#[path = "../../work_precision/plot.rs"]
mod plot;
mod problems;
mod report;
#[allow(dead_code, unused_imports)]
#[path = "../../../src/ron_tree.rs"]
mod ron_tree;
mod runners;

use std::path::PathBuf;

use ode::study::{Timing, tolerances};
use problems::Case;
use runners::Solver;

/// One solver's sweep on one case: (rtol, error, seconds, f-evaluations) per tolerance, and
/// why runs failed (rtol, the solver's message).
pub struct Curve {
    pub solver: Solver,
    pub points: Vec<(f64, f64, f64, u64)>,
    pub failures: Vec<(f64, String)>,
}

/// A run slower than this ends the solver's sweep on that case (tighter ones are slower).
const SLOW_SECS: f64 = 3.0;

/// Rounds over all cases, keeping each point's fastest: a burst of load on the shared
/// machine then does not decide a ratio.
const ROUNDS: usize = 2;

fn sweep(case: &Case, solver: Solver, tols: &[f64]) -> Curve {
    let mut points = Vec::new();
    let mut failures = Vec::new();
    for &rtol in tols {
        let ((y, evals), secs) = Timing::BENCH.fastest(|| solver.run(case, rtol));
        let error = case.error(y.as_deref());
        if let Some(why) = runners::take_why() {
            failures.push((rtol, why));
        }
        points.push((rtol, error, secs, evals));
        if secs > SLOW_SECS {
            break;
        }
    }
    Curve {
        solver,
        points,
        failures,
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let quick = args.iter().any(|a| a == "--quick");
    let out = PathBuf::from(
        args.iter()
            .find(|a| !a.starts_with("--"))
            .map_or("docs/benchmarks", String::as_str),
    );
    let json: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string("tests/data/stiff_reference.json")
            .expect("tests/data/stiff_reference.json (run from the repository root)"),
    )
    .expect("stiff_reference.json");
    let cases = problems::cases(&json);
    // `--profile CASE SOLVER-LABEL RTOL REPEATS`: one solve repeated, for `perf record`
    if let Some(i) = args.iter().position(|a| a == "--profile") {
        let get = |k: usize| args.get(i + k).map(String::as_str).unwrap_or_default();
        let case = cases.iter().find(|c| c.key == get(1)).expect("a case key");
        let solver = Solver::ALL
            .into_iter()
            .find(|s| s.label() == get(2))
            .expect("a solver label");
        let rtol: f64 = get(3).parse().expect("rtol");
        let repeats: usize = get(4).parse().expect("repeats");
        let start = std::time::Instant::now();
        let mut evals = 0;
        for _ in 0..repeats {
            evals = std::hint::black_box(solver.run(case, rtol)).1;
        }
        let per = start.elapsed().as_secs_f64() / repeats as f64;
        println!(
            "{} {} rtol {rtol:e}: {:.1} µs a solve, {evals} f-evaluations",
            case.key,
            solver.label(),
            per * 1e6
        );
        return;
    }
    // rtol 1e-2 … 1e-12 (the list every lectern study uses, less its last decade: RADAU5-type
    // codes refuse rtol near 1e-13 after their tolerance transformation)
    let tols: Vec<f64> = tolerances()
        .into_iter()
        .filter(|&t| t > 5e-13)
        .step_by(if quick { 3 } else { 1 })
        .collect();
    let mut results: Vec<Vec<Curve>> = Vec::new();
    for round in 0..ROUNDS {
        for (k, case) in cases.iter().enumerate() {
            eprintln!("round {}: {}", round + 1, case.title);
            let curves: Vec<Curve> = Solver::ALL.iter().map(|&s| sweep(case, s, &tols)).collect();
            if round == 0 {
                results.push(curves);
            } else {
                for (old, new) in results[k].iter_mut().zip(curves) {
                    for (p, q) in old.points.iter_mut().zip(new.points) {
                        p.2 = p.2.min(q.2);
                    }
                }
            }
        }
    }
    let md = report::markdown(&cases, &results, &tols, &json, &out);
    std::fs::write(out.join("stiff.md"), &md).expect("write stiff.md");
    println!("{md}");
}
