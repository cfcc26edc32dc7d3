//! The Markdown page and the plots: per case, the frontier at equal error (each group's
//! fastest solver, interpolated in log-log along its curve), f-evaluations at equal error,
//! and every point; a summary over all cases.

use std::fmt::Write as _;
use std::path::Path;

use crate::Curve;
use crate::ode::study::cost_at_error;
use crate::plot;
use crate::problems::Case;

/// The errors the summary compares at: 1e-4 … 1e-10.
const TARGETS: std::ops::RangeInclusive<i32> = 4..=10;

/// The fastest (by `cost`) curve of a group at `error`: (cost, solver label).
fn best_at(
    curves: &[Curve],
    ours: bool,
    error: f64,
    cost: impl Fn(&(f64, f64, f64, u64)) -> f64,
) -> Option<(f64, &'static str)> {
    curves
        .iter()
        .filter(|c| c.solver.ours() == ours)
        .filter_map(|c| {
            let pts: Vec<(f64, f64)> = c.points.iter().map(|p| (p.1, cost(p))).collect();
            cost_at_error(&pts, error).map(|v| (v, c.solver.label()))
        })
        .min_by(|a, b| a.0.total_cmp(&b.0))
}

fn plots(case: &Case, curves: &[Curve], dir: &Path) {
    let series = |f: &dyn Fn(&(f64, f64, f64, u64)) -> f64| -> Vec<plot::Series> {
        curves
            .iter()
            .enumerate()
            .map(|(i, c)| plot::Series {
                label: c.solver.label().to_string(),
                color: plot::PALETTE[i % plot::PALETTE.len()],
                dashed: !c.solver.ours(),
                points: c
                    .points
                    .iter()
                    .filter(|p| p.1.is_finite())
                    .map(|p| (p.1, f(p)))
                    .collect(),
            })
            .collect()
    };
    plot::loglog(
        &dir.join(format!("stiff-{}-time.png", case.key)),
        &format!("{}: error vs wall time", case.key),
        "final-time error (max relative)",
        "wall time per solve (s)",
        &series(&|p| p.2),
    )
    .expect("write plot");
    plot::loglog(
        &dir.join(format!("stiff-{}-evals.png", case.key)),
        &format!("{}: error vs f-evaluations", case.key),
        "final-time error (max relative)",
        "f-evaluations",
        &series(&|p| p.3 as f64),
    )
    .expect("write plot");
}

/// (error exponent, ratio) rows of one case's frontier, written as a table.
fn frontier(out: &mut String, curves: &[Curve]) -> Vec<(i32, Option<f64>)> {
    writeln!(
        out,
        "| error | lectern's fastest | µs | peers' fastest | µs | peers ÷ lectern (time) | f-evals: lectern | peers | peers ÷ lectern |"
    )
    .unwrap();
    writeln!(out, "|---:|---|---:|---|---:|---:|---:|---:|---:|").unwrap();
    let mut rows = Vec::new();
    for k in TARGETS {
        let e = 10f64.powi(-k);
        let ours = best_at(curves, true, e, |p| p.2);
        let peers = best_at(curves, false, e, |p| p.2);
        let ours_n = best_at(curves, true, e, |p| p.3 as f64);
        let peers_n = best_at(curves, false, e, |p| p.3 as f64);
        let ratio = match (ours, peers) {
            (Some(o), Some(p)) => Some(p.0 / o.0),
            _ => None,
        };
        let cell = |v: Option<(f64, &str)>, scale: f64| match v {
            Some((c, l)) => format!("{l} | {:.0}", c * scale),
            None => "– | –".into(),
        };
        let n = |v: Option<(f64, &str)>| v.map_or("–".into(), |(c, l)| format!("{c:.0} ({l})"));
        let nratio = match (ours_n, peers_n) {
            (Some(o), Some(p)) => format!("{:.2}×", p.0 / o.0),
            _ => "–".into(),
        };
        writeln!(
            out,
            "| 1e-{k} | {} | {} | {} | {} | {} | {nratio} |",
            cell(ours, 1e6),
            cell(peers, 1e6),
            ratio.map_or("–".into(), |r| format!("**{r:.2}×**")),
            n(ours_n),
            n(peers_n),
        )
        .unwrap();
        rows.push((k, ratio));
    }
    writeln!(out).unwrap();
    rows
}

