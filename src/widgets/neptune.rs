//! 4. Instability, "off to Neptune": y' = λy (or the oscillator x'' = −x) integrated with `h`
//! on either side of a method's stability limit. The axes stay clamped to the true solution's
//! scale; a path that leaves them ends in a red "diverged" marker, never NaN or a crash.

use egui_plot::{Line, MarkerShape, Plot, PlotPoint, Points, Text};

use super::methods::{MethodId, Path, fixed_path, steps_for};
use super::stability::{C, stable_h_limit};
use super::style::{self, fmt_num};
use super::{Param, SlideWidget};
use crate::deck::widgets::{Field1, Field2, NeptuneProblem, NeptuneSpec};

const H_RANGE: (f64, f64) = (0.01, 3.5);
/// The view shows |y| up to this multiple of the initial value.
const CLAMP: f64 = 2.5;

/// A path clipped to |y| ≤ CLAMP: the visible points and, if it left, where.
pub fn clip(path: &Path) -> (Vec<[f64; 2]>, Option<[f64; 2]>) {
    let mut pts: Vec<[f64; 2]> = Vec::with_capacity(path.ts.len());
    for (t, x) in path.ts.iter().zip(&path.xs) {
        let y = x[0];
        if y.abs() > CLAMP {
            if let Some(&[tp, yp]) = pts.last() {
                // cut the segment where it crosses the clamp line
                let edge = CLAMP * y.signum();
                let s = (edge - yp) / (y - yp);
                let exit = [tp + s * (t - tp), edge];
                pts.push(exit);
                return (pts, Some(exit));
            }
            return (pts, Some([*t, CLAMP * y.signum()]));
        }
        pts.push([*t, y]);
    }
    let exit = path.diverged_at.map(|t| {
        [
            t,
            CLAMP * path.last().first().copied().unwrap_or(1.0).signum(),
        ]
    });
    (pts, exit)
}

pub struct Neptune {
    pub spec: NeptuneSpec,
    initial: NeptuneSpec,
}

impl Neptune {
    pub fn new(spec: NeptuneSpec) -> Self {
        Self {
            initial: spec.clone(),
            spec,
        }
    }

    fn shown(&self) -> Vec<MethodId> {
        let s = &self.spec;
        [
            (s.euler, MethodId::Euler),
            (s.midpoint, MethodId::Midpoint),
            (s.rk4, MethodId::Rk4),
        ]
        .into_iter()
        .filter_map(|(on, m)| on.then_some(m))
        .collect()
    }

    /// λ of the test equation the problem reduces to (the oscillator's eigenvalues are ±i).
    pub fn lambda(&self) -> C {
        match self.spec.problem {
            NeptuneProblem::Decay { lambda } => C(lambda, 0.0),
            NeptuneProblem::Oscillator => C(0.0, 1.0),
        }
    }

    pub fn path(&self, m: MethodId) -> Path {
        let h = self.spec.h.clamp(H_RANGE.0, H_RANGE.1);
        let n = steps_for(0.0, self.spec.t_end, h, 10_000);
        let tab = m.scheme().unwrap();
        match self.spec.problem {
            NeptuneProblem::Decay { lambda } => fixed_path(
                &Field1::Decay { k: -lambda }.system(),
                tab,
                0.0,
                &[1.0],
                h,
                n,
                1e6,
            ),
            NeptuneProblem::Oscillator => {
                fixed_path(&Field2::Circle.system(), tab, 0.0, &[1.0, 0.0], h, n, 1e6)
            }
        }
    }

    fn exact(&self, t: f64) -> f64 {
        match self.spec.problem {
            NeptuneProblem::Decay { lambda } => (lambda * t).exp(),
            NeptuneProblem::Oscillator => t.cos(),
        }
    }
}

