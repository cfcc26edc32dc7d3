//! Convergence and work-precision studies: pure functions over a system, so a slide can run
//! them on a background thread, `lectern bench` can print them and the benchmarks can time
//! them, all by one timing policy ([`Timing`]) over one list of tolerances ([`tolerances`]).

use web_time::Instant;

use super::adaptive::{Adaptive, solve_embedded};
use super::fixed::{FixedSystem, solve_fixed_n};
use super::solve::{Outcome, Scheme, Solution, solve_fixed_final};
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

/// A very accurate final state for problems without an exact solution: Verner 9(8) at rtol
/// 1e-14, or, where a DOP853 probe's stiffness test fires (Vern9 would need millions of steps),
/// RADAU5 at rtol 1e-13.
pub fn reference<S: System + ?Sized>(sys: &S, t0: f64, x0: &[f64], t_end: f64) -> Vec<f64> {
    let probe = Adaptive {
        rtol: 1e-6,
        atol: 1e-9,
        record: false,
        stop_if_stiff: true,
        ..Adaptive::default()
    };
    let stiff = matches!(
        solve_embedded(sys, Method::Dop853, t0, x0, t_end, probe).outcome,
        Outcome::Stiff { .. }
    );
    let (method, rtol) = if stiff {
        (Method::Radau5, 1e-13)
    } else {
        (Method::Vern9, 1e-14)
    };
    let opts = Adaptive {
        rtol,
        atol: rtol * 1e-2,
        record: false,
        ..Adaptive::default()
    };
    solve_embedded(sys, method, t0, x0, t_end, opts)
        .last()
        .1
        .to_vec()
}

/// The one timing policy of every work-precision study (the slide, `lectern bench`, the
/// benchmarks): the fastest of repeated runs, at least `min_repeats`, repeated while the
/// whole took less than `budget_secs`, at most `max_repeats`. The fastest, not the mean: on a
/// shared machine a preempted repeat says nothing about the method (a mean made the slide's
/// seconds plot zig-zag live).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Timing {
    pub min_repeats: usize,
    pub budget_secs: f64,
    pub max_repeats: usize,
}

impl Timing {
    /// The slide: it runs again whenever a slider moves, beside the software renderer.
    pub const SLIDE: Timing = Timing {
        min_repeats: 3,
        budget_secs: 2e-3,
        max_repeats: 50,
    };
    /// `lectern bench` and the benchmarks in `benches/`.
    pub const BENCH: Timing = Timing {
        min_repeats: 3,
        budget_secs: 0.03,
        max_repeats: 200,
    };

    /// Runs `run` by this policy: its last result and the fastest repeat's seconds.
    pub fn fastest<R>(&self, mut run: impl FnMut() -> R) -> (R, f64) {
        let start = Instant::now();
        let mut reps = 0;
        let mut fastest = f64::INFINITY;
        loop {
            let t = Instant::now();
            let r = std::hint::black_box(run());
            fastest = fastest.min(t.elapsed().as_secs_f64());
            reps += 1;
            let spent = start.elapsed().as_secs_f64();
            if (reps >= self.min_repeats && spent > self.budget_secs) || reps >= self.max_repeats {
                return (r, fastest);
            }
        }
    }
}

/// Where a sample's seconds come from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Clock {
    /// measured, by [`Timing`]
    Measured(Timing),
    /// modelled: this many seconds per f-evaluation, one run each (reproducible pictures for
    /// snapshot tests and headless exports)
    PerEval(f64),
}

impl Clock {
    fn time<R>(&self, run: impl FnMut() -> R, f_evals: impl Fn(&R) -> u64) -> (R, f64) {
        match self {
            Clock::Measured(timing) => timing.fastest(run),
            Clock::PerEval(secs) => {
                let mut run = run;
                let r = run();
                let t = f_evals(&r) as f64 * secs;
                (r, t)
            }
        }
    }
}

/// The loosest tolerance of the adaptive sweeps; run k uses rtol = TOL_MAX / 10^k.
pub const TOL_MAX: f64 = 1e-2;
/// The tightest tolerance asked of a method: near round-off, and above the loop's floor
/// (rtol > 10 machine epsilons).
pub const TOL_MIN: f64 = 1e-13;

