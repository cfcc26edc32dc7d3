//! Widget 6: Convergence: global error at the end time vs step size h on log–log axes, one line per
//! method, with the least-squares slope (the measured order) labelled and recomputed live.
//! Include the notes' RK4 typo (ERRATA 1), `Tableau("tableaux/rk4-typo.ron")`, to watch fourth
//! order collapse to first. The error is against the problem's exact solution at `t_end`, or a
//! Verner 9(8) reference at rtol 1e-14 when it has none. An adaptive pair (DOP853, Vern9, …)
//! is run here with fixed steps of its propagating formula, so its line shows that formula's
//! order (5 … 9); the legend says "fixed h".

use super::problem_files::MadeIn;
use egui_plot::{Line, Plot, PlotPoint, Points};

use super::labels;
use super::live_ode::LiveOde;
use super::methods::{MethodSet, steps_for};
use super::style::{self, fmt_num};
use super::{Param, SlideWidget};
use crate::deck::widgets::ConvergenceSpec;
use crate::ode::problem::Problem;
use crate::ode::{Scheme, study};

/// A run's error is round-off-dominated below this many machine epsilons per step (times the
/// state's size): N steps each round at ~ε|x|, and the sum drifts like √N … N of those, so a
/// truncation error within 10·N·ε|x| of it no longer shows the method's order.
const ROUND_OFF_PER_STEP: f64 = 10.0 * f64::EPSILON;

/// A slope needs at least this many points in the truncation regime: two points give a
/// number, but not a measured order (the high orders reach round-off in two halvings).
const MIN_FIT_POINTS: usize = 3;

/// The (h, error) points where truncation dominates: error above [`ROUND_OFF_PER_STEP`] times
/// the steps taken over `span` and the truth's size `scale`.
pub fn truncation_points(pts: &[(f64, f64)], span: f64, scale: f64) -> Vec<(f64, f64)> {
    pts.iter()
        .copied()
        .filter(|&(h, e)| e > ROUND_OFF_PER_STEP * (span / h).max(1.0) * scale.max(1.0))
        .collect()
}

/// The step of halving `k`, rounded so a whole number of steps lands on t_end.
fn level_h(spec: &ConvergenceSpec, t0: f64, k: usize) -> f64 {
    let h = spec.h_max / 2f64.powi(k as i32);
    let span = spec.t_end - t0;
    span / steps_for(t0, spec.t_end, h, 1 << 20).max(1) as f64
}

/// Steps one method takes at halving `k` (the work the per-frame budget counts).
fn level_steps(spec: &ConvergenceSpec, t0: f64, k: usize) -> usize {
    ((spec.t_end - t0) / level_h(spec, t0, k)).round().max(0.0) as usize
}

/// The true state at t_end: the exact solution, else a tight Dormand–Prince reference.
pub fn truth(p: &Problem, t_end: f64) -> Vec<f64> {
    p.exact(t_end)
        .unwrap_or_else(|| study::reference(p, p.t0, &p.initial, t_end))
}

/// (h, error) points of one method at halvings `ks`, by `ode::study::convergence`; diverged
/// runs (infinite error) are left out.
pub fn errors_at(
    spec: &ConvergenceSpec,
    p: &Problem,
    truth: &[f64],
    scheme: Scheme<'_>,
    ks: std::ops::Range<usize>,
) -> Vec<(f64, f64)> {
    if spec.t_end.is_nan() || spec.t_end <= p.t0 {
        return Vec::new();
    }
    let hs: Vec<f64> = ks.map(|k| level_h(spec, p.t0, k)).collect();
    study::convergence(p, scheme, p.t0, &p.initial, spec.t_end, truth, &hs)
        .points
        .into_iter()
        .filter(|p| p.1.is_finite())
        .collect()
}

fn levels(spec: &ConvergenceSpec) -> usize {
    spec.levels.clamp(2, 12)
}

