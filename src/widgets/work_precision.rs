//! Widget 7: Speed vs error: the work–precision diagram (error vs f-evaluations, and vs wall time),
//! computed on a background thread so the UI never waits. Fixed-step methods (Euler, midpoint,
//! RK4, a fifth-order RK5, deck tableaux) are swept over the step h; the adaptive embedded pairs
//! (Tsit5, DOP853, Vern9, …) over their tolerance, through the one adaptive loop
//! (`ode::solve_embedded`). Answers "why not RK5, RK6?": each extra order costs more
//! f-evaluations per step and pays off once the error asked for is small enough — DOP853 and
//! Vern9 overtake RK4 at tight errors, while at loose ones RK4 or a fifth-order pair is cheaper.
//! On a stiff problem file (`problems/vanderpol-1000.ron`) the stiff solvers (`Rodas5p`,
//! `Radau5`) sweep their tolerance the same way, and DOPRI5 and DOP853 stop where their
//! stiffness test fires, shown as "stiff: stopped at t = …" rather than grinding for minutes.

use super::problem_files::MadeIn;
use std::sync::atomic::Ordering;
use std::sync::mpsc::{Receiver, channel};

use egui_plot::{Line, MarkerShape, Points};

use super::convergence::{log_axes_plot, pow10_label, truth};
use super::live_ode::LiveOde;
use super::methods::MethodSet;
use super::style::{self, fmt_num};
use super::{Param, SlideWidget};
use crate::deck::widgets::WorkPrecisionSpec;
use crate::ode::Scheme;
use crate::ode::problem::Problem;

mod sweeps;

pub use crate::ode::study::{Sample, Sweep, TOL_MAX, TOL_MIN, tolerances};
pub use sweeps::{
    Curve, DETERMINISTIC, H_MAX, MAX_ADAPTIVE_STEPS, dopri5_fixed, step_sizes, steps, study,
};

type Key = (WorkPrecisionSpec, u64, Vec<bool>);

/// One method of the study, owned so it can run on the background thread.
#[derive(Clone)]
enum Job {
    Method(crate::deck::widgets::ResolvedMethod),
    Rk5,
}

impl Job {
    fn sweep(&self, spec: &WorkPrecisionSpec, sys: &Problem) -> Sweep<'_> {
        match self {
            Job::Method(m) => match m.adaptive() {
                Some(adaptive) => Sweep::tolerances(adaptive, MAX_ADAPTIVE_STEPS),
                None => steps(spec, sys, m.scheme()),
            },
            Job::Rk5 => steps(spec, sys, Scheme::Tableau(dopri5_fixed())),
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
    pub fn new(spec: WorkPrecisionSpec, at: MadeIn<'_>) -> Self {
        let deck_path = at.deck_path;
        Self {
            ode: LiveOde::new(&spec.ode, at),
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
            v.push((curve("rk5", "RK5", style::RK5, false), Job::Rk5));
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
                c.samples = study(
                    &self.spec,
                    &problem,
                    &exact,
                    &job.sweep(&self.spec, &problem),
                );
                c
            })
            .collect()
    }

