//! Widget 4: Instability, "off to Neptune": y' = λy (or the oscillator x'' = −x, or any ODE) integrated
//! with `h` on either side of a method's stability limit. The axes stay clamped to the true
//! solution's scale; a path that leaves them ends in a red "diverged" marker, never NaN or a
//! crash. The printed limits use λ, the eigenvalue of the equation's Jacobian at the start with
//! the largest modulus (exact for y' = λy and the oscillator's ±i).

use super::problem_files::MadeIn;
use egui_plot::{Line, MarkerShape, PlotPoint, Points};

use super::labels;
use super::live_ode::LiveOde;
use super::methods::{MethodSet, Path, path_to, reference_path};
use super::stability::{C, H_LIMIT_MAX, limit_text, stable_h_limit};
use super::style;
use super::{Param, PlotData, Readout, SlideWidget};
use crate::deck::widgets::NeptuneSpec;
use crate::ode::System;
use crate::ode::problem::Problem;

const H_RANGE: (f64, f64) = (0.01, 3.5);
/// The view shows |y| up to this multiple of the initial value (of 1 when it starts at 0).
const CLAMP: f64 = 2.5;

/// A path clipped to |y| ≤ clamp: the visible points and, if it left, where.
pub fn clip(path: &Path, clamp: f64) -> (Vec<[f64; 2]>, Option<[f64; 2]>) {
    let pts: Vec<[f64; 2]> = path
        .ts
        .iter()
        .zip(&path.xs)
        .map(|(t, x)| [*t, x[0]])
        .collect();
    clip_points(&pts, path.diverged_at, clamp)
}

/// Points (t, y) clipped to |y| ≤ clamp: the visible ones and, if the curve left (or its run
/// diverged at `diverged_at`), where, on the clamp line.
pub fn clip_points(
    points: &[[f64; 2]],
    diverged_at: Option<f64>,
    clamp: f64,
) -> (Vec<[f64; 2]>, Option<[f64; 2]>) {
    let mut pts: Vec<[f64; 2]> = Vec::with_capacity(points.len());
    for &[t, y] in points {
        if y.abs() > clamp {
            if let Some(&[tp, yp]) = pts.last() {
                // cut the segment where it crosses the clamp line
                let edge = clamp * y.signum();
                let s = (edge - yp) / (y - yp);
                let exit = [tp + s * (t - tp), edge];
                pts.push(exit);
                return (pts, Some(exit));
            }
            return (pts, Some([t, clamp * y.signum()]));
        }
        pts.push([t, y]);
    }
    let exit = diverged_at.map(|t| {
        let last = points.last().map_or(1.0, |p| p[1]);
        [t, clamp * if last < 0.0 { -1.0 } else { 1.0 }]
    });
    (pts, exit)
}

/// The red marker where a path left the view at `e` (pointing the way it went), and its label
/// `text`, beside it (below it when it left upwards), to place with [`exit_labels_ui`].
pub fn exit_marker(
    p: &mut egui_plot::PlotUi<'_>,
    e: [f64; 2],
    text: String,
    u: f32,
) -> labels::PlotLabel {
    let up = e[1] > 0.0;
    p.points(
        Points::new("diverged", vec![e])
            .shape(if up {
                MarkerShape::Up
            } else {
                MarkerShape::Down
            })
            .color(style::DIVERGED)
            .radius(EXIT_MARKER_RADIUS * u)
            .filled(true),
    );
    labels::PlotLabel {
        text,
        color: style::DIVERGED,
        at: PlotPoint::new(e[0], e[1]),
        anchor: if up {
            egui::Align2::LEFT_TOP
        } else {
            egui::Align2::LEFT_BOTTOM
        },
    }
}

/// The exit markers' radius, in slide units.
const EXIT_MARKER_RADIUS: f32 = 2.0 * style::KEY_MARKER_RADIUS;

/// Places the exit markers' labels clear of the markers at `exits` and of the drawn `lines`.
pub fn exit_labels_ui(
    ui: &egui::Ui,
    transform: &egui_plot::PlotTransform,
    exit_labels: &[labels::PlotLabel],
    exits: &[PlotPoint],
    lines: &[Vec<[f64; 2]>],
    u: f32,
) {
    let obstacles: Vec<egui::Rect> = exits
        .iter()
        .map(|&e| labels::marker_rect(transform, e, EXIT_MARKER_RADIUS * u))
        .collect();
    labels::draw(ui, transform, exit_labels, &obstacles, lines);
}

pub struct Neptune {
    pub spec: NeptuneSpec,
    initial: NeptuneSpec,
    ode: LiveOde,
    methods: MethodSet,
}