/// The tolerances of every adaptive sweep (slide, `lectern bench`, benchmarks), one per decade
/// from [`TOL_MAX`] to [`TOL_MIN`].
pub fn tolerances() -> Vec<f64> {
    let decades = (TOL_MAX / TOL_MIN).log10().round() as i32;
    (0..=decades).map(|k| TOL_MAX / 10f64.powi(k)).collect()
}

/// One run of a work-precision diagram.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// the step h, or the relative tolerance of an adaptive run
    pub h_or_tol: f64,
    pub f_evals: u64,
    pub secs: f64,
    /// error at t_end; ∞ for a run that did not get there
    pub error: f64,
    /// where an explicit pair's stiffness test stopped the run
    pub stiff_at: Option<f64>,
}

/// What one method's sweep runs.
#[derive(Debug, Clone)]
pub enum Sweep<'a> {
    /// fixed steps, each h from t0 to t_end; a state beyond 1e12 ends the run (diverged)
    Steps { scheme: Scheme<'a>, hs: Vec<f64> },
    /// an adaptive method at each rtol, atol = `atol_over_rtol`·rtol, at most `max_steps`
    /// steps; an explicit pair stops where its stiffness test fires (a stiff problem would
    /// make it crawl for millions of steps)
    Tolerances {
        method: Method,
        tols: Vec<f64>,
        atol_over_rtol: f64,
        max_steps: usize,
    },
}

impl Sweep<'_> {
    /// An adaptive sweep over [`tolerances`] with rtol = atol.
    pub fn tolerances(method: Method, max_steps: usize) -> Sweep<'static> {
        Sweep::Tolerances {
            method,
            tols: tolerances(),
            atol_over_rtol: 1.0,
            max_steps,
        }
    }
}

/// Runs one method's sweep from (t0, x0) to t_end: error by [`max_error`] against
/// `exact_end`, the true state at t_end, f-evaluations, and seconds by `clock`.
pub fn work_precision<S: System + ?Sized>(
    sys: &S,
    t0: f64,
    x0: &[f64],
    t_end: f64,
    exact_end: &[f64],
    sweep: &Sweep<'_>,
    clock: Clock,
) -> Vec<Sample> {
    let sample = |h_or_tol: f64, run: &dyn Fn() -> Solution| {
        let (sol, secs) = clock.time(run, |s: &Solution| s.f_evals);
        let error = if sol.finished() {
            max_error(sol.last().1, exact_end)
        } else {
            f64::INFINITY
        };
        let stiff_at = match sol.outcome {
            Outcome::Stiff { t } => Some(t),
            _ => None,
        };
        Sample {
            h_or_tol,
            f_evals: sol.f_evals,
            secs,
            error,
            stiff_at,
        }
    };
    match sweep {
        Sweep::Steps { scheme, hs } => hs
            .iter()
            .map(|&h| {
                sample(h, &|| {
                    solve_fixed_final(sys, *scheme, t0, x0, h, t_end, 1e12)
                })
            })
            .collect(),
        Sweep::Tolerances {
            method,
            tols,
            atol_over_rtol,
            max_steps,
        } => tols
            .iter()
            .map(|&tol| {
                let opts = Adaptive {
                    rtol: tol,
                    atol: tol * atol_over_rtol,
                    record: false,
                    max_steps: *max_steps,
                    stop_if_stiff: true,
                    ..Adaptive::default()
                };
                sample(tol, &|| solve_embedded(sys, *method, t0, x0, t_end, opts))
            })
            .collect(),
    }
}

/// [`work_precision`] for RK4 with fixed steps `hs` on the fixed-size fast path
/// ([`solve_fixed_n`]).
pub fn work_precision_fixed_n<const N: usize, S: FixedSystem<N>>(
    sys: &S,
    t0: f64,
    x0: [f64; N],
    t_end: f64,
    exact_end: &[f64],
    hs: &[f64],
    clock: Clock,
) -> Vec<Sample> {
    hs.iter()
        .map(|&h| {
            let (sol, secs) = clock.time(
                || solve_fixed_n(sys, t0, std::hint::black_box(x0), h, t_end, 1e12),
                |s| s.f_evals,
            );
            Sample {
                h_or_tol: h,
                f_evals: sol.f_evals,
                secs,
                error: if sol.finished() {
                    max_error(&sol.x, exact_end)
                } else {
                    f64::INFINITY
                },
                stiff_at: None,
            }
        })
        .collect()
}

/// The least error a sweep reached (∞ if none finished).
pub fn best_error(samples: &[Sample]) -> f64 {
    samples
        .iter()
        .map(|s| s.error)
        .fold(f64::INFINITY, f64::min)
}

