//! The pure part of the work-precision widget: what one method's sweep runs (fixed steps over
//! h, an adaptive pair over its tolerance through `ode::solve_embedded`) and how a run is timed.
//! No egui beyond the colour a curve is drawn in; runs on any thread.

use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use crate::deck::widgets::WorkPrecisionSpec;
use crate::ode::problem::Problem;
use crate::ode::study::max_error;
use crate::ode::{Adaptive, Method, Scheme, Solution, Tableau, solve_embedded, solve_fixed_final};
use crate::widgets::methods::steps_for;

/// Snapshot tests set this: timings then come from a fixed cost per f-evaluation and the study
/// runs on the calling thread, so pictures are reproducible. Live, time is measured.
pub static DETERMINISTIC: AtomicBool = AtomicBool::new(false);

/// Dormand–Prince 5(4)'s fifth-order weights as a fixed-step method (6 stages), from the
/// numerics core.
pub fn dopri5_fixed() -> &'static Tableau {
    static DP: OnceLock<Tableau> = OnceLock::new();
    DP.get_or_init(|| {
        let mut t = Tableau::dopri5();
        t.name = "RK5 (Dormand–Prince)".into();
        t
    })
}

/// The largest step of the fixed-step sweep; run k uses h = H_MAX / 2^k.
pub const H_MAX: f64 = 1.0;
/// The loosest tolerance of the adaptive sweep; run k uses rtol = atol = TOL_MAX / 10^k.
pub const TOL_MAX: f64 = 1e-2;
/// The tightest tolerance asked of a pair: near round-off, and above the loop's floor
/// (rtol > 10 machine epsilons).
pub const TOL_MIN: f64 = 1e-13;
/// Steps (accepted + rejected) one adaptive run may take: a stiff equation typed live makes a
/// pair crawl, and the background study must end (the run reports `Failed`, drawn as nothing).
pub const MAX_ADAPTIVE_STEPS: usize = 1 << 18;

/// How one method is swept.
#[derive(Debug, Clone, Copy)]
pub enum Sweep<'a> {
    /// fixed steps h = H_MAX / 2^k
    Steps(Scheme<'a>),
    /// an adaptive pair at each of [`tolerances`]
    Tolerances(Method),
}

/// The tolerances of the adaptive runs, one per decade from [`TOL_MAX`] to [`TOL_MIN`]. The
/// sweep does not depend on `levels` (the step sizes of the fixed-step methods): a pair
/// always shows its whole curve, from the loose end where low order is cheaper to the tight
/// end where it overtakes RK4, for a few hundred f-evaluations each.
pub fn tolerances() -> Vec<f64> {
    let decades = (TOL_MAX / TOL_MIN).log10().round() as i32;
    (0..=decades).map(|k| TOL_MAX / 10f64.powi(k)).collect()
}

/// One run: the step or tolerance, f-evaluations, seconds, global error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// h (fixed step) or rtol = atol (adaptive pair)
    pub h_or_tol: f64,
    pub f_evals: usize,
    pub secs: f64,
    pub error: f64,
}

/// Runs `run` (at least three times, and repeated while short so the clock resolves it) and
/// turns its solution into a sample; in DETERMINISTIC mode time is 50 ns per f-evaluation.
/// The time is the fastest repeat: the study shares two cores with the slide's software
/// rendering, and a preempted repeat says nothing about the method (a mean made the seconds
/// plot zig-zag live).
fn timed(h_or_tol: f64, exact: &[f64], run: impl Fn() -> Solution) -> Sample {
    let start = Instant::now();
    let mut reps = 0;
    let mut fastest = f64::INFINITY;
    let sol = loop {
        let t = Instant::now();
        let sol = run();
        fastest = fastest.min(t.elapsed().as_secs_f64());
        reps += 1;
        if (reps >= 3 && start.elapsed().as_secs_f64() > 2e-3) || reps >= 50 {
            break sol;
        }
    };
    let secs = if DETERMINISTIC.load(Ordering::Relaxed) {
        sol.f_evals as f64 * 50e-9
    } else {
        fastest
    };
    let error = if sol.finished() {
        max_error(sol.last().1, exact)
    } else {
        f64::INFINITY
    };
    Sample {
        h_or_tol,
        f_evals: sol.f_evals as usize,
        secs,
        error,
    }
}

/// The study for one method (pure; runs on any thread) from the problem's t0 to t_end, error
/// by `ode::study::max_error` against `exact`, the true state at t_end: a fixed-step method
/// by `ode::solve_fixed_final` at each h, an adaptive pair by `ode::solve_embedded` at each
/// tolerance.
pub fn study(
    spec: &WorkPrecisionSpec,
    sys: &Problem,
    exact: &[f64],
    sweep: Sweep<'_>,
) -> Vec<Sample> {
    let (t0, x0, t_end) = (sys.t0, sys.initial.as_slice(), spec.t_end);
    match sweep {
        Sweep::Steps(scheme) => (0..spec.levels.clamp(2, 16))
            .map(|k| {
                let n = steps_for(t0, t_end, H_MAX / 2f64.powi(k as i32), 1 << 22).max(1);
                let h = (t_end - t0) / n as f64;
                timed(h, exact, || {
                    solve_fixed_final(sys, scheme, t0, x0, h, t_end, 1e12)
                })
            })
            .collect(),
        Sweep::Tolerances(method) => tolerances()
            .into_iter()
            .map(|tol| {
                let opts = Adaptive {
                    rtol: tol,
                    atol: tol,
                    record: false,
                    max_steps: MAX_ADAPTIVE_STEPS,
                    ..Adaptive::default()
                };
                timed(tol, exact, || {
                    solve_embedded(sys, method, t0, x0, t_end, opts)
                })
            })
            .collect(),
    }
}