/// Which runs failed and why (the solver's own message, for the last failed tolerance of a
/// kind).
fn failures(out: &mut String, curves: &[Curve]) {
    let mut any = false;
    for c in curves {
        let mut kinds: Vec<(String, Vec<f64>)> = Vec::new();
        for (rtol, why) in &c.failures {
            match kinds.iter_mut().find(|k| &k.0 == why) {
                Some(k) => k.1.push(*rtol),
                None => kinds.push((why.clone(), vec![*rtol])),
            }
        }
        for (why, rtols) in kinds {
            if !any {
                writeln!(
                    out,
                    "Failed runs (left out of the frontier):
"
                )
                .unwrap();
                any = true;
            }
            let list: Vec<String> = rtols.iter().map(|r| format!("{r:.0e}")).collect();
            writeln!(out, "- rtol {}: {why}", list.join(", ")).unwrap();
        }
    }
    if any {
        writeln!(out).unwrap();
    }
}

fn points(out: &mut String, curves: &[Curve]) {
    writeln!(out, "<details><summary>every run</summary>\n").unwrap();
    writeln!(out, "| solver | rtol | error | f-evals | µs |").unwrap();
    writeln!(out, "|---|---:|---:|---:|---:|").unwrap();
    for c in curves {
        for p in &c.points {
            let err = if p.1.is_finite() {
                format!("{:.2e}", p.1)
            } else {
                "failed".into()
            };
            writeln!(
                out,
                "| {} | {:.0e} | {err} | {} | {:.1} |",
                c.solver.label(),
                p.0,
                p.3,
                p.2 * 1e6
            )
            .unwrap();
        }
    }
    writeln!(out, "\n</details>\n").unwrap();
}

/// scipy's Radau (committed counts) against lectern's radau5 at the same tolerances.
fn scipy(out: &mut String, case: &Case, curves: &[Curve], json: &serde_json::Value) {
    let Some(runs) = json["problems"][case.key]["runs"].as_array() else {
        return;
    };
    let ours = curves
        .iter()
        .find(|c| c.solver == crate::runners::Solver::LecternRadau5);
    let mut rows = String::new();
    for r in runs.iter().filter(|r| r["method"] == "Radau") {
        let rtol = r["rtol"].as_f64().unwrap_or(f64::NAN);
        let Some(p) = ours.and_then(|c| c.points.iter().find(|p| (p.0 / rtol - 1.0).abs() < 1e-9))
        else {
            continue;
        };
        writeln!(
            rows,
            "| {rtol:.0e} | {} | {:.2e} | {} | {:.2e} |",
            r["nfev"],
            r["max_rel_error"].as_f64().unwrap_or(f64::NAN),
            p.3,
            p.1
        )
        .unwrap();
    }
    if !rows.is_empty() {
        writeln!(
            out,
            "scipy's `Radau` (the same RADAU5 algorithm, analytic Jacobian; counts computed once by \
             `scripts/scipy_stiff_reference.py`) against lectern's radau5 at the same tolerances:\n\n\
             | rtol | scipy f-evals | scipy error | lectern f-evals | lectern error |\n\
             |---:|---:|---:|---:|---:|\n{rows}"
        )
        .unwrap();
    }
}