/// The seconds a sweep needs to reach an error of at most `target`: interpolated in log–log
/// between the two runs that bracket it, the cheapest run if even that one gets there, `None`
/// if no run got there.
pub fn secs_to_reach(samples: &[Sample], target: f64) -> Option<f64> {
    let mut pts: Vec<(f64, f64)> = samples
        .iter()
        .filter(|s| s.error.is_finite() && s.error > 0.0 && s.secs > 0.0)
        .map(|s| (s.error.log10(), s.secs.log10()))
        .collect();
    pts.sort_by(|a, b| b.0.total_cmp(&a.0));
    let t = target.log10();
    if pts.first().is_some_and(|p| p.0 <= t) {
        return Some(10f64.powf(pts[0].1));
    }
    pts.windows(2).find(|w| w[0].0 > t && w[1].0 <= t).map(|w| {
        let f = (t - w[0].0) / (w[1].0 - w[0].0);
        10f64.powf(w[0].1 + f * (w[1].1 - w[0].1))
    })
}

/// For each target error 10⁻², 10^-2.5, … 10⁻¹² (as x = −log10 of it): how many times longer
/// each sweep takes than the fastest sweep that reaches it (log10 of the ratio, 0 = the
/// fastest). The sweep at 0 is the method to pick for that accuracy.
pub fn relative_cost(sweeps: &[&[Sample]]) -> Vec<Vec<[f64; 2]>> {
    let targets: Vec<f64> = (4..=24).map(|k| 10f64.powf(-(k as f64) / 2.0)).collect();
    let costs: Vec<Vec<Option<f64>>> = sweeps
        .iter()
        .map(|c| targets.iter().map(|&t| secs_to_reach(c, t)).collect())
        .collect();
    let best: Vec<Option<f64>> = (0..targets.len())
        .map(|k| costs.iter().filter_map(|c| c[k]).reduce(f64::min))
        .collect();
    costs
        .iter()
        .map(|c| {
            targets
                .iter()
                .enumerate()
                .filter_map(|(k, t)| Some([-t.log10(), (c[k]? / best[k]?).log10()]))
                .collect()
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

    fn sweep(pts: &[(f64, f64)]) -> Vec<Sample> {
        pts.iter()
            .map(|&(secs, error)| Sample {
                h_or_tol: 1.0,
                f_evals: 1,
                secs,
                error,
                stiff_at: None,
            })
            .collect()
    }

    #[test]
    fn relative_cost_puts_the_cheapest_method_at_zero_and_its_crossing_where_it_is() {
        // a cheap low order (error 1e-2 for 1 s, 1e-4 for 100 s) and a dear high order
        // (1e-2 for 10 s, 1e-10 for 100 s): loose errors favour the first, tight the second
        let low = sweep(&[(1.0, 1e-2), (100.0, 1e-4)]);
        let high = sweep(&[(10.0, 1e-2), (100.0, 1e-10)]);
        assert_eq!(secs_to_reach(&low, 1e-3), Some(10.0));
        assert_eq!(secs_to_reach(&low, 1e-6), None);
        let r = relative_cost(&[&low, &high]);
        // at 1e-2 (x = 2) the low order is the fastest, the high one 10× slower
        assert_eq!(r[0][0], [2.0, 0.0]);
        assert!((r[1][0][1] - 1.0).abs() < 1e-12);
        // at 1e-4 (x = 4) both take 100 s … beyond, only the high order is there, at 0
        let last = r[1].last().unwrap();
        assert_eq!(*last, [10.0, 0.0]);
        assert!(r[0].iter().all(|p| p[0] <= 4.0 + 1e-9));
    }

    #[test]
    fn the_timing_policy_repeats_within_its_bounds_and_keeps_the_fastest() {
        let mut n = 0;
        let policy = Timing {
            min_repeats: 3,
            budget_secs: 0.0,
            max_repeats: 10,
        };
        let (last, secs) = policy.fastest(|| {
            n += 1;
            n
        });
        // a zero budget: exactly the minimum number of repeats, the last result returned
        assert_eq!((n, last), (3, 3));
        assert!(secs >= 0.0 && secs.is_finite());
        let mut m = 0;
        let (_, _) = Timing {
            budget_secs: 1e9,
            ..policy
        }
        .fastest(|| m += 1);
        assert_eq!(m, 10);
    }
}
