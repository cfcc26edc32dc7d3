//! Widget 3: Inaccuracy: explicit Euler on the circle (ẋ, ẏ) = (−y, x) spirals outwards (its radius
//! grows by √(1 + h²) per step); midpoint drifts far less and RK4 stays on the circle at
//! lecture scale. The radius after each revolution is printed under each panel. Any ODE with
//! two or more variables can be drawn (its first two, one panel per method), with its exact
//! (or reference) solution dashed over one revolution.

use super::problem_files::MadeIn;
use egui_plot::{Line, PlotPoints, Points};

use super::live_ode::LiveOde;
use super::methods::{
    MAX_DRAWN_POINTS, MethodEntry, MethodSet, Path, decimate, fixed_path, reference_path, steps_for,
};
use super::style::{self, fmt_num};
use super::{Param, PlotData, Readout, SlideWidget};
use crate::deck::widgets::SpiralSpec;
use crate::ode::problem::Problem;

const H_RANGE: (f64, f64) = (0.005, 1.0);
const MAX_STEPS: usize = 20_000;
/// Radii printed under each panel: the first revolutions'.
const PRINTED_TURNS: usize = 4;

/// Euler's radius growth per step on the circle, √(1 + h²): |1 + ih| for z' = iz.
fn euler_growth_per_step(h: f64) -> f64 {
    (1.0 + h * h).sqrt()
}

/// One panel's drawing data, kept between frames: the full solve is reduced to a decimated
/// polyline, its end point, the plot's half-width and the radius after each revolution.
struct Panel {
    name: String,
    color: egui::Color32,
    line: Vec<[f64; 2]>,
    end: [f64; 2],
    lim: f64,
    revs: Vec<f64>,
}

struct Computed {
    panels: Vec<Panel>,
    /// The true solution over one revolution (t₀ … t₀ + 2π), dashed in every panel.
    exact: Vec<[f64; 2]>,
}

type Key = (SpiralSpec, u64, Vec<bool>);

pub struct Spiral {
    pub spec: SpiralSpec,
    initial: SpiralSpec,
    ode: LiveOde,
    methods: MethodSet,
    cache: Option<(Key, Computed)>,
}

impl Spiral {
    pub fn new(spec: SpiralSpec, at: MadeIn<'_>) -> Self {
        let deck_path = at.deck_path;
        Self {
            ode: LiveOde::new(&spec.ode, at),
            methods: MethodSet::new(&spec.methods, deck_path),
            initial: spec.clone(),
            spec,
            cache: None,
        }
    }

    /// The methods drawn: all that are switched on, or only the first without `compare`.
    fn drawn(&self) -> Vec<&MethodEntry> {
        let shown = self.methods.shown();
        if self.spec.compare {
            shown.collect()
        } else {
            shown.take(1).collect()
        }
    }

    /// The problem, if it has the two variables a spiral needs.
    fn problem(&mut self) -> Option<Problem> {
        self.ode.problem().filter(|p| p.vars.len() >= 2).cloned()
    }

    /// Every drawn method's path and radii per revolution.
    pub fn paths(&mut self) -> Vec<(String, Path, Vec<f64>)> {
        let Some(p) = self.problem() else {
            return Vec::new();
        };
        let h = self.spec.h.clamp(H_RANGE.0, H_RANGE.1);
        let t_end = p.t0 + self.spec.turns.clamp(0.1, 20.0) * std::f64::consts::TAU;
        let n = steps_for(p.t0, t_end, h, MAX_STEPS);
        self.drawn()
            .into_iter()
            .map(|m| {
                let path = fixed_path(&p, m.method.scheme(), p.t0, &p.initial, h, n, 1e6);
                let revs = (1..)
                    .map(|k| (k as f64 * std::f64::consts::TAU / h).round() as usize)
                    .take_while(|&i| i < path.xs.len())
                    .map(|i| path.xs[i][0].hypot(path.xs[i][1]))
                    .collect();
                (m.method.key.clone(), path, revs)
            })
            .collect()
    }

    fn update(&mut self) {
        let key = (
            self.spec.clone(),
            self.ode.revision(),
            self.methods.switches(),
        );
        if self.cache.as_ref().is_some_and(|(k, _)| *k == key) {
            return;
        }
        let Some(p) = self.problem() else {
            self.cache = None;
            return;
        };
        let looks: Vec<(String, egui::Color32)> = self
            .drawn()
            .iter()
            .map(|m| (m.method.name.clone(), m.color))
            .collect();
        let panels = self
            .paths()
            .into_iter()
            .zip(looks)
            .map(|((_, path, revs), (name, color))| {
                let pts: Vec<[f64; 2]> = path.xs.iter().map(|x| [x[0], x[1]]).collect();
                // over every point, not the decimated ones: the axes must hold the whole spiral
                let lim = pts
                    .iter()
                    .map(|p| p[0].abs().max(p[1].abs()))
                    .fold(1.2, f64::max)
                    * 1.05;
                Panel {
                    name,
                    color,
                    end: *pts.last().unwrap_or(&[p.initial[0], p.initial[1]]),
                    line: decimate(&pts, MAX_DRAWN_POINTS),
                    lim,
                    revs,
                }
            })
            .collect();
        let exact = one_revolution(&p);
        self.cache = Some((key, Computed { panels, exact }));
    }
}

