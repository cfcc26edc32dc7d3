//! Convergence and work-precision studies: pure functions over a system, so a slide can run
//! them on a background thread and `lectern bench` can print them.

use std::time::Instant;

use super::adaptive::{Adaptive, solve_embedded};
use super::fixed::{FixedSystem, solve_fixed_n};
use super::solve::{Scheme, solve_fixed_final};
use super::{Method, System};

/// Max-norm distance between two states (∞ when either is not finite).
pub fn max_error(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, |m, e| {
            if e.is_nan() || m.is_nan() {
                f64::INFINITY
            } else {
                m.max(e)
            }
        })
}

/// Final-time errors as h shrinks, with the least-squares slope of log(err) over log(h):
/// the measured order.
#[derive(Debug, Clone, PartialEq)]
pub struct Convergence {
    /// (h, error at t_end)
    pub points: Vec<(f64, f64)>,
    pub slope: f64,
}

/// The least-squares slope of log y over log x.
pub fn loglog_slope(points: &[(f64, f64)]) -> f64 {
    let pts: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| *x > 0.0 && *y > 0.0 && y.is_finite())
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    let n = pts.len() as f64;
    if pts.len() < 2 {
        return f64::NAN;
    }
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    sxy / sxx
}

/// Runs `scheme` with each h from t0 to t_end and compares the final state with `exact_end`.
pub fn convergence<S: System + ?Sized>(
    sys: &S,
    scheme: Scheme<'_>,
    t0: f64,
    x0: &[f64],
    t_end: f64,
    exact_end: &[f64],
    hs: &[f64],
) -> Convergence {
    let points: Vec<(f64, f64)> = hs
        .iter()
        .map(|&h| {
            let sol = solve_fixed_final(sys, scheme, t0, x0, h, t_end, f64::INFINITY);
            let err = if sol.finished() {
                max_error(sol.last().1, exact_end)
            } else {
                f64::INFINITY
            };
            (h, err)
        })
        .collect();
    let slope = loglog_slope(&points);
    Convergence { points, slope }
}

/// A very accurate final state (Verner 9(8) at rtol 1e-14) for problems without an exact
/// solution.
pub fn reference<S: System + ?Sized>(sys: &S, t0: f64, x0: &[f64], t_end: f64) -> Vec<f64> {
    let opts = Adaptive {
        rtol: 1e-14,
        atol: 1e-16,
        record: false,
        ..Adaptive::default()
    };
    solve_embedded(sys, Method::Vern9, t0, x0, t_end, opts)
        .last()
        .1
        .to_vec()
}

/// One run of a work-precision diagram.
#[derive(Debug, Clone, PartialEq)]
pub struct Point {
    pub method: String,
    /// the step h, or the tolerance (rtol = atol) of adaptive runs
    pub h_or_tol: f64,
    pub error: f64,
    pub f_evals: u64,
    /// minimum wall time over the repeats
    pub secs: f64,
}

/// What to sweep: fixed-step methods over `hs`, adaptive pairs over `tols`.
#[derive(Debug, Clone)]
pub struct Sweep {
    pub methods: Vec<Method>,
    pub hs: Vec<f64>,
    pub tols: Vec<f64>,
    /// timing repeats per point (the minimum is kept)
    pub repeats: usize,
}

