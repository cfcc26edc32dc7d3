//! 6. Convergence: global error at the end time vs step size h on log–log axes, one line per
//! method, with the least-squares slope (the measured order) labelled and recomputed live.
//! Include the notes' RK4 typo (ERRATA 1) to watch fourth order collapse to first.

use egui_plot::{Line, Plot, PlotPoint, Points, Text};

use super::methods::{MethodId, steps_for};
use super::style::{self, fmt_num};
use super::{Param, SlideWidget};
use crate::deck::widgets::ConvergenceSpec;
use crate::ode::study;

/// Below this, errors are round-off, not truncation: left out of the fit.
const ERR_FLOOR: f64 = 1e-13;

/// The step of halving `k`, rounded so a whole number of steps lands on t_end.
fn level_h(spec: &ConvergenceSpec, k: usize) -> f64 {
    let h = spec.h_max / 2f64.powi(k as i32);
    spec.t_end / steps_for(0.0, spec.t_end, h, 1 << 20) as f64
}

/// Steps one method takes at halving `k` (the work the per-frame budget counts).
fn level_steps(spec: &ConvergenceSpec, k: usize) -> usize {
    (spec.t_end / level_h(spec, k)).round() as usize
}

/// (h, error) points of one method at halvings `ks`, by `ode::study::convergence`; diverged
/// runs (infinite error) are left out.
pub fn errors_at(
    spec: &ConvergenceSpec,
    m: MethodId,
    ks: std::ops::Range<usize>,
) -> Vec<(f64, f64)> {
    let (Some(scheme), Some(truth)) = (m.scheme(), spec.field.exact(0.0, spec.x0, spec.t_end))
    else {
        return Vec::new();
    };
    let hs: Vec<f64> = ks.map(|k| level_h(spec, k)).collect();
    let sys = spec.field.system();
    study::convergence(&sys, scheme, 0.0, &[spec.x0], spec.t_end, &[truth], &hs)
        .points
        .into_iter()
        .filter(|p| p.1.is_finite())
        .collect()
}

/// (h, error) points of one method at every halving.
pub fn errors(spec: &ConvergenceSpec, m: MethodId) -> Vec<(f64, f64)> {
    errors_at(spec, m, 0..levels(spec))
}

fn levels(spec: &ConvergenceSpec) -> usize {
    spec.levels.clamp(2, 12)
}

/// Least-squares slope of log(err) against log(h) (`ode::study::loglog_slope`), over points
/// above the round-off floor.
pub fn fitted_slope(pts: &[(f64, f64)]) -> Option<f64> {
    let v: Vec<(f64, f64)> = pts.iter().copied().filter(|p| p.1 > ERR_FLOOR).collect();
    let slope = study::loglog_slope(&v);
    slope.is_finite().then_some(slope)
}

/// Steps (summed over methods) computed per frame at most: 12 halvings of RK4 and friends
/// are ~10⁵ steps, spread over a few frames instead of stalling one. Whole levels are
/// computed, at least one per frame, so the result does not depend on timing.
const STEPS_PER_FRAME: usize = 40_000;

type Rows = Vec<(MethodId, Vec<(f64, f64)>, Option<f64>)>;

pub struct Convergence {
    pub spec: ConvergenceSpec,
    initial: ConvergenceSpec,
    /// Results for a spec, complete up to `done` halvings.
    cache: Option<(ConvergenceSpec, Rows, usize)>,
}

impl Convergence {
    pub fn new(spec: ConvergenceSpec) -> Self {
        Self {
            initial: spec.clone(),
            spec,
            cache: None,
        }
    }

    /// Every halving at once (for tests and exports).
    pub fn compute(&self) -> Rows {
        let mut rows = self.rows_empty();
        self.extend(&mut rows, 0..levels(&self.spec));
        rows
    }

    fn rows_empty(&self) -> Rows {
        self.methods()
            .into_iter()
            .map(|m| (m, Vec::new(), None))
            .collect()
    }

    fn extend(&self, rows: &mut Rows, ks: std::ops::Range<usize>) {
        for (m, pts, slope) in rows.iter_mut() {
            pts.extend(errors_at(&self.spec, *m, ks.clone()));
            *slope = fitted_slope(pts);
        }
    }

    /// Advances the cached study by one frame's budget; true when it is complete.
    fn advance(&mut self) -> bool {
        let stale = !self.cache.as_ref().is_some_and(|(s, ..)| *s == self.spec);
        if stale {
            self.cache = Some((self.spec.clone(), self.rows_empty(), 0));
        }
        let total = levels(&self.spec);
        let per_level = |k| level_steps(&self.spec, k) * self.methods().len();
        let (_, _, done) = self.cache.as_ref().expect("set above");
        let mut end = *done;
        let mut budget = 0;
        while end < total && (end == *done || budget + per_level(end) <= STEPS_PER_FRAME) {
            budget += per_level(end);
            end += 1;
        }
        let start = *done;
        let (_, mut rows, _) = self.cache.take().expect("set above");
        self.extend(&mut rows, start..end);
        self.cache = Some((self.spec.clone(), rows, end));
        end == total
    }

