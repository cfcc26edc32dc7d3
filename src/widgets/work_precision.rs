//! Widget 7: Speed vs error: the work–precision diagram (error vs f-evaluations, and vs wall time),
//! computed on a background thread so the UI never waits. Fixed-step methods (Euler, midpoint,
//! RK4, a fifth-order RK5, deck tableaux) are swept over the step h; the adaptive embedded pairs
//! (Tsit5, DOP853, Vern9, …) over their tolerance, through the one adaptive loop
//! (`ode::solve_embedded`). Answers "why not RK5, RK6?": each extra order costs more
//! f-evaluations per step and pays off once the error asked for is small enough — DOP853 and
//! Vern9 overtake RK4 at tight errors, while at loose ones RK4 or a fifth-order pair is cheaper.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, channel};
use std::time::Instant;

use egui_plot::{Line, MarkerShape, Points};

use std::path::Path as FsPath;
use std::sync::OnceLock;

use super::convergence::{log_axes_plot, pow10_label, truth};
use super::live_ode::LiveOde;
use super::methods::{MethodSet, steps_for};
use super::style::{self, fmt_num};
use super::{Param, SlideWidget};
use crate::deck::widgets::WorkPrecisionSpec;
use crate::ode::problem::Problem;
use crate::ode::study::max_error;
use crate::ode::{Adaptive, Method, Scheme, Solution, Tableau, solve_embedded, solve_fixed_final};

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

type Key = (WorkPrecisionSpec, u64, Vec<bool>);

/// One method of the study, owned so it can run on the background thread.
#[derive(Clone)]
enum Job {
    Method(crate::deck::widgets::ResolvedMethod),
    Rk5,
}

impl Job {
    fn sweep(&self) -> Sweep<'_> {
        match self {
            Job::Method(m) => match m.adaptive() {
                Some(pair) => Sweep::Tolerances(pair),
                None => Sweep::Steps(m.scheme()),
            },
            Job::Rk5 => Sweep::Steps(Scheme::Tableau(dopri5_fixed())),
        }
    }
}

/// A curve still to compute: everything but its samples.
type Pending = (Curve, Job);

pub struct WorkPrecision {
    pub spec: WorkPrecisionSpec,
    initial: WorkPrecisionSpec,
    ode: LiveOde,
    methods: MethodSet,
    computed_for: Option<Key>,
    results: Vec<Curve>,
    pending: Option<Receiver<Curve>>,
}

impl WorkPrecision {
    pub fn new(spec: WorkPrecisionSpec, deck_path: Option<&FsPath>) -> Self {
        Self {
            ode: LiveOde::new(&spec.ode, deck_path),
            methods: MethodSet::new(&spec.methods, deck_path),
            initial: spec.clone(),
            spec,
            computed_for: None,
            results: Vec::new(),
            pending: None,
        }
    }

    fn jobs(&self) -> Vec<Pending> {
        let curve = |key: &str, name: &str, color, adaptive| Curve {
            key: key.to_owned(),
            name: name.to_owned(),
            color,
            adaptive,
            samples: Vec::new(),
        };
        let mut v: Vec<Pending> = self
            .methods
            .shown()
            .map(|m| {
                let c = curve(
                    &m.method.key,
                    &m.method.name,
                    m.color,
                    m.method.adaptive().is_some(),
                );
                (c, Job::Method(m.method.clone()))
            })
            .collect();
        if self.spec.rk5 {
            v.push((curve("rk5", "RK5", style::DOPRI, false), Job::Rk5));
        }
        v
    }

    fn key(&mut self) -> Key {
        (
            self.spec.clone(),
            self.ode.revision(),
            self.methods.switches(),
        )
    }

    /// Every curve at once, on the calling thread (tests and `export --data`).
    pub fn compute(&mut self) -> Vec<Curve> {
        let Some(problem) = self.ode.problem().cloned() else {
            return Vec::new();
        };
        let exact = truth(&problem, self.spec.t_end);
        self.jobs()
            .into_iter()
            .map(|(mut c, job)| {
                c.samples = study(&self.spec, &problem, &exact, job.sweep());
                c
            })
            .collect()
    }

