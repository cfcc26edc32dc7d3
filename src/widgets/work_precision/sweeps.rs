//! What the work-precision slide sweeps; the study itself (running, timing, comparing the
//! sweeps) is `ode::study`'s, shared with `lectern bench` and the benchmarks. Fixed-step
//! methods run at h = H_MAX / 2^k for the spec's `levels`; adaptive methods (the explicit
//! pairs, rodas5p, radau5) over `ode::study::tolerances()`. No egui beyond the colour a curve
//! is drawn in; runs on any thread.

use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, Ordering};

use crate::deck::widgets::WorkPrecisionSpec;
use crate::ode::problem::Problem;
use crate::ode::study::{self, Clock, Sample, Sweep, Timing};
use crate::ode::{Scheme, Tableau};
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
/// Steps (accepted + rejected) one adaptive run may take: a stiff equation typed live makes a
/// pair crawl (when its stiffness test does not stop it), and the background study must end
/// (the run reports `Failed`, drawn as nothing).
pub const MAX_ADAPTIVE_STEPS: usize = 1 << 18;

/// The fixed steps for the spec's `levels`, each landing exactly on t_end.
pub fn step_sizes(spec: &WorkPrecisionSpec, t0: f64) -> Vec<f64> {
    (0..spec.levels.clamp(2, 16))
        .map(|k| {
            let n = steps_for(t0, spec.t_end, H_MAX / 2f64.powi(k as i32), 1 << 22).max(1);
            (spec.t_end - t0) / n as f64
        })
        .collect()
}

/// A fixed-step method's sweep.
pub fn steps<'a>(spec: &WorkPrecisionSpec, sys: &Problem, scheme: Scheme<'a>) -> Sweep<'a> {
    Sweep::Steps {
        scheme,
        hs: step_sizes(spec, sys.t0),
    }
}

/// The slide's clock: measured live, modelled (50 ns per f-evaluation) when DETERMINISTIC.
pub fn clock() -> Clock {
    if DETERMINISTIC.load(Ordering::Relaxed) {
        Clock::PerEval(50e-9)
    } else {
        Clock::Measured(Timing::SLIDE)
    }
}

/// One method's sweep over the problem from its t0 to the spec's t_end, error against
/// `exact`, the true state at t_end.
pub fn study(
    spec: &WorkPrecisionSpec,
    sys: &Problem,
    exact: &[f64],
    sweep: &Sweep<'_>,
) -> Vec<Sample> {
    study::work_precision(sys, sys.t0, &sys.initial, spec.t_end, exact, sweep, clock())
}

/// One method's curve.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    /// `rk4`, `dop853`, a tableau's stem, `rk5`: CSV series names
    pub key: String,
    pub name: String,
    pub color: egui::Color32,
    /// swept over the tolerance (an adaptive method) rather than h
    pub adaptive: bool,
    pub samples: Vec<Sample>,
}

impl Curve {
    pub fn best_error(&self) -> f64 {
        study::best_error(&self.samples)
    }

    /// Where the stiffness test stopped this (explicit, adaptive) method, if it stopped every
    /// run: the earliest such time.
    pub fn stiff_at(&self) -> Option<f64> {
        let all = !self.samples.is_empty() && self.samples.iter().all(|s| s.stiff_at.is_some());
        all.then(|| {
            self.samples
                .iter()
                .filter_map(|s| s.stiff_at)
                .fold(f64::INFINITY, f64::min)
        })
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::ode::Method;
    use crate::ode::study::{TOL_MAX, TOL_MIN, tolerances};
    use std::path::Path as FsPath;

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
            &steps(&spec, &p, Scheme::Tableau(dopri5_fixed())),
        );
        let order = (rk5[2].error / rk5[3].error).log2();
        assert!((order - 5.0).abs() < 0.3, "{order}");
        let rk4 = study(
            &spec,
            &p,
            &exact,
            &steps(&spec, &p, Scheme::Method(Method::Rk4)),
        );
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
        let sweep = Sweep::tolerances(Method::Dop853, MAX_ADAPTIVE_STEPS);
        let s = study(&spec, &p, &exact, &sweep);
        assert_eq!(s.len(), 12);
        for w in s.windows(2) {
            // tighter tolerance: more work, and (away from round-off) a smaller error
            assert!(w[1].f_evals > w[0].f_evals, "{s:?}");
        }
        // the achieved error follows the tolerance (within a few decades over t = 10)
        for x in &s {
            assert!(x.error < 1e3 * x.h_or_tol, "{x:?}");
            assert_eq!(x.stiff_at, None);
        }
        assert!(s[11].error < 1e-11, "{:?}", s[11]);
    }
}