pub fn markdown(
    cases: &[Case],
    results: &[Vec<Curve>],
    tols: &[f64],
    json: &serde_json::Value,
    dir: &Path,
) -> String {
    let mut body = String::new();
    let mut summary = Vec::new();
    for (case, curves) in cases.iter().zip(results) {
        plots(case, curves, dir);
        writeln!(body, "## {}\n", case.title).unwrap();
        writeln!(body, "Reference: {}.\n", case.reference_source).unwrap();
        writeln!(
            body,
            "![error vs time](stiff-{0}-time.png)\n\n![error vs f-evaluations](stiff-{0}-evals.png)\n",
            case.key
        )
        .unwrap();
        summary.push((case.title, frontier(&mut body, curves)));
        scipy(&mut body, case, curves, json);
        writeln!(body).unwrap();
        failures(&mut body, curves);
        points(&mut body, curves);
    }
    let mut md = String::new();
    writeln!(md, "# Stiff solvers: lectern against the Rust peers\n").unwrap();
    writeln!(
        md,
        "Generated by `scripts/bench-stiff` (the separate cargo project `benches/stiff-peers`, \
         release build; one run for every figure on this page; machine: {} CPU threads shared \
         with other jobs, so absolute times are noisy). Each point is the fastest of repeated \
         solves by lectern's one timing policy (`ode::study::Timing::BENCH`: at least 3, until \
         30 ms are spent, at most 200) in each of {} rounds spread over the run. Tolerances \
         rtol = {:.0e} … {:.0e} per decade, atol = ratio · rtol as each case says. Error = the \
         largest relative error over the components of the final state against the reference \
         (the measure of `scripts/scipy_stiff_reference.py`). f-evaluations are counted at the \
         right-hand side itself, the same way for every solver (Jacobian evaluations not \
         included; everyone gets the exact one).\n",
        std::thread::available_parallelism().map_or(1, |n| n.get()),
        crate::ROUNDS,
        tols[0],
        tols[tols.len() - 1],
    )
    .unwrap();
    writeln!(
        md,
        "Solvers, each handed the same hand-written right-hand side and exact Jacobian \
         (`benches/stiff-peers/src/problems.rs`): **lectern rodas5p, radau5** \
         (`ode::solve_embedded`, general slice driver, final state only); \
         **differential-equations 0.7** Radau5, BDF, Kvaerno745 (`[f64; N]` state, a \
         keep-the-last-point output handler, its dense `Matrix` Jacobian filled from ours); \
         **russell_ode 5** Radau5 (its Jacobian is a COO sparse matrix; we put all n² \
         entries; its default linear solver); **diffsol 0.19** BDF and ESDIRK34 (nalgebra \
         dense matrices and LU; diffsol asks for Jacobian-vector products, which we compute \
         from the same exact Jacobian).\n"
    )
    .unwrap();
    writeln!(
        md,
        "Notes on the peers, as built here (Debian 12, Rust 1.95): all four crates build. \
         `russell_ode` 5 needs no BLAS by default (its `russell_lab` uses the pure-Rust \
         `algebra_linear` kernels; OpenBLAS is an optional feature, not used here: for n ≤ 8 \
         the call overhead would dominate) and refuses atol ≤ 10·ε (≈ 2.2e-15), which rules \
         out Robertson's tight runs. differential-equations' BDF cannot start (\"step size \
         became too small\" at t = 0) where atol is tiny, and its Kvaerno745 gives up after 10 \
         rejections in a row by default, which stopped it on every case: it runs here with \
         `max_rejects(1000)`; diffsol stops a solve after 5000 steps by default and runs here with \
         `max_number_timesteps = 1e7`, the budget every solver gets. Every failed run is listed under its case with the solver's own \
         message. lectern's linear algebra is dense LU (n³/3 per factorisation; RADAU5 needs a \
         real and a complex one per new matrix): right for the n ≤ a few dozen a lecture meets, \
         not for large sparse systems (a PDE's method of lines), where diffsol and russell_ode \
         offer sparse solvers.\n"
    )
    .unwrap();
    writeln!(md, "## Summary\n").unwrap();
    writeln!(
        md,
        "Peers' best time ÷ lectern's best time at equal error, at errors 1e-4 … 1e-10 \
         (log-log interpolation along each solver's curve; > 1 means lectern is faster). \
         Target ≥ 1.0 everywhere, goal ≥ 1.5.\n"
    )
    .unwrap();
    writeln!(
        md,
        "| case | range of ratios | worst at | ≥ 1.0 everywhere? | ≥ 1.5 everywhere? |"
    )
    .unwrap();
    writeln!(md, "|---|---:|---:|---|---|").unwrap();
    for (title, rows) in &summary {
        let vals: Vec<(i32, f64)> = rows
            .iter()
            .filter_map(|(k, r)| r.map(|r| (*k, r)))
            .collect();
        let verdict = |min: f64| {
            let all = vals.iter().all(|v| v.1 >= min);
            let missing = vals.len() < rows.len();
            match (all, missing) {
                (false, _) => "**missed**".to_string(),
                (true, false) => "met".to_string(),
                (true, true) => format!("met where both reach ({} of {})", vals.len(), rows.len()),
            }
        };
        let lo = vals.iter().map(|v| v.1).fold(f64::INFINITY, f64::min);
        let hi = vals.iter().map(|v| v.1).fold(f64::NEG_INFINITY, f64::max);
        let worst = vals.iter().min_by(|a, b| a.1.total_cmp(&b.1));
        writeln!(
            md,
            "| {title} | {} | {} | {} | {} |",
            if vals.is_empty() {
                "–".into()
            } else {
                format!("{lo:.2}× – {hi:.2}×")
            },
            worst.map_or("–".into(), |w| format!("1e-{} ({:.2}×)", w.0, w.1)),
            verdict(1.0),
            verdict(1.5)
        )
        .unwrap();
    }
    writeln!(md).unwrap();
    md.push_str(&body);
    md
}