/// One method's curve.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    /// `rk4`, `dop853`, a tableau's stem, `rk5`: CSV series names
    pub key: String,
    pub name: String,
    pub color: egui::Color32,
    /// swept over the tolerance (an adaptive pair) rather than h
    pub adaptive: bool,
    pub samples: Vec<Sample>,
}

impl Curve {
    pub fn best_error(&self) -> f64 {
        self.samples
            .iter()
            .map(|s| s.error)
            .fold(f64::INFINITY, f64::min)
    }
}

/// The seconds `c` needs to reach an error of at most `target`: interpolated in log–log
/// between the two runs that bracket it, `None` if no run got there.
pub fn secs_to_reach(c: &Curve, target: f64) -> Option<f64> {
    let mut pts: Vec<(f64, f64)> = c
        .samples
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
/// each curve takes than the fastest curve that reaches it (log10 of the ratio, 0 = the
/// fastest). The curve at 0 is the method to pick for that accuracy: the slide's answer to
/// "why not RK5, RK6?" is where that changes.
pub fn relative_cost(curves: &[Curve]) -> Vec<Vec<[f64; 2]>> {
    let targets: Vec<f64> = (4..=24).map(|k| 10f64.powf(-(k as f64) / 2.0)).collect();
    let costs: Vec<Vec<Option<f64>>> = curves
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

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use std::path::Path as FsPath;

    #[test]
    fn relative_cost_puts_the_cheapest_method_at_zero_and_its_crossing_where_it_is() {
        // a cheap low order (error 1e-2 for 1 s, 1e-4 for 100 s) and a dear high order
        // (1e-2 for 10 s, 1e-10 for 100 s): loose errors favour the first, tight the second
        let curve = |pts: &[(f64, f64)]| Curve {
            key: String::new(),
            name: String::new(),
            color: egui::Color32::WHITE,
            adaptive: false,
            samples: pts
                .iter()
                .map(|&(secs, error)| Sample {
                    h_or_tol: 1.0,
                    f_evals: 1,
                    secs,
                    error,
                })
                .collect(),
        };
        let low = curve(&[(1.0, 1e-2), (100.0, 1e-4)]);
        let high = curve(&[(10.0, 1e-2), (100.0, 1e-10)]);
        assert_eq!(secs_to_reach(&low, 1e-3), Some(10.0));
        assert_eq!(secs_to_reach(&low, 1e-6), None);
        let r = relative_cost(&[low, high]);
        // at 1e-2 (x = 2) the low order is the fastest, the high one 10× slower
        assert_eq!(r[0][0], [2.0, 0.0]);
        assert!((r[1][0][1] - 1.0).abs() < 1e-12);
        // at 1e-4 (x = 4) both take 100 s … beyond, only the high order is there, at 0
        let last = r[1].last().unwrap();
        assert_eq!(*last, [10.0, 0.0]);
        assert!(r[0].iter().all(|p| p[0] <= 4.0 + 1e-9));
    }

    pub(in crate::widgets) fn deck() -> &'static FsPath {
        FsPath::new(concat!(env!("CARGO_MANIFEST_DIR"), "/slides/lecture.ron"))
    }

    /// The circle over t ∈ [0, 10] with `levels` step sizes and `methods` (", methods: […]").
    pub(in crate::widgets) fn spec(levels: usize, methods: &str) -> WorkPrecisionSpec {
        ron::from_str(&format!(
            "(ode: File(\"problems/circle.ron\"), t_end: 10.0, levels: {levels}{methods})"
        ))
        .unwrap()
    }

    #[test]
    fn rk5_is_fifth_order_and_beats_rk4_per_evaluation_at_high_accuracy() {
        let spec = spec(6, "");
        let p = Problem::load(deck().with_file_name("problems/circle.ron")).unwrap();
        let exact = p.exact(10.0).unwrap();
        let rk5 = study(
            &spec,
            &p,
            &exact,
            Sweep::Steps(Scheme::Tableau(dopri5_fixed())),
        );
        let order = (rk5[2].error / rk5[3].error).log2();
        assert!((order - 5.0).abs() < 0.3, "{order}");
        let rk4 = study(&spec, &p, &exact, Sweep::Steps(Scheme::Method(Method::Rk4)));
        // at ~the same work, RK5's error is smaller
        assert!(rk5[3].error < rk4[3].error);
    }

    #[test]
    fn adaptive_pairs_sweep_the_tolerance_and_meet_it() {
        let tols = tolerances();
        assert_eq!((tols.len(), tols[0]), (12, TOL_MAX));
        assert!((tols[11] / TOL_MIN - 1.0).abs() < 1e-12);
        // the sweep is the same whatever `levels` (the fixed-step methods' step sizes) says
        let spec = spec(4, "");
        let p = Problem::load(deck().with_file_name("problems/circle.ron")).unwrap();
        let exact = p.exact(10.0).unwrap();
        let s = study(&spec, &p, &exact, Sweep::Tolerances(Method::Dop853));
        assert_eq!(s.len(), 12);
        for w in s.windows(2) {
            // tighter tolerance: more work, and (away from round-off) a smaller error
            assert!(w[1].f_evals > w[0].f_evals, "{s:?}");
        }
        // the achieved error follows the tolerance (within a few decades over t = 10)
        for x in &s {
            assert!(x.error < 1e3 * x.h_or_tol, "{x:?}");
        }
        assert!(s[11].error < 1e-11, "{:?}", s[11]);
    }
}