/// The true solution over t₀ … t₀ + 2π at 257 points: the exact one, or a fine RK4 reference.
fn one_revolution(p: &Problem) -> Vec<[f64; 2]> {
    let tau = std::f64::consts::TAU;
    if p.has_exact() {
        return (0..=256)
            .filter_map(|i| {
                let t = p.t0 + i as f64 / 256.0 * tau;
                p.exact(t).map(|x| [x[0], x[1]])
            })
            .collect();
    }
    let r = reference_path(p, p.t0, &p.initial, p.t0 + tau);
    decimate(&r.xs.iter().map(|x| [x[0], x[1]]).collect::<Vec<_>>(), 257)
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
                euler_growth_per_step(self.spec.h)
            ));
        });
        style::problems_ui(ui, self.ode.load_error(), &self.methods.errors);
        if self.ode.problem().is_some_and(|p| p.vars.len() < 2) {
            style::problems_ui(
                ui,
                Some("the spiral draws problems with two variables"),
                &[],
            );
        }
        self.update();
        let Some((_, computed)) = &self.cache else {
            return;
        };
        let data = &computed.panels;
        let n = data.len().max(1) as f32;
        let u = style::unit(ui);
        let spacing = ui.spacing().item_spacing.x;
        let w = ((ui.available_width() - spacing * (n - 1.0)) / n).max(50.0 * u);
        // below each plot: its name and its radii, two text lines
        let text_h = 2.0
            * (ui.text_style_height(&egui::TextStyle::Body) + ui.spacing().item_spacing.y)
            + 2.0 * ui.spacing().item_spacing.y;
        let plot_h = (ui.available_height() - text_h).max(80.0 * u);
        let side = w.min(plot_h);
        // one range for every panel, so the three can be compared: the widest spiral's
        let lim = data.iter().map(|p| p.lim).fold(0.0, f64::max);
        let aspect = self
            .spec
            .aspect
            .unwrap_or(crate::deck::widgets::Aspect::Equal);
        ui.horizontal_top(|ui| {
            for panel in data {
                let (name, end) = (&panel.name, panel.end);
                ui.vertical(|ui| {
                    ui.set_width(w);
                    let color = panel.color;
                    let circle = PlotPoints::from(computed.exact.clone());
                    style::with_aspect(style::plot(ui, format!("spiral-{name}"), ""), aspect)
                        .width(w)
                        .height(side)
                        .default_x_bounds(-lim, lim)
                        .default_y_bounds(-lim, lim)
                        .show(ui, |p| {
                            p.set_plot_bounds(egui_plot::PlotBounds::from_min_max(
                                [-lim, -lim],
                                [lim, lim],
                            ));
                            p.line(
                                Line::new(name.as_str(), panel.line.clone())
                                    .color(color)
                                    .width(style::PATH_WIDTH * u),
                            );
                            p.points(
                                Points::new("end", vec![end])
                                    .color(color)
                                    .radius(style::MARKER_RADIUS * u),
                            );
                            // over the path, so the circle shows where a method keeps to it
                            p.line(
                                Line::new("exact", circle)
                                    .color(ink)
                                    .width(style::REFERENCE_WIDTH * u)
                                    .style(egui_plot::LineStyle::Dashed { length: 14.0 * u }),
                            );
                        });
                    ui.colored_label(
                        style::text_color(ui, color),
                        egui::RichText::new(name.as_str()).strong(),
                    );
                    let radii: Vec<String> = panel
                        .revs
                        .iter()
                        .take(PRINTED_TURNS)
                        .map(|r| fmt_num(*r))
                        .collect();
                    ui.label(format!("r per turn: {}", radii.join(", ")));
                });
            }
        });
    }

    fn params(&mut self) -> Vec<Param<'_>> {
        let mut v = vec![
            Param::step_h(&mut self.spec.h, H_RANGE),
            Param::f64("turns", "revolutions", &mut self.spec.turns, 0.5, 10.0),
            Param::bool("compare", "other methods beside", &mut self.spec.compare),
        ];
        v.extend(self.methods.params());
        v.extend(self.ode.params());
        v
    }

    ode_plumbing!(Spiral);

    fn data(&mut self) -> Option<PlotData> {
        let vars = self.problem()?.vars;
        let series = self.paths().into_iter().map(|(k, p, _)| (k, p)).collect();
        Some(PlotData { vars, series })
    }

    /// What the panels print: `h`, Euler's `growth_per_step` √(1 + h²), and per method the
    /// radius after each printed revolution, `radius_turn_1` … `radius_turn_4`.
    fn readouts(&mut self) -> Vec<Readout> {
        let mut v = vec![
            Readout::new("h", "", self.spec.h),
            Readout::new(
                "growth_per_step",
                "euler",
                euler_growth_per_step(self.spec.h),
            ),
        ];
        for (key, _, revs) in self.paths() {
            for (k, r) in revs.iter().take(PRINTED_TURNS).enumerate() {
                v.push(Readout::new(format!("radius_turn_{}", k + 1), &key, *r));
            }
        }
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path as FsPath;

    #[test]
    fn euler_radius_per_revolution_matches_theory() {
        let deck = FsPath::new(concat!(env!("CARGO_MANIFEST_DIR"), "/slides/lecture.ron"));
        let spec =
            ron::from_str("(ode: File(\"problems/circle.ron\"), h: 0.1, turns: 2.0)").unwrap();
        let mut s = Spiral::new(spec, crate::widgets::MadeIn::deck(Some(deck)));
        let paths = s.paths();
        let revs = &paths[0].2;
        let n1 = (std::f64::consts::TAU / 0.1).round();
        let expected = (1.0f64 + 0.01).powf(n1 / 2.0);
        assert!((revs[0] - expected).abs() < 1e-9, "{revs:?} vs {expected}");
        let rk4 = &paths[2].2;
        assert!((rk4[0] - 1.0).abs() < 1e-5, "{rk4:?}");
    }
}