    /// Starts the study for the current spec (in the background unless DETERMINISTIC).
    fn start(&mut self, ctx: &egui::Context) {
        self.computed_for = Some(self.key());
        self.results.clear();
        self.pending = None;
        if DETERMINISTIC.load(Ordering::Relaxed) {
            self.results = self.compute();
            return;
        }
        let Some(problem) = self.ode.problem().cloned() else {
            return;
        };
        let jobs = self.jobs();
        let spec = self.spec.clone();
        let (tx, rx) = channel();
        let ctx = ctx.clone();
        // Dropping the receiver (spec changed again) makes the next send fail: the thread stops.
        // Each run is bounded (2^22 fixed steps, MAX_ADAPTIVE_STEPS adaptive ones).
        std::thread::spawn(move || {
            let exact = truth(&problem, spec.t_end);
            for (mut curve, job) in jobs {
                curve.samples = study(&spec, &problem, &exact, job.sweep());
                if tx.send(curve).is_err() {
                    return;
                }
                ctx.request_repaint();
            }
        });
        self.pending = Some(rx);
    }

    /// True while the background study is still running.
    pub fn busy(&self) -> bool {
        self.pending.is_some()
    }

    fn poll(&mut self) {
        if let Some(rx) = &self.pending {
            loop {
                match rx.try_recv() {
                    Ok(r) => self.results.push(r),
                    Err(std::sync::mpsc::TryRecvError::Empty) => break,
                    Err(std::sync::mpsc::TryRecvError::Disconnected) => {
                        self.pending = None;
                        break;
                    }
                }
            }
        }
    }

    /// What the two sweeps ran, for the caption: "● fixed step h = 1 … 2⁻⁹;", "■ adaptive,
    /// tolerance 10⁻² … 10⁻¹³;" (only those the curves use).
    fn sweeps_caption(&self) -> Vec<String> {
        let levels = self.spec.levels.clamp(2, 16);
        let mut parts = Vec::new();
        if self.results.iter().any(|c| !c.adaptive) {
            parts.push(format!(
                "● fixed step h = 1 … 2{};",
                pow10_label(-(levels as f64 - 1.0)).trim_start_matches("10")
            ));
        }
        if self.results.iter().any(|c| c.adaptive) {
            parts.push(format!(
                "■ adaptive, tolerance {} … {};",
                pow10_label(TOL_MAX.log10()),
                pow10_label(TOL_MIN.log10())
            ));
        }
        parts
    }
}

