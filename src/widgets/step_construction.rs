//! Widget 2: One step, built up stage by stage: Euler's tangent; midpoint's half step, the slope at
//! the midpoint, then the full step with it; RK4's k1..k4 as arrows, then their weighted
//! combination. `[` and `]` step backwards and forwards through the construction.

use super::problem_files::MadeIn;
use egui_plot::{Arrows, Line, PlotPoint, PlotPoints, Points};

use super::controls;
use super::labels;
use super::live_ode::LiveOde;
use super::methods::fixed_path;
use super::style::{self, fmt_num};
use super::{Param, PlotData, Readout, SlideWidget};
use crate::deck::widgets::{MethodRef, StepSpec, WidgetSpec};
use crate::ode::problem::Problem;
use crate::ode::{Method, Scheme, System};

/// The three constructions drawn (any other method is drawn as RK4's).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Construction {
    Euler,
    Midpoint,
    Rk4,
}

impl Construction {
    pub fn of(m: &MethodRef) -> Self {
        match m.builtin() {
            Some(Method::Euler) => Construction::Euler,
            Some(Method::Midpoint) => Construction::Midpoint,
            _ => Construction::Rk4,
        }
    }

    fn method(self) -> Method {
        match self {
            Construction::Euler => Method::Euler,
            Construction::Midpoint => Method::Midpoint,
            Construction::Rk4 => Method::Rk4,
        }
    }

    fn reference(self) -> MethodRef {
        MethodRef::Builtin(self.method())
    }

    fn name(self) -> &'static str {
        self.method().label()
    }
}

/// Number of reveal stages of a construction.
pub fn stages(m: Construction) -> usize {
    match m {
        Construction::Euler => 2,
        Construction::Midpoint => 3,
        Construction::Rk4 => 5,
    }
}

/// One drawn element of the construction.
#[derive(Debug, Clone, PartialEq)]
pub struct Arrow {
    pub from: [f64; 2],
    pub to: [f64; 2],
    pub label: String,
    /// Stage (1-based) at which it appears.
    pub stage: usize,
    /// Drawn faint (a sampled slope) rather than bold (a step actually taken).
    pub faint: bool,
    /// Where the label sits relative to `to`: above-right unless a neighbour needs the room.
    pub anchor: egui::Align2,
}