/// Least-squares slope of log(err) against log(h) (`ode::study::loglog_slope`) over the
/// truncation-dominated points ([`truncation_points`]); none with fewer than
/// [`MIN_FIT_POINTS`] of them.
pub fn fitted_slope(pts: &[(f64, f64)], span: f64, scale: f64) -> Option<f64> {
    let v = truncation_points(pts, span, scale);
    if v.len() < MIN_FIT_POINTS {
        return None;
    }
    let slope = study::loglog_slope(&v);
    slope.is_finite().then_some(slope)
}

/// The size of the true state the round-off floor scales with.
fn scale_of(truth: &[f64]) -> f64 {
    truth.iter().fold(0.0_f64, |a, v| a.max(v.abs()))
}

/// f-evaluations (steps × stages) computed per frame at most: 12 halvings of RK4 and friends
/// are ~10⁵ steps, and a step of Vern9 costs 16 evaluations to RK4's 4, so the work is spread
/// over a few frames instead of stalling one. A unit is one method at one halving, computed
/// whole (at least one per frame), so the result does not depend on timing.
const F_EVALS_PER_FRAME: usize = 160_000;

/// Per method (key, name, colour): its (h, error) points, fitted slope, and for an adaptive
/// pair the order its slope should approach (shown beside the slope).
type Rows = Vec<(
    String,
    String,
    egui::Color32,
    Vec<(f64, f64)>,
    Option<f64>,
    Option<u32>,
)>;
type Key = (ConvergenceSpec, u64, Vec<bool>);

pub struct Convergence {
    pub spec: ConvergenceSpec,
    initial: ConvergenceSpec,
    ode: LiveOde,
    methods: MethodSet,
    /// Results for a key, complete up to `done` work units (method × halving, level by level),
    /// with the truth they compare with.
    cache: Option<(Key, Rows, usize, Vec<f64>)>,
}

impl Convergence {
    pub fn new(spec: ConvergenceSpec, at: MadeIn<'_>) -> Self {
        let deck_path = at.deck_path;
        Self {
            ode: LiveOde::new(&spec.ode, at),
            methods: MethodSet::new(&spec.methods, deck_path),
            initial: spec.clone(),
            spec,
            cache: None,
        }
    }

    /// Every halving at once (for tests and exports).
    pub fn compute(&mut self) -> Rows {
        let Some(p) = self.ode.problem().cloned() else {
            return Vec::new();
        };
        let truth = truth(&p, self.spec.t_end);
        let mut rows = self.rows_empty();
        self.extend(&p, &truth, &mut rows, 0..levels(&self.spec));
        rows
    }

    fn rows_empty(&self) -> Rows {
        self.methods
            .shown()
            .map(|m| {
                (
                    m.method.key.clone(),
                    legend_name(&m.method),
                    m.color,
                    Vec::new(),
                    None,
                    m.method.adaptive().and(m.method.order()),
                )
            })
            .collect()
    }

    fn extend(&self, p: &Problem, truth: &[f64], rows: &mut Rows, ks: std::ops::Range<usize>) {
        for (row, m) in rows.iter_mut().zip(self.methods.shown()) {
            row.3.extend(errors_at(
                &self.spec,
                p,
                truth,
                m.method.scheme(),
                ks.clone(),
            ));
            row.4 = fitted_slope(&row.3, self.spec.t_end - p.t0, scale_of(truth));
        }
    }