impl SlideWidget for Neptune {
    fn ui(&mut self, ui: &mut egui::Ui) {
        style::projector_text(ui);
        let ink = style::ink(ui);
        let k = style::keys(ui);
        k.step_h(&mut self.spec.h, H_RANGE);
        let lambda = self.lambda();
        ui.horizontal(|ui| {
            style::h_slider(ui, &mut self.spec.h, H_RANGE);
            style::method_toggles(
                ui,
                [
                    (&mut self.spec.euler, MethodId::Euler),
                    (&mut self.spec.midpoint, MethodId::Midpoint),
                    (&mut self.spec.rk4, MethodId::Rk4),
                ],
            );
        });
        let shown = self.shown();
        ui.horizontal(|ui| {
            ui.label("stable for h <");
            for &m in &shown {
                let lim = stable_h_limit(&m.tableau().unwrap(), lambda, 10.0);
                let txt = if lim == 0.0 {
                    format!("{}: never", m.name())
                } else {
                    format!("{}: {}", m.name(), fmt_num(lim))
                };
                ui.colored_label(style::method_color(m), egui::RichText::new(txt).strong());
            }
        });
        let t_end = self.spec.t_end;
        let exact: Vec<[f64; 2]> = (0..=400)
            .map(|i| {
                let t = t_end * i as f64 / 400.0;
                [t, self.exact(t)]
            })
            .collect();
        let paths: Vec<_> = shown.iter().map(|&m| (m, clip(&self.path(m)))).collect();
        Plot::new("neptune")
            .allow_drag(false)
            .allow_zoom(false)
            .allow_scroll(false)
            .x_axis_label("t")
            .y_axis_label(match self.spec.problem {
                NeptuneProblem::Decay { .. } => "y",
                NeptuneProblem::Oscillator => "x",
            })
            .default_x_bounds(0.0, t_end)
            .default_y_bounds(-CLAMP * 1.1, CLAMP * 1.1)
            .show(ui, |p| {
                p.set_plot_bounds(egui_plot::PlotBounds::from_min_max(
                    [0.0, -CLAMP * 1.1],
                    [t_end, CLAMP * 1.1],
                ));
                p.line(Line::new("exact", exact).color(ink).width(2.0));
                for (m, (pts, exit)) in &paths {
                    let color = style::method_color(*m);
                    p.line(
                        Line::new(m.name(), pts.clone())
                            .color(color)
                            .width(style::PATH_WIDTH),
                    );
                    p.points(Points::new(m.name(), pts.clone()).color(color).radius(3.0));
                    if let Some(e) = exit {
                        p.points(
                            Points::new("diverged", vec![*e])
                                .shape(if e[1] > 0.0 {
                                    MarkerShape::Up
                                } else {
                                    MarkerShape::Down
                                })
                                .color(style::DIVERGED)
                                .radius(12.0)
                                .filled(true),
                        );
                        let anchor = if e[1] > 0.0 {
                            egui::Align2::LEFT_TOP
                        } else {
                            egui::Align2::LEFT_BOTTOM
                        };
                        p.text(
                            Text::new(
                                "diverged",
                                PlotPoint::new(e[0] + 0.05 * t_end, e[1]),
                                egui::RichText::new(format!(
                                    "{} diverged: off to Neptune!",
                                    m.name()
                                ))
                                .size(22.0)
                                .strong()
                                .color(style::DIVERGED),
                            )
                            .anchor(anchor),
                        );
                    }
                }
            });
    }

    fn params(&mut self) -> Vec<Param<'_>> {
        vec![
            Param::f64_log("h", "step h", &mut self.spec.h, H_RANGE.0, H_RANGE.1),
            Param::bool("euler", "Euler", &mut self.spec.euler),
            Param::bool("midpoint", "Midpoint", &mut self.spec.midpoint),
            Param::bool("rk4", "RK4", &mut self.spec.rk4),
        ]
    }

    spec_plumbing!(Neptune);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(h: f64) -> NeptuneSpec {
        NeptuneSpec {
            problem: NeptuneProblem::Decay { lambda: -5.0 },
            h,
            t_end: 30.0,
            euler: true,
            midpoint: true,
            rk4: true,
        }
    }

    #[test]
    fn euler_diverges_exactly_past_two_over_lambda() {
        let below = Neptune::new(spec(0.39)).path(MethodId::Euler);
        let above = Neptune::new(spec(0.41)).path(MethodId::Euler);
        assert!(below.diverged_at.is_none() && below.last()[0].abs() < 1.0);
        let (_, exit) = clip(&above);
        assert!(exit.is_some(), "h above 2/|λ| must leave the clamped view");
        let huge = Neptune::new(spec(3.5)).path(MethodId::Euler);
        let (pts, _) = clip(&huge);
        assert!(pts.iter().all(|p| p[0].is_finite() && p[1].abs() <= CLAMP));
    }
}