    fn methods(&self) -> Vec<MethodId> {
        let mut ms = self.spec.methods.clone();
        if self.spec.typo && !ms.contains(&MethodId::Rk4Typo) {
            ms.push(MethodId::Rk4Typo);
        }
        ms.retain(|m| *m != MethodId::Exact);
        ms
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

pub fn log_axes_plot<'a>(id: &str, x_label: &str, y_label: &str) -> Plot<'a> {
    Plot::new(id.to_owned())
        .allow_drag(false)
        .allow_zoom(false)
        .allow_scroll(false)
        .x_axis_label(x_label.to_owned())
        .y_axis_label(y_label.to_owned())
        .x_grid_spacer(egui_plot::uniform_grid_spacer(|_| [1.0, 1.0, 1.0]))
        .y_grid_spacer(egui_plot::uniform_grid_spacer(|_| [1.0, 2.0, 4.0]))
        .x_axis_formatter(|m, _| pow10_label(m.value))
        .y_axis_formatter(|m, _| pow10_label(m.value))
}

impl SlideWidget for Convergence {
    fn ui(&mut self, ui: &mut egui::Ui) {
        style::projector_text(ui);
        ui.horizontal(|ui| {
            ui.add(
                egui::Slider::new(&mut self.spec.h_max, 0.05..=1.0)
                    .logarithmic(true)
                    .text("largest h"),
            );
            ui.add(egui::Slider::new(&mut self.spec.levels, 3..=12).text("halvings"));
            ui.checkbox(
                &mut self.spec.typo,
                egui::RichText::new("notes' RK4 typo")
                    .color(style::RK4_TYPO)
                    .strong(),
            );
        });
        if !self.advance() {
            ui.ctx().request_repaint();
        }
        let Some((_, data, _)) = &self.cache else {
            return;
        };
        ui.horizontal(|ui| {
            ui.label(format!(
                "{}, error at t = {}:  slope =",
                self.spec.field.label(),
                fmt_num(self.spec.t_end)
            ));
            for (m, _, s) in data {
                let txt = s
                    .map(|s| format!("{} {:.2}", m.name(), s))
                    .unwrap_or_else(|| format!("{} –", m.name()));
                ui.colored_label(style::method_color(*m), egui::RichText::new(txt).strong());
            }
        });
        let h_min = data
            .iter()
            .flat_map(|d| d.1.iter().map(|p| p.0))
            .fold(f64::INFINITY, f64::min);
        let plot = log_axes_plot("convergence", "step h", "global error");
        let plot = if h_min.is_finite() {
            plot.include_x(h_min.log10() - 0.6)
        } else {
            plot
        };
        plot.show(ui, |p| {
            for (m, pts, slope) in data {
                let color = style::method_color(*m);
                let v: Vec<[f64; 2]> = pts
                    .iter()
                    .filter(|p| p.1 > 0.0)
                    .map(|p| [p.0.log10(), p.1.log10().max(-16.0)])
                    .collect();
                p.line(
                    Line::new(m.name(), v.clone())
                        .color(color)
                        .width(style::PATH_WIDTH),
                );
                p.points(Points::new(m.name(), v.clone()).color(color).radius(5.0));
                // label at the smallest h, left of the line, in room the x range leaves for it
                if let (Some(s), Some(last)) = (slope, v.last()) {
                    p.text(
                        Text::new(
                            format!("{} slope", m.name()),
                            PlotPoint::new(last[0], last[1]),
                            egui::RichText::new(format!("slope {s:.2}  "))
                                .size(22.0)
                                .strong()
                                .color(color),
                        )
                        .anchor(egui::Align2::RIGHT_CENTER),
                    );
                }
            }
        });
    }

    fn params(&mut self) -> Vec<Param<'_>> {
        vec![
            Param::f64_log("h_max", "largest h", &mut self.spec.h_max, 0.05, 1.0),
            Param::usize("levels", "halvings", &mut self.spec.levels, 3, 12),
            Param::bool("typo", "notes' RK4 typo", &mut self.spec.typo),
        ]
    }

    spec_plumbing!(Convergence);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::deck::widgets::Field1;

    #[test]
    fn measured_slopes_are_the_orders_and_the_typo_drops_to_one() {
        let spec = ConvergenceSpec {
            field: Field1::Forced,
            x0: 1.5,
            t_end: 4.0,
            h_max: 0.25,
            levels: 6,
            methods: vec![MethodId::Euler, MethodId::Midpoint, MethodId::Rk4],
            typo: true,
        };
        let c = Convergence::new(spec).compute();
        let slope = |m: MethodId| c.iter().find(|e| e.0 == m).unwrap().2.unwrap();
        assert!(
            (slope(MethodId::Euler) - 1.0).abs() < 0.15,
            "{}",
            slope(MethodId::Euler)
        );
        assert!((slope(MethodId::Midpoint) - 2.0).abs() < 0.15);
        assert!(
            (slope(MethodId::Rk4) - 4.0).abs() < 0.25,
            "{}",
            slope(MethodId::Rk4)
        );
        assert!(
            (slope(MethodId::Rk4Typo) - 1.0).abs() < 0.25,
            "{}",
            slope(MethodId::Rk4Typo)
        );
    }
}