    /// Advances the cached study by one frame's budget; true when it is complete.
    fn advance(&mut self) -> bool {
        let Some(p) = self.ode.problem().cloned() else {
            self.cache = None;
            return true;
        };
        let key = (
            self.spec.clone(),
            self.ode.revision(),
            self.methods.switches(),
        );
        let stale = !self.cache.as_ref().is_some_and(|(k, ..)| *k == key);
        if stale {
            let truth = truth(&p, self.spec.t_end);
            self.cache = Some((key.clone(), self.rows_empty(), 0, truth));
        }
        // work units: one method at one halving, level by level (so each row's points stay
        // in order of h); `done` counts the units computed
        let stages: Vec<usize> = self
            .methods
            .shown()
            // f-evaluations per step: the stages of a tableau; an implicit method's Newton
            // iterations are counted as four
            .map(|m| m.method.tableau.as_ref().map_or(4, |t| t.b.len().max(1)))
            .collect();
        let n = stages.len().max(1);
        let total = levels(&self.spec) * n;
        let cost =
            |u: usize| level_steps(&self.spec, p.t0, u / n) * stages.get(u % n).unwrap_or(&1);
        let Some((_, mut rows, done, truth)) = self.cache.take() else {
            return true;
        };
        let mut end = done;
        let mut budget = 0;
        while end < total && (end == done || budget + cost(end) <= F_EVALS_PER_FRAME) {
            budget += cost(end);
            end += 1;
        }
        for u in done..end {
            let (k, i) = (u / n, u % n);
            if let (Some(row), Some(m)) = (rows.get_mut(i), self.methods.shown().nth(i)) {
                row.3.extend(errors_at(
                    &self.spec,
                    &p,
                    &truth,
                    m.method.scheme(),
                    k..k + 1,
                ));
                row.4 = fitted_slope(&row.3, self.spec.t_end - p.t0, scale_of(&truth));
            }
        }
        self.cache = Some((key, rows, end, truth));
        end >= total
    }
}

/// A method's name in the legend: an adaptive pair says that it runs with a fixed step here
/// ("DOP853 (fixed h)"), since a convergence plot needs h, not a tolerance; the plot labels
/// its slope with the order of its formula.
pub fn legend_name(m: &crate::deck::widgets::ResolvedMethod) -> String {
    if m.adaptive().is_some() {
        format!("{} (fixed h)", m.name)
    } else {
        m.name.clone()
    }
}

/// Tick labels for log10 axes: "10⁻³".
pub fn pow10_label(v: f64) -> String {
    const SUP: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let k = v.round() as i64;
    if (v - k as f64).abs() > 1e-6 {
        return String::new();
    }
    let mut s = String::from("10");
    if k < 0 {
        s.push('⁻');
    }
    for d in k.abs().to_string().chars() {
        s.push(SUP[d.to_digit(10).unwrap() as usize]);
    }
    s
}

/// A log–log plot (axes in decades); the y axis's name is drawn above it by the caller
/// ([`style::y_name_ui`]).
pub fn log_axes_plot<'a>(ui: &egui::Ui, id: &str, x_label: &str) -> Plot<'a> {
    style::plot(ui, id.to_owned(), x_label)
        .x_grid_spacer(egui_plot::uniform_grid_spacer(|_| [1.0, 1.0, 1.0]))
        .y_grid_spacer(egui_plot::uniform_grid_spacer(|_| [1.0, 2.0, 4.0]))
        .x_axis_formatter(|m, _| pow10_label(m.value))
        .y_axis_formatter(|m, _| pow10_label(m.value))
}