impl SlideWidget for WorkPrecision {
    fn ui(&mut self, ui: &mut egui::Ui) {
        style::projector_text(ui);
        ui.horizontal_wrapped(|ui| {
            ui.add(egui::Slider::new(&mut self.spec.levels, 3..=14).text("step sizes"));
            self.methods.toggles_ui(ui);
            ui.checkbox(
                &mut self.spec.rk5,
                egui::RichText::new("RK5")
                    .color(style::text_color(ui, style::DOPRI))
                    .strong(),
            );
            if self.busy() {
                ui.spinner();
                ui.label("computing in the background…");
            }
        });
        style::problems_ui(ui, self.ode.load_error(), &self.methods.errors);
        let key = self.key();
        if self.computed_for.as_ref() != Some(&key) {
            self.start(ui.ctx());
        }
        self.poll();
        let (name, t0) = self
            .ode
            .problem()
            .map(|p| (p.name.clone(), p.t0))
            .unwrap_or_default();
        ui.horizontal_wrapped(|ui| {
            let mut caption = vec![format!(
                "{name} over t ∈ [{}, {}];",
                fmt_num(t0).trim_end_matches(".000"),
                fmt_num(self.spec.t_end),
            )];
            caption.extend(self.sweeps_caption());
            caption.push("best error:".into());
            for part in caption {
                ui.add(egui::Label::new(part).wrap_mode(egui::TextWrapMode::Extend));
            }
            for c in &self.results {
                // whole entries move to the next row; none breaks inside
                let txt = format!("{} {}", c.name, fmt_num(c.best_error()));
                let color = style::text_color(ui, c.color);
                ui.add(
                    egui::Label::new(egui::RichText::new(txt).strong().color(color))
                        .wrap_mode(egui::TextWrapMode::Extend),
                );
            }
        });
        let half = (ui.available_width() - ui.spacing().item_spacing.x) / 2.0;
        let height = ui.available_height();
        let results = &self.results;
        ui.horizontal_top(|ui| {
            for (id, xlab, by_time) in [
                ("wp-evals", "f evaluations", false),
                ("wp-time", "seconds", true),
            ] {
                ui.allocate_ui(egui::vec2(half, height), |ui| {
                    log_axes_plot(id, xlab, "error")
                        .width(half)
                        .height(height)
                        .show(ui, |p| {
                            for c in results {
                                let v: Vec<[f64; 2]> = c
                                    .samples
                                    .iter()
                                    .filter(|s| s.error.is_finite() && s.error > 0.0)
                                    .map(|s| {
                                        [
                                            if by_time { s.secs } else { s.f_evals as f64 }.log10(),
                                            s.error.log10().max(-16.0),
                                        ]
                                    })
                                    .collect();
                                // squares mark a tolerance sweep, dots a step-size sweep
                                let (shape, radius) = if c.adaptive {
                                    (MarkerShape::Square, 5.0)
                                } else {
                                    (MarkerShape::Circle, 4.5)
                                };
                                p.line(
                                    Line::new(c.name.clone(), v.clone())
                                        .color(c.color)
                                        .width(style::PATH_WIDTH),
                                );
                                p.points(
                                    Points::new(c.name.clone(), v)
                                        .color(c.color)
                                        .shape(shape)
                                        .filled(true)
                                        .radius(radius),
                                );
                            }
                        });
                });
            }
        });
    }

    fn params(&mut self) -> Vec<Param<'_>> {
        let mut v = vec![
            Param::usize("levels", "step sizes", &mut self.spec.levels, 3, 14),
            Param::bool("rk5", "RK5", &mut self.spec.rk5),
        ];
        v.extend(self.methods.params());
        v.extend(self.ode.params());
        v
    }

    ode_plumbing!(WorkPrecision);

    /// `series,sweep,h_or_tol,f_evals,error`: every run, series by method key (`rk5` for the
    /// fixed-step fifth-order weights), `sweep` `h` or `tol`. Wall time is left out: it is the
    /// machine's, not the method's (and a modelled one in headless exports).
    fn csv(&mut self) -> Option<String> {
        self.ode.problem()?;
        let mut out = String::from("series,sweep,h_or_tol,f_evals,error\n");
        for c in self.compute() {
            let sweep = if c.adaptive { "tol" } else { "h" };
            for s in &c.samples {
                out.push_str(&format!(
                    "{},{sweep},{:?},{},{:?}\n",
                    c.key, s.h_or_tol, s.f_evals, s.error
                ));
            }
        }
        Some(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn deck() -> &'static FsPath {
        FsPath::new(concat!(env!("CARGO_MANIFEST_DIR"), "/slides/lecture.ron"))
    }

    fn spec(levels: usize, methods: &str) -> WorkPrecisionSpec {
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

    #[test]
    fn background_study_delivers_without_blocking_the_frame() {
        let ctx = egui::Context::default();
        let mut w = WorkPrecision::new(spec(12, ", methods: [Euler, Rk4, Dop853]"), Some(deck()));
        w.start(&ctx);
        assert!(w.busy());
        while w.busy() {
            w.poll();
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
        let keys: Vec<_> = w.results.iter().map(|c| c.key.as_str()).collect();
        assert_eq!(keys, ["euler", "rk4", "dop853", "rk5"]);
        assert!(w.results[2].adaptive && !w.results[1].adaptive);
    }
}
