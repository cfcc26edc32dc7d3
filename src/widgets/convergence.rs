//! 6. Convergence: global error at the end time vs step size h on log–log axes, one line per
//! method, with the least-squares slope (the measured order) labelled and recomputed live.
//! Include the notes' RK4 typo (ERRATA 1) to watch fourth order collapse to first.

use egui_plot::{Line, Plot, PlotPoint, Points, Text};
use serde::{Deserialize, Serialize};

use super::methods::{MethodId, fixed_path, steps_for};
use super::problems::Field1;
use super::style::{self, fmt_num};
use super::{Param, SlideWidget};

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConvergenceSpec {
    #[serde(default = "default_field")]
    pub field: Field1,
    #[serde(default = "default_x0")]
    pub x0: f64,
    #[serde(default = "default_t_end")]
    pub t_end: f64,
    /// Largest step; each further point halves it.
    #[serde(default = "default_h_max")]
    pub h_max: f64,
    #[serde(default = "default_levels")]
    pub levels: usize,
    #[serde(default = "default_methods")]
    pub methods: Vec<MethodId>,
    /// Also show the notes' RK4 with the k4 typo.
    #[serde(default)]
    pub typo: bool,
}

fn default_field() -> Field1 {
    Field1::Forced
}
fn default_x0() -> f64 {
    1.5
}
fn default_t_end() -> f64 {
    4.0
}
fn default_h_max() -> f64 {
    0.5
}
fn default_levels() -> usize {
    8
}
fn default_methods() -> Vec<MethodId> {
    vec![MethodId::Euler, MethodId::Midpoint, MethodId::Rk4]
}

/// Below this, errors are round-off, not truncation: left out of the fit.
const ERR_FLOOR: f64 = 1e-13;

/// (h, error) points of one method.
pub fn errors(spec: &ConvergenceSpec, m: MethodId) -> Vec<(f64, f64)> {
    let sys = spec.field.system();
    let exact = spec.field.exact(0.0, spec.x0, spec.t_end);
    (0..spec.levels.clamp(2, 12))
        .filter_map(|k| {
            let h = spec.h_max / 2f64.powi(k as i32);
            let n = steps_for(0.0, spec.t_end, h, 1 << 20);
            let h = spec.t_end / n as f64; // land exactly on t_end
            let p = fixed_path(&sys, m.tableau()?, 0.0, &[spec.x0], h, n, 1e12);
            let truth = exact?;
            (p.diverged_at.is_none()).then(|| (h, (p.last()[0] - truth).abs()))
        })
        .collect()
}

/// Least-squares slope of log10(err) against log10(h), over points above the round-off floor.
pub fn fitted_slope(pts: &[(f64, f64)]) -> Option<f64> {
    let v: Vec<(f64, f64)> = pts
        .iter()
        .filter(|p| p.1 > ERR_FLOOR)
        .map(|p| (p.0.log10(), p.1.log10()))
        .collect();
    if v.len() < 2 {
        return None;
    }
    let n = v.len() as f64;
    let (mx, my) = (
        v.iter().map(|p| p.0).sum::<f64>() / n,
        v.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxy: f64 = v.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = v.iter().map(|p| (p.0 - mx).powi(2)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

pub struct Convergence {
    pub spec: ConvergenceSpec,
    initial: ConvergenceSpec,
    cache: Option<(
        ConvergenceSpec,
        Vec<(MethodId, Vec<(f64, f64)>, Option<f64>)>,
    )>,
}

impl Convergence {
    pub fn new(spec: ConvergenceSpec) -> Self {
        Self {
            initial: spec.clone(),
            spec,
            cache: None,
        }
    }

    pub fn compute(&self) -> Vec<(MethodId, Vec<(f64, f64)>, Option<f64>)> {
        let mut ms = self.spec.methods.clone();
        if self.spec.typo && !ms.contains(&MethodId::Rk4Typo) {
            ms.push(MethodId::Rk4Typo);
        }
        ms.into_iter()
            .filter(|m| *m != MethodId::Exact)
            .map(|m| {
                let e = errors(&self.spec, m);
                let s = fitted_slope(&e);
                (m, e, s)
            })
            .collect()
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
        if !self.cache.as_ref().is_some_and(|(s, _)| *s == self.spec) {
            self.cache = Some((self.spec.clone(), self.compute()));
        }
        let Some((_, data)) = &self.cache else { return };
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
