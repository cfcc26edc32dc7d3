//! Widget 7: Speed vs error: the work–precision diagram (error vs f-evaluations, and vs wall time) of
//! Euler, midpoint, RK4 and a fifth-order method, computed on a background thread so the UI
//! never waits. Answers "why not RK5, RK6?": more stages buy less and less per evaluation, and
//! all methods meet the round-off floor.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, channel};
use std::time::Instant;

use egui_plot::{Line, Points};

use std::path::Path as FsPath;
use std::sync::OnceLock;

use super::convergence::{log_axes_plot, truth};
use super::live_ode::LiveOde;
use super::methods::{MethodSet, steps_for};
use super::style::{self, fmt_num};
use super::{Param, SlideWidget};
use crate::deck::widgets::WorkPrecisionSpec;
use crate::ode::problem::Problem;
use crate::ode::study::max_error;
use crate::ode::{Scheme, Tableau, solve_fixed_final};

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

/// One run: f-evaluations, seconds, global error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    pub f_evals: usize,
    pub secs: f64,
    pub error: f64,
}

/// The study for one method (pure; runs on any thread): `ode::solve_fixed_final` at each h,
/// error by `ode::study::max_error` against `exact`, the true state at t_end.
pub fn study(
    spec: &WorkPrecisionSpec,
    sys: &Problem,
    exact: &[f64],
    scheme: Scheme<'_>,
) -> Vec<Sample> {
    let (t0, x0) = (sys.t0, sys.initial.as_slice());
    let h_max = 1.0;
    (0..spec.levels.clamp(2, 16))
        .map(|k| {
            let n = steps_for(t0, spec.t_end, h_max / 2f64.powi(k as i32), 1 << 22).max(1);
            let h = (spec.t_end - t0) / n as f64;
            let start = Instant::now();
            let mut reps = 0;
            let sol = loop {
                let sol = solve_fixed_final(sys, scheme, t0, x0, h, spec.t_end, 1e12);
                reps += 1;
                // repeat short runs so the clock resolves them
                if start.elapsed().as_secs_f64() > 2e-3 || reps >= 50 {
                    break sol;
                }
            };
            let secs = if DETERMINISTIC.load(Ordering::Relaxed) {
                sol.f_evals as f64 * 50e-9
            } else {
                start.elapsed().as_secs_f64() / reps as f64
            };
            let error = if sol.finished() {
                max_error(sol.last().1, exact)
            } else {
                f64::INFINITY
            };
            Sample {
                f_evals: sol.f_evals as usize,
                secs,
                error,
            }
        })
        .collect()
}

type Results = Vec<(String, egui::Color32, Vec<Sample>)>;
type Key = (WorkPrecisionSpec, u64, Vec<bool>);

/// One method of the study, owned so it can run on the background thread.
#[derive(Clone)]
enum Job {
    Method(crate::deck::widgets::ResolvedMethod),
    Rk5,
}

impl Job {
    fn scheme(&self) -> Scheme<'_> {
        match self {
            Job::Method(m) => m.scheme(),
            Job::Rk5 => Scheme::Tableau(dopri5_fixed()),
        }
    }
}

pub struct WorkPrecision {
    pub spec: WorkPrecisionSpec,
    initial: WorkPrecisionSpec,
    ode: LiveOde,
    methods: MethodSet,
    computed_for: Option<Key>,
    results: Results,
    pending: Option<Receiver<(String, egui::Color32, Vec<Sample>)>>,
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

    fn jobs(&self) -> Vec<(String, egui::Color32, Job)> {
        let mut v: Vec<_> = self
            .methods
            .shown()
            .map(|m| {
                (
                    m.method.name.clone(),
                    m.color,
                    Job::Method(m.method.clone()),
                )
            })
            .collect();
        if self.spec.rk5 {
            v.push(("RK5".into(), style::DOPRI, Job::Rk5));
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

    /// Starts the study for the current spec (in the background unless DETERMINISTIC).
    fn start(&mut self, ctx: &egui::Context) {
        self.computed_for = Some(self.key());
        self.results.clear();
        self.pending = None;
        let Some(problem) = self.ode.problem().cloned() else {
            return;
        };
        let jobs = self.jobs();
        let spec = self.spec.clone();
        if DETERMINISTIC.load(Ordering::Relaxed) {
            let exact = truth(&problem, spec.t_end);
            self.results = jobs
                .into_iter()
                .map(|(n, c, job)| (n, c, study(&spec, &problem, &exact, job.scheme())))
                .collect();
            return;
        }
        let (tx, rx) = channel();
        let ctx = ctx.clone();
        // Dropping the receiver (spec changed again) makes the next send fail: the thread stops.
        std::thread::spawn(move || {
            let exact = truth(&problem, spec.t_end);
            for (name, color, job) in jobs {
                let r = study(&spec, &problem, &exact, job.scheme());
                if tx.send((name, color, r)).is_err() {
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
        ui.horizontal(|ui| {
            ui.label(format!(
                "{name} over t ∈ [{}, {}]; best error per method:",
                fmt_num(t0).trim_end_matches(".000"),
                fmt_num(self.spec.t_end)
            ));
            for (name, color, s) in &self.results {
                let best = s.iter().map(|s| s.error).fold(f64::INFINITY, f64::min);
                ui.colored_label(
                    style::text_color(ui, *color),
                    egui::RichText::new(format!("{name} {}", fmt_num(best))).strong(),
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
                            for (name, color, samples) in results {
                                let v: Vec<[f64; 2]> = samples
                                    .iter()
                                    .filter(|s| s.error.is_finite() && s.error > 0.0)
                                    .map(|s| {
                                        [
                                            if by_time { s.secs } else { s.f_evals as f64 }.log10(),
                                            s.error.log10().max(-16.0),
                                        ]
                                    })
                                    .collect();
                                p.line(
                                    Line::new(name.clone(), v.clone())
                                        .color(*color)
                                        .width(style::PATH_WIDTH),
                                );
                                p.points(Points::new(name.clone(), v).color(*color).radius(4.5));
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
}

#[cfg(test)]
mod tests {
    use super::*;

    fn deck() -> &'static FsPath {
        FsPath::new(concat!(env!("CARGO_MANIFEST_DIR"), "/slides/lecture.ron"))
    }

    fn spec(levels: usize) -> WorkPrecisionSpec {
        ron::from_str(&format!(
            "(ode: File(\"problems/circle.ron\"), t_end: 10.0, levels: {levels})"
        ))
        .unwrap()
    }

    #[test]
    fn rk5_is_fifth_order_and_beats_rk4_per_evaluation_at_high_accuracy() {
        let spec = spec(6);
        let p = Problem::load(deck().with_file_name("problems/circle.ron")).unwrap();
        let exact = p.exact(10.0).unwrap();
        let rk5 = study(&spec, &p, &exact, Scheme::Tableau(dopri5_fixed()));
        let order = (rk5[2].error / rk5[3].error).log2();
        assert!((order - 5.0).abs() < 0.3, "{order}");
        let rk4 = study(&spec, &p, &exact, Scheme::Method(crate::ode::Method::Rk4));
        // at ~the same work, RK5's error is smaller
        assert!(rk5[3].error < rk4[3].error);
    }

    #[test]
    fn background_study_delivers_without_blocking_the_frame() {
        let ctx = egui::Context::default();
        let mut w = WorkPrecision::new(spec(12), Some(deck()));
        w.start(&ctx);
        assert!(w.busy());
        while w.busy() {
            w.poll();
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
        assert_eq!(w.results.len(), 4);
    }
}
