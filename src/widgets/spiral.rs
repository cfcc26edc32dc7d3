//! 3. Inaccuracy: explicit Euler on the circle (ẋ, ẏ) = (−y, x) spirals outwards (its radius
//! grows by √(1 + h²) per step); midpoint drifts far less and RK4 stays on the circle at
//! lecture scale. The radius after each revolution is printed under each panel.

use egui_plot::{Line, Plot, PlotPoints, Points};

use super::methods::{MAX_DRAWN_POINTS, MethodId, Path, decimate, fixed_path, steps_for};
use super::style::{self, fmt_num};
use super::{Param, SlideWidget};
use crate::deck::widgets::{Field2, SpiralSpec};

const H_RANGE: (f64, f64) = (0.005, 1.0);
const MAX_STEPS: usize = 20_000;

/// One panel's drawing data, kept between frames: the full solve is reduced to a decimated
/// polyline, its end point, the plot's half-width and the radius after each revolution.
struct Panel {
    method: MethodId,
    line: Vec<[f64; 2]>,
    end: [f64; 2],
    lim: f64,
    revs: Vec<f64>,
}

pub struct Spiral {
    pub spec: SpiralSpec,
    initial: SpiralSpec,
    cache: Option<(SpiralSpec, Vec<Panel>)>,
}

impl Spiral {
    pub fn new(spec: SpiralSpec) -> Self {
        Self {
            initial: spec.clone(),
            spec,
            cache: None,
        }
    }

    fn methods(&self) -> &'static [MethodId] {
        if self.spec.compare {
            &MethodId::INTEGRATORS
        } else {
            &[MethodId::Euler]
        }
    }

    /// The path of `m` from (1, 0) over `turns` revolutions, and its radius after each one.
    pub fn path(&self, m: MethodId) -> (Path, Vec<f64>) {
        let h = self.spec.h.clamp(H_RANGE.0, H_RANGE.1);
        let t_end = self.spec.turns.clamp(0.1, 20.0) * std::f64::consts::TAU;
        let n = steps_for(0.0, t_end, h, MAX_STEPS);
        let sys = Field2::Circle.system();
        let p = fixed_path(&sys, m.scheme().unwrap(), 0.0, &[1.0, 0.0], h, n, 1e6);
        let revs = (1..)
            .map(|k| (k as f64 * std::f64::consts::TAU / h).round() as usize)
            .take_while(|&i| i < p.xs.len())
            .map(|i| p.xs[i][0].hypot(p.xs[i][1]))
            .collect();
        (p, revs)
    }

    /// The Euler path alone (kept for callers of the seed API).
    pub fn euler_path(&self) -> Vec<[f64; 2]> {
        self.path(MethodId::Euler)
            .0
            .xs
            .iter()
            .map(|x| [x[0], x[1]])
            .collect()
    }

    fn update(&mut self) {
        if self.cache.as_ref().is_some_and(|(s, _)| *s == self.spec) {
            return;
        }
        let data = self
            .methods()
            .iter()
            .map(|&m| {
                let (p, revs) = self.path(m);
                let pts: Vec<[f64; 2]> = p.xs.iter().map(|x| [x[0], x[1]]).collect();
                // over every point, not the decimated ones: the axes must hold the whole spiral
                let lim = pts
                    .iter()
                    .map(|p| p[0].abs().max(p[1].abs()))
                    .fold(1.2, f64::max)
                    * 1.05;
                Panel {
                    method: m,
                    end: *pts.last().unwrap_or(&[1.0, 0.0]),
                    line: decimate(&pts, MAX_DRAWN_POINTS),
                    lim,
                    revs,
                }
            })
            .collect();
        self.cache = Some((self.spec.clone(), data));
    }
}

impl SlideWidget for Spiral {
    fn ui(&mut self, ui: &mut egui::Ui) {
        style::projector_text(ui);
        let ink = style::ink(ui);
        let k = style::keys(ui);
        k.step_h(&mut self.spec.h, H_RANGE);
        ui.horizontal(|ui| {
            style::h_slider(ui, &mut self.spec.h, H_RANGE);
            ui.label(format!(
                "Euler grows r by √(1+h²) = {:.4} per step",
                (1.0 + self.spec.h.powi(2)).sqrt()
            ));
        });
        self.update();
        let Some((_, data)) = &self.cache else { return };
        let n = data.len() as f32;
        let spacing = ui.spacing().item_spacing.x;
        let w = ((ui.available_width() - spacing * (n - 1.0)) / n).max(50.0);
        let plot_h = (ui.available_height() - 70.0).max(80.0);
        let side = w.min(plot_h);
        ui.horizontal_top(|ui| {
            for panel in data {
                let (m, lim, end) = (&panel.method, panel.lim, panel.end);
                ui.vertical(|ui| {
                    ui.set_width(w);
                    let color = style::method_color(*m);
                    let circle: PlotPoints = (0..=256)
                        .map(|i| {
                            let a = i as f64 / 256.0 * std::f64::consts::TAU;
                            [a.cos(), a.sin()]
                        })
                        .collect();
                    Plot::new(format!("spiral-{}", m.name()))
                        .width(w)
                        .height(side)
                        .data_aspect(1.0)
                        .allow_drag(false)
                        .allow_zoom(false)
                        .allow_scroll(false)
                        .show_x(false)
                        .show_y(false)
                        .default_x_bounds(-lim, lim)
                        .default_y_bounds(-lim, lim)
                        .show(ui, |p| {
                            p.line(
                                Line::new("exact", circle)
                                    .color(ink)
                                    .width(1.5)
                                    .style(egui_plot::LineStyle::dashed_loose()),
                            );
                            p.line(
                                Line::new(m.name(), panel.line.clone())
                                    .color(color)
                                    .width(style::PATH_WIDTH),
                            );
                            p.points(Points::new("end", vec![end]).color(color).radius(5.0));
                        });
                    ui.colored_label(color, egui::RichText::new(m.name()).strong());
                    let radii: Vec<String> =
                        panel.revs.iter().take(4).map(|r| fmt_num(*r)).collect();
                    ui.label(format!("r per turn: {}", radii.join(", ")));
                });
            }
        });
    }

    fn params(&mut self) -> Vec<Param<'_>> {
        vec![
            Param::f64_log("h", "step h", &mut self.spec.h, H_RANGE.0, H_RANGE.1),
            Param::f64("turns", "revolutions", &mut self.spec.turns, 0.5, 10.0),
            Param::bool("compare", "midpoint and RK4 beside", &mut self.spec.compare),
        ]
    }

    spec_plumbing!(Spiral);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn euler_radius_per_revolution_matches_theory() {
        let s = Spiral::new(SpiralSpec {
            h: 0.1,
            turns: 2.0,
            compare: true,
        });
        let (_, revs) = s.path(MethodId::Euler);
        let n1 = (std::f64::consts::TAU / 0.1).round();
        let expected = (1.0f64 + 0.01).powf(n1 / 2.0);
        assert!((revs[0] - expected).abs() < 1e-9, "{revs:?} vs {expected}");
        let (_, rk4) = s.path(MethodId::Rk4);
        assert!((rk4[0] - 1.0).abs() < 1e-5, "{rk4:?}");
    }
}
