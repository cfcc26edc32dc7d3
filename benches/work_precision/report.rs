//! The report: the frontier table (time of the peers' best ÷ lectern's best at equal error),
//! the scipy reference figures, the plots and all points, written as Markdown.

use std::fmt::Write as _;
use std::path::Path;

use lectern::ode::study::{cost_at_error, max_error};
use lectern::ode::{Adaptive, Method, solve_embedded_n};

use super::plot;
use super::runners::{Curve, FIXED_RK4};

pub struct Case {
    pub name: &'static str,
    pub title: &'static str,
    pub curves: Vec<Curve>,
}

/// The errors of the frontier table: 1e-3 … 1e-11.
pub const ERRORS: std::ops::RangeInclusive<i32> = 3..=11;

/// A curve's time at a given error, interpolated in log-log (None outside its range).
pub fn time_at(curve: &Curve, error: f64) -> Option<f64> {
    let pts: Vec<(f64, f64)> = curve.points.iter().map(|p| (p.0, p.1)).collect();
    cost_at_error(&pts, error)
}

/// The fastest curve among those `pick` accepts at a given error: (label, seconds).
pub fn fastest_at<'a>(
    case: &'a Case,
    error: f64,
    pick: impl Fn(&Curve) -> bool,
) -> Option<(&'a str, f64)> {
    case.curves
        .iter()
        .filter(|c| pick(c))
        .filter_map(|c| time_at(c, error).map(|t| (c.label.as_str(), t)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
}

/// Keeps the faster time of each point (errors and f-evaluations are deterministic).
pub fn merge_min(case: &mut Case, again: Vec<Curve>) {
    for (c, a) in case.curves.iter_mut().zip(again) {
        assert_eq!(c.label, a.label);
        for (p, q) in c.points.iter_mut().zip(a.points) {
            assert_eq!((p.0.to_bits(), p.2), (q.0.to_bits(), q.2), "{}", c.label);
            p.1 = p.1.min(q.1);
        }
    }
}

/// The frontier: at each error, lectern's best method against the peers' best; returns the
/// ratios (peer time ÷ our time) where both reach the error.
pub fn frontier_table(out: &mut String, case: &Case) -> Vec<(i32, Option<f64>)> {
    writeln!(
        out,
        "| error | lectern's best | its time (µs) | peers' best | its time (µs) | peers' best ÷ lectern's best |"
    )
    .unwrap();
    writeln!(out, "|---:|---|---:|---|---:|---:|").unwrap();
    let mut ratios = Vec::new();
    for k in ERRORS {
        let e = 10f64.powi(-k);
        let ours = fastest_at(case, e, |c| c.ours);
        let peer = fastest_at(case, e, |c| !c.ours);
        let cell = |p: Option<(&str, f64)>| match p {
            Some((label, t)) => format!("{label} | {:.2}", t * 1e6),
            None => "(not reached) | ".into(),
        };
        let ratio = match (ours, peer) {
            (Some(o), Some(p)) => Some(p.1 / o.1),
            _ => None,
        };
        writeln!(
            out,
            "| 1e-{k} | {} | {} | {} |",
            cell(ours),
            cell(peer),
            ratio.map_or("–".into(), |r| format!("**{r:.2}×**"))
        )
        .unwrap();
        ratios.push((k, ratio));
    }
    writeln!(out).unwrap();
    ratios
}

/// f-evaluations at error 1e-9 of every adaptive curve (interpolated), best first.
pub fn evals_line(out: &mut String, case: &Case) {
    let mut v: Vec<(String, f64)> = case
        .curves
        .iter()
        .filter(|c| c.adaptive || c.label == FIXED_RK4)
        .filter_map(|c| {
            let pts: Vec<(f64, f64)> = c.points.iter().map(|p| (p.0, p.2 as f64)).collect();
            cost_at_error(&pts, 1e-9).map(|n| (c.label.clone(), n))
        })
        .collect();
    v.sort_by(|a, b| a.1.total_cmp(&b.1));
    let list: Vec<String> = v.iter().map(|(l, n)| format!("{l} {n:.0}")).collect();
    writeln!(out, "f-evaluations at error 1e-9: {}.\n", list.join(", ")).unwrap();
}

pub fn points_table(out: &mut String, case: &Case) {
    writeln!(out, "<details><summary>All points</summary>\n").unwrap();
    writeln!(out, "| solver | error | f-evals | time (µs) |").unwrap();
    writeln!(out, "|---|---:|---:|---:|").unwrap();
    for c in &case.curves {
        for p in &c.points {
            writeln!(
                out,
                "| {} | {:.3e} | {} | {:.2} |",
                c.label,
                p.0,
                p.2,
                p.1 * 1e6
            )
            .unwrap();
        }
    }
    writeln!(out, "\n</details>\n").unwrap();
}

/// The curves worth a colour: ours on the fast path, and the peers' RK4 and best adaptive ones.
fn plotted(c: &Curve) -> bool {
    if c.ours {
        !c.label.contains("slices")
    } else {
        matches!(
            c.label.as_str(),
            "ode_solvers RK4" | "ode_solvers Dop853" | "diff-eq DOP853" | "diff-eq RKV988e"
        )
    }
}

pub fn plots(case: &Case, dir: &Path) {
    let series = |f: &dyn Fn(&(f64, f64, u64)) -> f64| -> Vec<plot::Series> {
        case.curves
            .iter()
            .filter(|c| plotted(c))
            .enumerate()
            .map(|(i, c)| plot::Series {
                label: c.label.clone(),
                color: plot::PALETTE[i % plot::PALETTE.len()],
                dashed: !c.ours,
                points: c.points.iter().map(|p| (p.0, f(p))).collect(),
            })
            .collect()
    };
    plot::loglog(
        &dir.join(format!("ode-{}-time.png", case.name)),
        &format!("{}: error vs wall time", case.title),
        "final-time error (max norm)",
        "wall time per solve (s)",
        &series(&|p| p.1),
    )
    .unwrap();
    plot::loglog(
        &dir.join(format!("ode-{}-evals.png", case.name)),
        &format!("{}: error vs f-evaluations", case.title),
        "final-time error (max norm)",
        "f-evaluations",
        &series(&|p| p.2 as f64),
    )
    .unwrap();
}

/// scipy's `solve_ivp(method="DOP853")` (committed figures) against our DOP853 and Vern9 at
/// the same tolerances, on Kepler e = 0.6 over one period.
pub fn scipy_table(out: &mut String) {
    let text = std::fs::read_to_string("tests/data/ode_reference.json").unwrap();
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    let kep = &json["kepler_e06"];
    writeln!(
        out,
        "| rtol = atol | scipy {} DOP853: f-evals | its error | lectern dop853: f-evals | its error | lectern vern9: f-evals | its error |",
        json["scipy"].as_str().unwrap_or("?")
    )
    .unwrap();
    writeln!(out, "|---:|---:|---:|---:|---:|---:|---:|").unwrap();
    let x0 = [0.4, 0.0, 0.0, 2.0];
    for row in kep["scipy_dop853"].as_array().unwrap() {
        let tol = row["tol"].as_f64().unwrap();
        let ours = |m: Method| {
            let opts = Adaptive {
                rtol: tol,
                atol: tol,
                ..Adaptive::default()
            };
            let sol = solve_embedded_n(
                &lectern::ode::native::Kepler,
                m,
                0.0,
                x0,
                std::f64::consts::TAU,
                opts,
            );
            (sol.f_evals, max_error(&sol.x, &x0))
        };
        let (d, v) = (ours(Method::Dop853), ours(Method::Vern9));
        writeln!(
            out,
            "| {tol:.0e} | {} | {:.2e} | {} | {:.2e} | {} | {:.2e} |",
            row["nfev"],
            row["error"].as_f64().unwrap(),
            d.0,
            d.1,
            v.0,
            v.1
        )
        .unwrap();
    }
    writeln!(out).unwrap();
}