impl SlideWidget for Convergence {
    fn ui(&mut self, ui: &mut egui::Ui) {
        style::projector_text(ui);
        ui.horizontal_wrapped(|ui| {
            style::slider(ui, &mut self.spec.h_max, 0.05..=1.0, "largest h", true);
            style::slider(ui, &mut self.spec.levels, 3..=12, "halvings", false);
            self.methods.toggles_ui(ui);
        });
        style::problems_ui(ui, self.ode.load_error(), &self.methods.errors);
        if !self.advance() {
            ui.ctx().request_repaint();
        }
        let label = self.ode.label();
        let Some((_, data, _, truth)) = &self.cache else {
            return;
        };
        let span = self.spec.t_end - self.ode.problem().map_or(0.0, |p| p.t0);
        let scale = scale_of(truth);
        ui.horizontal_wrapped(|ui| {
            ui.label(format!(
                "{label}, error at t = {}:  slope =",
                fmt_num(self.spec.t_end)
            ));
            for (_, name, color, pts, s, _) in data {
                // a line that reaches round-off before three halvings has no measured order
                let txt = match s {
                    Some(s) => format!("{name} {s:.2}"),
                    None if pts.len() >= MIN_FIT_POINTS => format!("{name} – (round-off)"),
                    None => format!("{name} –"),
                };
                // whole entries move to the next row; none breaks inside
                let color = style::text_color(ui, *color);
                ui.add(
                    egui::Label::new(egui::RichText::new(txt).strong().color(color))
                        .wrap_mode(egui::TextWrapMode::Extend),
                );
            }
        });
        let h_min = data
            .iter()
            .flat_map(|d| d.3.iter().map(|p| p.0))
            .fold(f64::INFINITY, f64::min);
        let u = style::unit(ui);
        style::y_name_ui(ui, "global error");
        let plot = log_axes_plot(ui, "convergence", "step h");
        let plot = if h_min.is_finite() {
            plot.include_x(h_min.log10() - 0.6)
        } else {
            plot
        };
        let mut labels = Vec::new();
        let mut ends = Vec::new();
        let mut lines = Vec::new();
        let shown = plot.show(ui, |p| {
            for (_, name, color, pts, slope, order) in data {
                let color = *color;
                let v: Vec<[f64; 2]> = pts
                    .iter()
                    .filter(|p| p.1 > 0.0)
                    .map(|p| [p.0.log10(), p.1.log10().max(-16.0)])
                    .collect();
                p.line(
                    Line::new(name.as_str(), v.clone())
                        .color(color)
                        .width(style::PATH_WIDTH * u),
                );
                p.points(
                    Points::new(name.as_str(), v.clone())
                        .color(color)
                        .radius(style::MARKER_RADIUS * u),
                );
                lines.push(v.clone());
                // every computed point is an obstacle: a label never covers one
                ends.extend(v.iter().map(|e| PlotPoint::new(e[0], e[1])));
                // label at the smallest h of the fit (round-off-dominated points do not
                // count), left of the line, in room the x range leaves for it
                let fitted = truncation_points(pts, span, scale);
                let fitted_end = fitted
                    .iter()
                    .rfind(|p| p.1 > 0.0)
                    .map(|p| [p.0.log10(), p.1.log10()]);
                if let (Some(s), Some(last)) = (slope, fitted_end) {
                    let text = match order {
                        Some(o) => format!("slope {s:.2} (order {o})"),
                        None => format!("slope {s:.2}"),
                    };
                    labels.push(labels::PlotLabel {
                        text,
                        color,
                        at: PlotPoint::new(last[0], last[1]),
                        anchor: egui::Align2::RIGHT_CENTER,
                    });
                }
            }
        });
        let t = &shown.transform;
        let obstacles: Vec<egui::Rect> = ends
            .iter()
            .map(|&e| labels::marker_rect(t, e, style::MARKER_RADIUS * u))
            .collect();
        labels::draw(ui, t, &labels, &obstacles, &lines);
    }