    /// Starts the study for the current spec (in the background unless DETERMINISTIC).
    fn start(&mut self, ctx: &egui::Context) {
        self.computed_for = Some(self.key());
        self.results.clear();
        self.pending = None;
        // A browser page has no threads to spare: the web player runs the study in the frame
        // (each run bounded as below).
        if DETERMINISTIC.load(Ordering::Relaxed) || cfg!(target_arch = "wasm32") {
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
                curve.samples = study(&spec, &problem, &exact, &job.sweep(&spec, &problem));
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
            style::slider(ui, &mut self.spec.levels, 3..=14, "step sizes", false);
            self.methods.toggles_ui(ui);
            style::toggle(
                ui,
                &mut self.spec.rk5,
                egui::RichText::new("RK5")
                    .color(style::text_color(ui, style::RK5))
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
                let txt = match c.stiff_at() {
                    Some(t) => format!("{} stiff: stopped at t = {}", c.name, fmt_num(t)),
                    None => format!("{} {}", c.name, fmt_num(c.best_error())),
                };
                let color = style::text_color(ui, c.color);
                ui.add(
                    egui::Label::new(egui::RichText::new(txt).strong().color(color))
                        .wrap_mode(egui::TextWrapMode::Extend),
                );
            }
        });
        let u = style::unit(ui);
        let half = (ui.available_width() - ui.spacing().item_spacing.x) / 2.0;
        // each panel its own y name, above its own left edge (the right panel's used to be
        // folded into its x label)
        ui.horizontal_top(|ui| {
            for name in ["error", "time ÷ fastest"] {
                ui.vertical(|ui| {
                    ui.set_width(half);
                    style::y_name_ui(ui, name);
                });
            }
        });
        let height = ui.available_height();
        let results = &self.results;
        let sweeps: Vec<&[Sample]> = results.iter().map(|c| c.samples.as_slice()).collect();
        let relative = crate::ode::study::relative_cost(&sweeps);
        ui.horizontal_top(|ui| {
            // left: what each run reached for its work; right: the answer to the slide's
            // question, per error asked for, how many times the fastest method's time each
            // takes (the method at 1× is the one to pick, and it changes with the error)
            ui.allocate_ui(egui::vec2(half, height), |ui| {
                log_axes_plot(ui, "wp-evals", "f evaluations")
                    .width(half)
                    .height(height)
                    .show(ui, |p| {
                        for c in results {
                            let v: Vec<[f64; 2]> = c
                                .samples
                                .iter()
                                .filter(|s| s.error.is_finite() && s.error > 0.0)
                                .map(|s| [(s.f_evals as f64).log10(), s.error.log10().max(-16.0)])
                                .collect();
                            // squares mark a tolerance sweep, dots a step-size sweep
                            let (shape, radius) = if c.adaptive {
                                (MarkerShape::Square, style::MARKER_RADIUS * u)
                            } else {
                                (MarkerShape::Circle, 0.9 * style::MARKER_RADIUS * u)
                            };
                            p.line(
                                Line::new(c.name.clone(), v.clone())
                                    .color(c.color)
                                    .width(style::PATH_WIDTH * u),
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
            ui.allocate_ui(egui::vec2(half, height), |ui| {
                style::plot(ui, "wp-relative", "error asked for")
                    .width(half)
                    .height(height)
                    .x_grid_spacer(egui_plot::uniform_grid_spacer(|_| [2.0, 2.0, 2.0]))
                    .y_grid_spacer(egui_plot::uniform_grid_spacer(|_| [1.0, 1.0, 1.0]))
                    .x_axis_formatter(|m, _| pow10_label(-m.value))
                    .y_axis_formatter(|m, _| {
                        let v = 10f64.powf(m.value).round();
                        if v >= 1.0 {
                            format!("{v}×")
                        } else {
                            String::new()
                        }
                    })
                    .include_y(0.0)
                    .show(ui, |p| {
                        for (c, v) in results.iter().zip(&relative) {
                            p.line(
                                Line::new(c.name.clone(), v.clone())
                                    .color(c.color)
                                    .width(style::PATH_WIDTH * u),
                            );
                        }
                    });
            });
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

    ode_plumbing!(WorkPrecision, |w: &Self| {
        if w.spec.rk5 {
            vec![("RK5".to_owned(), style::RK5)]
        } else {
            Vec::new()
        }
    });

    /// `series,sweep,h_or_tol,f_evals,error`: every run, series by method key (`rk5` for the
    /// fixed-step fifth-order weights), `sweep` `h` or `tol`. Wall time is left out: it is the
    /// machine's, not the method's (and a modelled one in headless exports).
    /// Each curve's best error, as the caption prints it, from the whole study (not what
    /// the background thread has sent so far: export asks before any frame is drawn). An
    /// explicit pair that its stiffness test stopped at every tolerance reads `stiff_at`
    /// (the earliest such t) instead.
    fn readouts(&mut self) -> Vec<super::Readout> {
        self.compute()
            .iter()
            .map(|c| match c.stiff_at() {
                Some(t) => super::Readout::new("stiff_at", c.key.clone(), t),
                None => super::Readout::new("best_error", c.key.clone(), c.best_error()),
            })
            .collect()
    }

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
    use super::sweeps::tests::{deck, spec};
    use super::*;

    #[test]
    fn background_study_delivers_without_blocking_the_frame() {
        let ctx = egui::Context::default();
        let mut w = WorkPrecision::new(
            spec(12, ", methods: [Euler, Rk4, Dop853]"),
            crate::widgets::MadeIn::deck(Some(deck())),
        );
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