/// The eigenvalue of largest modulus of f's Jacobian at (t, x) (central differences), with a
/// non-negative imaginary part; for one or two variables (`None` beyond).
pub fn dominant_eigenvalue(p: &Problem, t: f64, x: &[f64]) -> Option<C> {
    let n = p.dim();
    if n > 2 {
        return None;
    }
    let mut jac = [[0.0; 2]; 2];
    let (mut up, mut down) = (vec![0.0; n], vec![0.0; n]);
    for j in 0..n {
        let e = 1e-6 * x[j].abs().max(1.0);
        let mut xp = x.to_vec();
        xp[j] += e;
        p.rhs(t, &xp, &mut up);
        xp[j] -= 2.0 * e;
        p.rhs(t, &xp, &mut down);
        for i in 0..n {
            jac[i][j] = (up[i] - down[i]) / (2.0 * e);
        }
    }
    if n == 1 {
        return jac[0][0].is_finite().then_some(C(jac[0][0], 0.0));
    }
    let half_tr = 0.5 * (jac[0][0] + jac[1][1]);
    let det = jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0];
    let disc = half_tr * half_tr - det;
    let l = if disc >= 0.0 {
        let r = disc.sqrt();
        // the real root of larger modulus
        if (half_tr + r).abs() >= (half_tr - r).abs() {
            C(half_tr + r, 0.0)
        } else {
            C(half_tr - r, 0.0)
        }
    } else {
        C(half_tr, (-disc).sqrt())
    };
    (l.0.is_finite() && l.1.is_finite()).then_some(l)
}

impl Neptune {
    pub fn new(spec: NeptuneSpec, at: MadeIn<'_>) -> Self {
        let deck_path = at.deck_path;
        Self {
            ode: LiveOde::new(&spec.ode, at),
            methods: MethodSet::new(&spec.methods, deck_path),
            initial: spec.clone(),
            spec,
        }
    }

    /// λ of the test equation the problem reduces to near its start.
    pub fn lambda(&mut self) -> Option<C> {
        let p = self.ode.problem()?;
        dominant_eigenvalue(p, p.t0, &p.initial)
    }

    /// The path of every method switched on: (key, name, colour, path).
    pub fn paths(&mut self) -> Vec<(String, String, egui::Color32, Path)> {
        let Some(p) = self.ode.problem().cloned() else {
            return Vec::new();
        };
        let h = self.spec.h.clamp(H_RANGE.0, H_RANGE.1);
        let t_end = self.spec.t_end;
        self.methods
            .shown()
            .map(|m| {
                let path = path_to(
                    &p,
                    m.method.scheme(),
                    p.t0,
                    &p.initial,
                    h,
                    t_end,
                    10_000,
                    1e6,
                );
                (m.method.key.clone(), m.method.name.clone(), m.color, path)
            })
            .collect()
    }

    /// Each shown method's largest stable h for `lambda`: (key, name, colour, limit); a method
    /// without R(z) (a symplectic splitting) reads as never stable here.
    pub fn limits(&self, lambda: C) -> Vec<(String, String, egui::Color32, f64)> {
        self.methods
            .shown()
            .map(|m| {
                let abs_r = |z: C| {
                    m.method
                        .stability((z.0, z.1))
                        .map_or(f64::INFINITY, |r| r.0.hypot(r.1))
                };
                let lim = stable_h_limit(abs_r, lambda, H_LIMIT_MAX);
                (m.method.key.clone(), m.method.name.clone(), m.color, lim)
            })
            .collect()
    }