/// Error at t_end against `exact_end` vs f-evaluations and wall time, for every method and
/// step (or tolerance) of the sweep. Diverged runs are reported with an infinite error.
pub fn work_precision<S: System + ?Sized>(
    sys: &S,
    t0: f64,
    x0: &[f64],
    t_end: f64,
    exact_end: &[f64],
    sweep: &Sweep,
) -> Vec<Point> {
    let mut out = Vec::new();
    for &m in &sweep.methods {
        let params: &[f64] = if m.is_adaptive() {
            &sweep.tols
        } else {
            &sweep.hs
        };
        for &p in params {
            let run = || {
                if m.is_adaptive() {
                    let opts = Adaptive {
                        rtol: p,
                        atol: p,
                        record: false,
                        ..Adaptive::default()
                    };
                    solve_embedded(sys, m, t0, x0, t_end, opts)
                } else {
                    solve_fixed_final(sys, Scheme::Method(m), t0, x0, p, t_end, f64::INFINITY)
                }
            };
            let mut best = f64::INFINITY;
            let mut sol = None;
            for _ in 0..sweep.repeats.max(1) {
                let start = Instant::now();
                let s = run();
                best = best.min(start.elapsed().as_secs_f64());
                sol = Some(s);
            }
            let sol = sol.expect("at least one repeat");
            let error = if sol.finished() {
                max_error(sol.last().1, exact_end)
            } else {
                f64::INFINITY
            };
            out.push(Point {
                method: m.name().to_string(),
                h_or_tol: p,
                error,
                f_evals: sol.f_evals,
                secs: best,
            });
        }
    }
    out
}

#[allow(clippy::too_many_arguments)]
/// [`work_precision`] for RK4 on the fixed-size fast path ([`solve_fixed_n`]); the points are
/// labelled `label`.
pub fn work_precision_fixed<const N: usize, S: FixedSystem<N>>(
    sys: &S,
    label: &str,
    t0: f64,
    x0: [f64; N],
    t_end: f64,
    exact_end: &[f64],
    hs: &[f64],
    repeats: usize,
) -> Vec<Point> {
    hs.iter()
        .map(|&h| {
            let mut best = f64::INFINITY;
            let mut sol = None;
            for _ in 0..repeats.max(1) {
                let start = Instant::now();
                let s = solve_fixed_n(sys, t0, std::hint::black_box(x0), h, t_end, f64::INFINITY);
                best = best.min(start.elapsed().as_secs_f64());
                sol = Some(s);
            }
            let sol = sol.expect("at least one repeat");
            Point {
                method: label.to_string(),
                h_or_tol: h,
                error: if sol.finished() {
                    max_error(&sol.x, exact_end)
                } else {
                    f64::INFINITY
                },
                f_evals: sol.f_evals,
                secs: best,
            }
        })
        .collect()
}

/// The cost (e.g. seconds) at a given error along a work-precision curve of (error, cost)
/// points, interpolated linearly in log-log; None outside the curve's range of errors.
pub fn cost_at_error(points: &[(f64, f64)], error: f64) -> Option<f64> {
    let mut pts: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p.0 > 0.0 && p.0.is_finite() && p.1 > 0.0)
        .map(|p| (p.0.ln(), p.1.ln()))
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let e = error.ln();
    pts.windows(2)
        .find(|w| w[0].0 <= e && e <= w[1].0)
        .map(|w| {
            let s = if w[1].0 > w[0].0 {
                (e - w[0].0) / (w[1].0 - w[0].0)
            } else {
                0.0
            };
            (w[0].1 + s * (w[1].1 - w[0].1)).exp()
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slope_of_a_power_law() {
        let pts: Vec<(f64, f64)> = [0.1, 0.05, 0.025]
            .iter()
            .map(|&h: &f64| (h, 3.0 * h.powi(4)))
            .collect();
        assert!((loglog_slope(&pts) - 4.0).abs() < 1e-12);
    }

    #[test]
    fn cost_at_error_interpolates_in_log_log() {
        // cost = err^-1/4 exactly along the curve, unsorted on purpose
        let pts: Vec<(f64, f64)> = [1e-8, 1e-2, 1e-4]
            .iter()
            .map(|&e: &f64| (e, e.powf(-0.25)))
            .collect();
        let c = cost_at_error(&pts, 1e-6).unwrap();
        assert!((c - 1e-6f64.powf(-0.25)).abs() < 1e-9 * c);
        assert_eq!(cost_at_error(&pts, 1e-9), None);
        assert_eq!(cost_at_error(&pts, 1.0), None);
    }
}