/// The construction of one step of `m` from `(t0, x0)`: arrows and the end point. The end
/// point comes from the project's integrator, so the picture is the method, not a drawing of it.
pub fn construct(p: &Problem, m: Construction, t0: f64, x0: f64, h: f64) -> (Vec<Arrow>, [f64; 2]) {
    let mut d = [0.0];
    let mut f = |t: f64, x: f64| {
        p.rhs(t, &[x], &mut d);
        d[0]
    };
    let slope_mark = |t: f64, x: f64, k: f64, label: &str, stage: usize| {
        let d = 0.18 * h;
        Arrow {
            from: [t - d, x - d * k],
            to: [t + d, x + d * k],
            label: label.into(),
            stage,
            faint: true,
            anchor: egui::Align2::LEFT_BOTTOM,
        }
    };
    let step = |t: f64, x: f64, dt: f64, k: f64, label: &str, stage: usize| Arrow {
        from: [t, x],
        to: [t + dt, x + dt * k],
        label: label.into(),
        stage,
        faint: false,
        anchor: egui::Align2::LEFT_BOTTOM,
    };
    let mut out = Vec::new();
    let k1 = f(t0, x0);
    match m {
        Construction::Euler => {
            out.push(slope_mark(t0, x0, k1, "k₁ = f(x₀)", 1));
            out.push(step(t0, x0, h, k1, "x₀ + h k₁", 2));
        }
        Construction::Midpoint => {
            out.push(step(t0, x0, h / 2.0, k1, "half step", 1));
            let (tm, xm) = (t0 + h / 2.0, x0 + h / 2.0 * k1);
            let k2 = f(tm, xm);
            out.push(slope_mark(tm, xm, k2, "f at midpoint", 2));
            out.push(step(t0, x0, h, k2, "x₀ + h f(mid)", 3));
        }
        Construction::Rk4 => {
            out.push(step(t0, x0, h / 2.0, k1, "k₁", 1));
            let k2 = f(t0 + h / 2.0, x0 + h / 2.0 * k1);
            out.push(slope_mark(t0 + h / 2.0, x0 + h / 2.0 * k1, k2, "", 2));
            out.push(step(t0, x0, h / 2.0, k2, "k₂", 2));
            let k3 = f(t0 + h / 2.0, x0 + h / 2.0 * k2);
            out.push(slope_mark(t0 + h / 2.0, x0 + h / 2.0 * k2, k3, "", 3));
            let k3_at = out.len();
            out.push(step(t0, x0, h, k3, "k₃", 3));
            let k4 = f(t0 + h, x0 + h * k3);
            out.push(slope_mark(t0 + h, x0 + h * k3, k4, "k₄", 4));
            let k = (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0;
            out.push(step(t0, x0, h, k, "(k₁+2k₂+2k₃+k₄)/6", 5));
            // k₃'s step and the combination end close together at t₀ + h: the higher end
            // gets its label above, the lower one below, so they never overlap.
            let below = egui::Align2::LEFT_TOP;
            if k >= k3 {
                out[k3_at].anchor = below;
            } else if let Some(last) = out.last_mut() {
                last.anchor = below;
            }
        }
    }
    let end = fixed_path(
        p,
        Scheme::Method(m.method()),
        t0,
        &[x0],
        h,
        1,
        f64::INFINITY,
    );
    (out, [t0 + h, end.last()[0]])
}

const H_RANGE: (f64, f64) = (0.1, 3.0);

pub struct StepConstruction {
    pub spec: StepSpec,
    initial: StepSpec,
    ode: LiveOde,
}

impl StepConstruction {
    pub fn new(mut spec: StepSpec, at: MadeIn<'_>) -> Self {
        let mut ode = LiveOde::new(&spec.ode, at);
        if spec.start.is_none()
            && let Some(p) = ode.problem()
        {
            spec.start = Some((p.t0, p.initial[0]));
        }
        Self {
            initial: spec.clone(),
            spec,
            ode,
        }
    }

    /// The 1-D problem to construct on, or why there is none.
    fn problem(&mut self) -> Result<Problem, String> {
        let err = self.ode.load_error().map(str::to_owned);
        match self.ode.problem() {
            Some(p) if p.vars.len() == 1 => Ok(p.clone()),
            Some(p) => Err(format!(
                "the step construction draws 1-D problems; this one has {} variables",
                p.vars.len()
            )),
            None => Err(err.unwrap_or_else(|| "no equation".into())),
        }
    }
}

impl SlideWidget for StepConstruction {
    fn colours(&self) -> Vec<(String, egui::Color32)> {
        [
            Construction::Euler,
            Construction::Midpoint,
            Construction::Rk4,
        ]
        .into_iter()
        .map(|c| (c.name().to_owned(), style::method_color(c.method())))
        .collect()
    }

    fn ui(&mut self, ui: &mut egui::Ui) {
        style::projector_text(ui);
        let ink = style::ink(ui);
        // stay inside a column: the control row must not widen the plot past its share
        ui.set_max_width(ui.available_width());
        let m = Construction::of(&self.spec.method);
        let n = stages(m);
        let k = style::keys(ui);
        if k.forward {
            self.spec.stage = (self.spec.stage + 1).min(n);
        }
        if k.back {
            self.spec.stage = self.spec.stage.saturating_sub(1);
        }
        k.step_h(&mut self.spec.h, H_RANGE);
        self.spec.stage = self.spec.stage.min(n);
        ui.horizontal_wrapped(|ui| {
            for c in [
                Construction::Euler,
                Construction::Midpoint,
                Construction::Rk4,
            ] {
                // selected: readable on the selection fill; otherwise the method's colour
                let colour = if m == c {
                    ui.visuals().strong_text_color()
                } else {
                    style::text_color(ui, style::method_color(c.method()))
                };
                let text = egui::RichText::new(c.name()).color(colour).strong();
                if !style::controls_shown(ui) {
                    // the audience sees which method is built, not the switch
                    if m == c {
                        ui.label(
                            egui::RichText::new(c.name())
                                .color(style::text_color(ui, style::method_color(c.method())))
                                .strong(),
                        );
                    }
                    continue;
                }
                if controls::control(ui, |ui| ui.selectable_label(m == c, text)).clicked() {
                    self.spec.method = c.reference();
                    self.spec.stage = 0;
                }
            }
        });
        ui.horizontal(|ui| {
            ui.spacing_mut().slider_width = 160.0 * style::unit(ui);
            style::slider(ui, &mut self.spec.h, H_RANGE.0..=H_RANGE.1, "h", false);
            style::slider(ui, &mut self.spec.stage, 0..=n, "stage  [ ]", false);
        });
        let p = match self.problem() {
            Ok(p) => p,
            Err(e) => {
                style::problems_ui(ui, Some(&e), &[]);
                return;
            }
        };
        style::problems_ui(ui, self.ode.load_error(), &[]);
        let (t0, x0) = self.spec.start.unwrap_or((p.t0, p.initial[0]));
        let h = self.spec.h;
        let (arrows, end) = construct(&p, m, t0, x0, h);
        let stage = self.spec.stage;
        let color = style::method_color(m.method());
        let exact: Vec<[f64; 2]> = if p.has_exact() {
            (0..=200)
                .filter_map(|i| {
                    let t = t0 - 0.1 * h + i as f64 / 200.0 * 1.3 * h;
                    p.exact_from(t0, &[x0], t).map(|x| [t, x[0]])
                })
                .collect()
        } else {
            let r = super::methods::reference_path(&p, t0, &[x0], t0 + 1.2 * h);
            r.ts.iter().zip(&r.xs).map(|(t, x)| [*t, x[0]]).collect()
        };
        let truth = p.exact_from(t0, &[x0], t0 + h).map(|x| x[0]);
        if stage == n {
            let err = truth
                .map(|x| {
                    let e = (end[1] - x).abs();
                    let share = if x != 0.0 {
                        format!(" ({:.0} % of x)", 100.0 * e / x.abs())
                    } else {
                        String::new()
                    };
                    format!("{}{share}", fmt_num(e))
                })
                .unwrap_or_else(|| "–".into());
            ui.label(format!(
                "x(t₀+h) ≈ {}   error of this one step: {err}",
                fmt_num(end[1])
            ));
        } else {
            ui.label(format!("stage {stage} of {n}: press ] to continue"));
        }
        let u = style::unit(ui);
        style::y_name_ui(ui, "x");
        let mut labels = Vec::new();
        let mut points_at = vec![PlotPoint::new(t0, x0)];
        // labels keep off every drawn line: the exact curve and each shown arrow or slope
        let mut lines = vec![exact.clone()];
        lines.extend(
            arrows
                .iter()
                .filter(|a| a.stage <= stage)
                .map(|a| vec![a.from, a.to]),
        );
        let shown = style::plot(ui, "step-construction", "t")
            .width(ui.available_width())
            .include_x(t0 - 0.1 * h)
            .include_x(t0 + 1.2 * h)
            .show(ui, |p| {
                p.line(
                    Line::new("exact", exact)
                        .color(ink)
                        .width(style::REFERENCE_WIDTH * u),
                );
                for a in arrows.iter().filter(|a| a.stage <= stage) {
                    let (c, w) = if a.faint {
                        (style::FIELD, 0.0)
                    } else {
                        (color, 12.0 * u)
                    };
                    if a.faint {
                        p.line(
                            Line::new("slope", vec![a.from, a.to])
                                .color(c)
                                .width(4.0 * u),
                        );
                    } else {
                        p.add(
                            Arrows::new(
                                a.label.clone(),
                                PlotPoints::from(vec![a.from]),
                                PlotPoints::from(vec![a.to]),
                            )
                            .color(c)
                            .tip_length(w),
                        );
                        p.line(
                            Line::new(a.label.clone(), vec![a.from, a.to])
                                .color(c)
                                .width(style::PATH_WIDTH * u),
                        );
                    }
                    if !a.label.is_empty() {
                        labels.push(labels::PlotLabel {
                            text: a.label.clone(),
                            color: c,
                            at: PlotPoint::new(a.to[0], a.to[1]),
                            anchor: a.anchor,
                        });
                    }
                }
                p.points(
                    Points::new("x0", vec![[t0, x0]])
                        .color(ink)
                        .radius(style::KEY_MARKER_RADIUS * u),
                );
                if stage == n {
                    p.points(
                        Points::new("x1", vec![end])
                            .color(color)
                            .radius(style::KEY_MARKER_RADIUS * u),
                    );
                    points_at.push(PlotPoint::new(end[0], end[1]));
                    if let Some(x) = truth {
                        p.points(
                            Points::new("exact x(t0+h)", vec![[t0 + h, x]])
                                .color(ink)
                                .radius(style::MARKER_RADIUS * u),
                        );
                        points_at.push(PlotPoint::new(t0 + h, x));
                    }
                }
            });
        let t = &shown.transform;
        let obstacles: Vec<egui::Rect> = points_at
            .iter()
            .map(|&e| labels::marker_rect(t, e, style::KEY_MARKER_RADIUS * u))
            .collect();
        labels::draw(ui, t, &labels, &obstacles, &lines);
    }

    fn params(&mut self) -> Vec<Param<'_>> {
        let mut v = vec![
            Param::f64("h", "step h", &mut self.spec.h, H_RANGE.0, H_RANGE.1),
            Param::usize("stage", "construction stage", &mut self.spec.stage, 0, 5),
        ];
        v.extend(self.ode.params());
        v
    }

    fn reset(&mut self) {
        self.spec = self.initial.clone();
        self.ode.reset();
    }

    fn spec(&self) -> WidgetSpec {
        WidgetSpec::StepConstruction(self.spec.clone())
    }

    fn ode(&mut self) -> Option<&mut LiveOde> {
        Some(&mut self.ode)
    }

    fn problems(&self) -> Vec<String> {
        style::problem_lines(self.ode.load_error(), &[])
    }

    /// One step of the chosen method from the start: its two points.
    fn data(&mut self) -> Option<PlotData> {
        let p = self.problem().ok()?;
        let m = Construction::of(&self.spec.method);
        let (t0, x0) = self.spec.start.unwrap_or((p.t0, p.initial[0]));
        let path = fixed_path(
            &p,
            Scheme::Method(m.method()),
            t0,
            &[x0],
            self.spec.h,
            1,
            f64::INFINITY,
        );
        Some(PlotData {
            vars: p.vars.clone(),
            series: vec![(m.method().name().to_string(), path)],
        })
    }

    /// What the slide prints once the step is built: x(t₀+h) of the method (`x_end`), the
    /// exact value there (`exact_end`) and the error of the step (`error_end`).
    fn readouts(&mut self) -> Vec<Readout> {
        let Ok(p) = self.problem() else {
            return Vec::new();
        };
        let m = Construction::of(&self.spec.method);
        let key = m.method().name().to_string();
        let (t0, x0) = self.spec.start.unwrap_or((p.t0, p.initial[0]));
        let h = self.spec.h;
        let (_, end) = construct(&p, m, t0, x0, h);
        let mut v = vec![
            Readout::new("h", "", h),
            Readout::new("x_end", key.clone(), end[1]),
        ];
        if let Some(x) = p.exact_from(t0, &[x0], t0 + h).map(|x| x[0]) {
            v.push(Readout::new("exact_end", "", x));
            v.push(Readout::new("error_end", key, (end[1] - x).abs()));
        }
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn drawn_rk4_combination_lands_on_the_integrators_step() {
        let p = Problem::load(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/slides/problems/forced.ron"
        ))
        .unwrap();
        for m in [
            Construction::Euler,
            Construction::Midpoint,
            Construction::Rk4,
        ] {
            let (arrows, end) = construct(&p, m, 0.2, 1.1, 0.9);
            let last = arrows.last().unwrap();
            assert!(
                (last.to[0] - end[0]).abs() < 1e-12 && (last.to[1] - end[1]).abs() < 1e-12,
                "{m:?}"
            );
            assert_eq!(last.stage, stages(m));
        }
    }
}