    /// |y| the view holds: CLAMP times the initial value.
    fn clamp(p: &Problem) -> f64 {
        let y0 = p.initial[0].abs();
        CLAMP * if y0 > 0.0 { y0 } else { 1.0 }
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
            self.methods.toggles_ui(ui);
        });
        style::problems_ui(ui, self.ode.load_error(), &self.methods.errors);
        let Some(p) = self.ode.problem().cloned() else {
            return;
        };
        if let Some(lambda) = lambda {
            let limits = self.limits(lambda);
            ui.horizontal(|ui| {
                ui.label(format!("{}, stable for", lambda_text(lambda)));
                for (_, name, color, lim) in limits {
                    ui.colored_label(
                        style::text_color(ui, color),
                        egui::RichText::new(format!("{name}: {}", limit_text(lim))).strong(),
                    );
                }
            });
        }
        let clamp = Self::clamp(&p);
        let t0 = p.t0;
        let t_end = self.spec.t_end.max(t0 + 1e-9);
        let exact: Vec<[f64; 2]> = if p.has_exact() {
            (0..=400)
                .filter_map(|i| {
                    let t = t0 + (t_end - t0) * i as f64 / 400.0;
                    p.exact(t).map(|x| [t, x[0]])
                })
                .collect()
        } else {
            let r = reference_path(&p, t0, &p.initial, t_end);
            r.ts.iter().zip(&r.xs).map(|(t, x)| [*t, x[0]]).collect()
        };
        let paths: Vec<_> = self
            .paths()
            .into_iter()
            .map(|(_, name, color, path)| (name, color, clip(&path, clamp)))
            .collect();
        let y_name = p.vars[0].clone();
        let u = style::unit(ui);
        style::y_name_ui(ui, &y_name);
        let mut labels = Vec::new();
        let mut obstacles_at = Vec::new();
        let mut lines = vec![exact.clone()];
        lines.extend(paths.iter().map(|(_, _, (pts, _))| pts.clone()));
        let shown = style::plot(ui, "neptune", "t")
            .default_x_bounds(t0, t_end)
            .default_y_bounds(-clamp * 1.1, clamp * 1.1)
            .show(ui, |p| {
                p.set_plot_bounds(egui_plot::PlotBounds::from_min_max(
                    [t0, -clamp * 1.1],
                    [t_end, clamp * 1.1],
                ));
                p.line(
                    Line::new("exact", exact)
                        .color(ink)
                        .width(style::REFERENCE_WIDTH * u),
                );
                for (name, color, (pts, exit)) in &paths {
                    let color = *color;
                    p.line(
                        Line::new(name.as_str(), pts.clone())
                            .color(color)
                            .width(style::PATH_WIDTH * u),
                    );
                    p.points(
                        Points::new(name.as_str(), pts.clone())
                            .color(color)
                            .radius(0.6 * style::MARKER_RADIUS * u),
                    );
                    if let Some(e) = exit {
                        let text = format!("{name} diverged: off to Neptune!");
                        labels.push(exit_marker(p, *e, text, u));
                        obstacles_at.push(PlotPoint::new(e[0], e[1]));
                    }
                }
            });
        exit_labels_ui(ui, &shown.transform, &labels, &obstacles_at, &lines, u);
    }

    fn params(&mut self) -> Vec<Param<'_>> {
        let mut v = vec![Param::step_h(&mut self.spec.h, H_RANGE)];
        v.extend(self.methods.params());
        v.extend(self.ode.params());
        v
    }

    ode_plumbing!(Neptune);

    fn data(&mut self) -> Option<PlotData> {
        let vars = self.ode.problem()?.vars.clone();
        let series = self
            .paths()
            .into_iter()
            .map(|(k, _, _, p)| (k, p))
            .collect();
        Some(PlotData { vars, series })
    }

    /// λ, h, each method's stable-h limit (0 = never), and where a path diverged.
    fn readouts(&mut self) -> Vec<Readout> {
        let mut v = vec![Readout::new("h", "", self.spec.h)];
        if let Some(l) = self.lambda() {
            v.push(Readout::new("lambda_re", "", l.0));
            v.push(Readout::new("lambda_im", "", l.1));
            for (key, _, _, lim) in self.limits(l) {
                v.push(Readout::new("stable_h", key, lim));
            }
        }
        for (key, _, _, path) in self.paths() {
            if let Some(t) = path.diverged_at {
                v.push(Readout::new("diverged_at", key, t));
            }
        }
        v
    }
}

/// λ as the slide prints it: "λ = −5" for a real λ, "λ = 0 ± 1i" for a complex pair.
pub fn lambda_text(l: C) -> String {
    if l.1 == 0.0 {
        format!("λ = {}", style::fmt_signed(l.0))
    } else {
        format!(
            "λ = {} ± {}i",
            style::fmt_signed(l.0),
            style::fmt_signed(l.1.abs())
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path as FsPath;

    fn widget(h: f64) -> Neptune {
        let deck = FsPath::new(concat!(env!("CARGO_MANIFEST_DIR"), "/slides/lecture.ron"));
        let spec = format!("(ode: File(\"problems/decay.ron\"), h: {h}, t_end: 30.0)");
        Neptune::new(
            ron::from_str(&spec).unwrap(),
            crate::widgets::MadeIn::deck(Some(deck)),
        )
    }

    #[test]
    fn euler_diverges_exactly_past_two_over_lambda() {
        let mut below = widget(0.39);
        let lambda = below.lambda().unwrap();
        assert!(
            (lambda.0 + 5.0).abs() < 1e-8 && lambda.1 == 0.0,
            "{lambda:?}"
        );
        let below = below.paths().remove(0).3;
        let above = widget(0.41).paths().remove(0).3;
        assert!(below.diverged_at.is_none() && below.last()[0].abs() < 1.0);
        let (_, exit) = clip(&above, CLAMP);
        assert!(exit.is_some(), "h above 2/|λ| must leave the clamped view");
        let huge = widget(3.5).paths().remove(0).3;
        let (pts, _) = clip(&huge, CLAMP);
        assert!(pts.iter().all(|p| p[0].is_finite() && p[1].abs() <= CLAMP));
    }

    #[test]
    fn the_oscillators_eigenvalues_are_plus_minus_i() {
        let p = Problem::load(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/slides/problems/circle.ron"
        ))
        .unwrap();
        let l = dominant_eigenvalue(&p, 0.0, &p.initial).unwrap();
        assert!(l.0.abs() < 1e-9 && (l.1 - 1.0).abs() < 1e-9, "{l:?}");
    }
}