    fn params(&mut self) -> Vec<Param<'_>> {
        let mut v = vec![
            Param::f64_log("h_max", "largest h", &mut self.spec.h_max, 0.05, 1.0),
            Param::usize("levels", "halvings", &mut self.spec.levels, 3, 12),
        ];
        v.extend(self.methods.params());
        v.extend(self.ode.params());
        v
    }

    ode_plumbing!(Convergence);

    /// `series,h,error`: every run (all halvings), series by method key; diverged runs are
    /// left out as on the plot.
    fn csv(&mut self) -> Option<String> {
        self.ode.problem()?;
        let mut out = String::from("series,h,error\n");
        for (key, _, _, pts, _, _) in self.compute() {
            for (h, e) in pts {
                out.push_str(&format!("{key},{h:?},{e:?}\n"));
            }
        }
        Some(out)
    }

    /// Each method's fitted slope as labelled (`slope`), over the points the fit used.
    fn readouts(&mut self) -> Vec<super::Readout> {
        self.compute()
            .into_iter()
            .filter_map(|(key, _, _, _, slope, _)| Some(super::Readout::new("slope", key, slope?)))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path as FsPath;

    #[test]
    fn measured_slopes_are_the_orders_and_the_typo_drops_to_one() {
        let deck = FsPath::new(concat!(env!("CARGO_MANIFEST_DIR"), "/slides/lecture.ron"));
        let spec = ron::from_str(
            "(ode: File(\"problems/forced.ron\"), t_end: 4.0, h_max: 0.25, levels: 6, \
             methods: [Euler, Midpoint, Rk4, Tableau(\"tableaux/rk4-typo.ron\")])",
        )
        .unwrap();
        let c = Convergence::new(spec, crate::widgets::MadeIn::deck(Some(deck))).compute();
        let slope = |k: &str| c.iter().find(|e| e.0 == k).unwrap().4.unwrap();
        for (k, want, tol) in [
            ("euler", 1.0, 0.15),
            ("midpoint", 2.0, 0.15),
            ("rk4", 4.0, 0.25),
            ("rk4-typo", 1.0, 0.25),
        ] {
            assert!((slope(k) - want).abs() < tol, "{k}: {}", slope(k));
        }
    }

    #[test]
    fn frame_by_frame_study_is_bounded_and_equals_the_whole() {
        let deck = FsPath::new(concat!(env!("CARGO_MANIFEST_DIR"), "/slides/lecture.ron"));
        let spec = ron::from_str(
            "(ode: File(\"problems/forced.ron\"), t_end: 4.0, h_max: 1.0, levels: 12, \
             methods: [Euler, Rk4, Dop853, Vern9])",
        )
        .unwrap();
        let mut c = Convergence::new(spec, crate::widgets::MadeIn::deck(Some(deck)));
        let whole = c.compute();
        let mut frames = 1;
        while !c.advance() {
            frames += 1;
            assert!(frames < 100);
        }
        // 4·(2¹² − 1) steps × 33 stages ≈ 540 000 evaluations: several frames, each within
        // the budget (or one unit)
        assert!(frames >= 4, "{frames}");
        let (_, rows, _, _) = c.cache.as_ref().unwrap();
        assert_eq!(*rows, whole);
    }

    #[test]
    fn adaptive_pairs_run_at_fixed_h_and_show_their_orders() {
        let deck = FsPath::new(concat!(env!("CARGO_MANIFEST_DIR"), "/slides/lecture.ron"));
        let spec = ron::from_str(
            "(ode: File(\"problems/forced.ron\"), t_end: 4.0, h_max: 1.0, levels: 5, \
             methods: [Rk4, Tsit5, Vern6, Dop853, Vern9])",
        )
        .unwrap();
        let c = Convergence::new(spec, crate::widgets::MadeIn::deck(Some(deck))).compute();
        let row = |k: &str| c.iter().find(|e| e.0 == k).unwrap();
        assert_eq!(row("dop853").1, "DOP853 (fixed h)");
        assert_eq!((row("dop853").5, row("rk4").5), (Some(8), None));
        assert_eq!(row("rk4").1, "RK4");
        // Double precision leaves the high orders two or three halvings above round-off:
        // DOP853 keeps three truncation-dominated points, Vern9 only two, which give a number
        // (10.5) but no measured order, so it gets no slope.
        for (k, lo, hi) in [
            ("rk4", 3.8, 4.3),
            ("tsit5", 4.5, 5.5),
            ("vern6", 5.8, 7.2),
            ("dop853", 7.4, 8.6),
        ] {
            let s = row(k).4.unwrap();
            assert!((lo..=hi).contains(&s), "{k}: {s}");
        }
        assert_eq!(row("vern9").4, None);
        let span = 4.0;
        let kept = truncation_points(&row("vern9").3, span, 1.0);
        assert_eq!(kept.len(), 2, "{:?}", row("vern9").3);
    }
}
