//! 1. The slope field of ẋ = f(x, t) (t–x plane) or of a 2-D system (phase plane), with the
//! Euler, midpoint, RK4 and exact paths over it. Click or drag to move the start point; `h` by
//! slider or `-`/`+`; the global error of each method at the end of the interval is printed live.

use egui_plot::{Arrows, Line, Plot, PlotPoint, PlotPoints, Points};

use super::methods::{
    MAX_DRAWN_POINTS, MAX_STEP_MARKERS, MethodId, Path, decimate, fixed_path, steps_for,
};
use super::problems::reference_path;
use super::style::{self, fmt_num};
use super::{Param, SlideWidget};
use crate::deck::widgets::{FieldKind, SlopeFieldSpec};
use crate::ode::System;

const H_RANGE: (f64, f64) = (0.01, 2.0);
const MAX_STEPS: usize = 20_000;

/// One method's solve reduced to what a frame needs: the full solve is used for the error
/// and then dropped; only a decimated polyline (and the step markers when few) is kept.
struct DrawnPath {
    method: MethodId,
    line: Vec<[f64; 2]>,
    /// every step, only when there are at most MAX_STEP_MARKERS of them
    markers: Vec<[f64; 2]>,
    error: Option<f64>,
    diverged_at: Option<f64>,
}

struct Computed {
    paths: Vec<DrawnPath>,
    reference: Vec<[f64; 2]>,
}

/// The slope marks, keyed by what they depend on (not the start point or h).
type MarksKey = (FieldKind, (f64, f64, f64, f64), usize);
type Marks = (Vec<[f64; 2]>, Vec<[f64; 2]>);

pub struct SlopeField {
    pub spec: SlopeFieldSpec,
    initial: SlopeFieldSpec,
    cache: Option<(SlopeFieldSpec, Computed)>,
    marks_cache: Option<(MarksKey, Marks)>,
}

impl SlopeField {
    pub fn new(spec: SlopeFieldSpec) -> Self {
        Self {
            initial: spec.clone(),
            spec,
            cache: None,
            marks_cache: None,
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

    /// Paths of the shown methods with their global error at their last time, and the
    /// reference path.
    pub fn compute(&self) -> (Vec<(MethodId, Path, Option<f64>)>, Path) {
        match self.spec.field {
            FieldKind::OneD(f) => self.compute_with(&f.system(), |t0, x0, t| {
                f.exact(t0, x0[0], t).map(|x| vec![x])
            }),
            FieldKind::Phase(f) => self.compute_with(&f.system(), |_t0, x0, t| {
                f.exact([x0[0], x0[1]], t).map(|p| p.to_vec())
            }),
        }
    }

    fn compute_with<S: System>(
        &self,
        sys: &S,
        exact: impl Fn(f64, &[f64], f64) -> Option<Vec<f64>>,
    ) -> (Vec<(MethodId, Path, Option<f64>)>, Path) {
        let s = &self.spec;
        let (t0, x0) = match s.field {
            FieldKind::OneD(_) => (s.start.0, vec![s.start.1]),
            FieldKind::Phase(_) => (0.0, vec![s.start.0, s.start.1]),
        };
        let h = s.h.clamp(H_RANGE.0, H_RANGE.1);
        let extent = (s.view.1 - s.view.0)
            .abs()
            .max((s.view.3 - s.view.2).abs())
            .max(1.0);
        let bound = 1e3 * extent;
        let n = steps_for(t0, s.t_end, h, MAX_STEPS);
        let reference = reference_path(sys, t0, &x0, s.t_end.max(t0 + 1e-9));
        let ref_end = *reference.ts.last().unwrap_or(&t0);
        let paths = self
            .shown()
            .into_iter()
            .map(|m| {
                let p = fixed_path(sys, m.scheme().unwrap(), t0, &x0, h, n, bound);
                let err = if p.diverged_at.is_some() {
                    None
                } else {
                    let t_last = *p.ts.last().unwrap();
                    // no closed form: the reference solve, reused when it ends where the path does
                    let truth = exact(t0, &x0, t_last).unwrap_or_else(|| {
                        if (t_last - ref_end).abs() <= 1e-9 * t_last.abs().max(1.0) {
                            reference.last().to_vec()
                        } else {
                            reference_path(sys, t0, &x0, t_last).last().to_vec()
                        }
                    });
                    let e = p
                        .last()
                        .iter()
                        .zip(&truth)
                        .map(|(a, b)| (a - b).powi(2))
                        .sum::<f64>();
                    Some(e.sqrt())
                };
                (m, p, err)
            })
            .collect();
        (paths, reference)
    }

    /// A path as plot points: (t, x) in the t–x plane, (x, y) in the phase plane.
    fn plot_points(&self, path: &Path) -> Vec<[f64; 2]> {
        if matches!(self.spec.field, FieldKind::Phase(_)) {
            path.xs.iter().map(|x| [x[0], x[1]]).collect()
        } else {
            path.ts
                .iter()
                .zip(&path.xs)
                .map(|(t, x)| [*t, x[0]])
                .collect()
        }
    }

    /// Re-solves only when the parameters changed; frames in between only draw.
    fn update(&mut self) {
        if self.cache.as_ref().is_some_and(|(s, _)| *s == self.spec) {
            return;
        }
        let (paths, reference) = self.compute();
        let paths = paths
            .into_iter()
            .map(|(method, path, error)| {
                let pts = self.plot_points(&path);
                DrawnPath {
                    method,
                    line: decimate(&pts, MAX_DRAWN_POINTS),
                    markers: if pts.len() <= MAX_STEP_MARKERS {
                        pts
                    } else {
                        Vec::new()
                    },
                    error,
                    diverged_at: path.diverged_at,
                }
            })
            .collect();
        let reference = decimate(&self.plot_points(&reference), MAX_DRAWN_POINTS);
        self.cache = Some((self.spec.clone(), Computed { paths, reference }));
    }

    fn update_marks(&mut self) {
        let s = &self.spec;
        let key = (s.field, s.view, s.grid);
        if self.marks_cache.as_ref().is_some_and(|(k, _)| *k == key) {
            return;
        }
        self.marks_cache = Some((key, self.marks()));
    }

    /// Short marks along the field, centred on a grid, their length a fixed share of a cell
    /// in screen-proportional units so steep slopes don't shoot out of their cell.
    fn marks(&self) -> (Vec<[f64; 2]>, Vec<[f64; 2]>) {
        let (x0, x1, y0, y1) = self.spec.view;
        let (w, hgt) = (x1 - x0, y1 - y0);
        let g = self.spec.grid.clamp(3, 60);
        let len = 0.8 / g as f64;
        let mut origins = Vec::with_capacity(g * g);
        let mut tips = Vec::with_capacity(g * g);
        for i in 0..g {
            for j in 0..g {
                let px = x0 + (i as f64 + 0.5) / g as f64 * w;
                let py = y0 + (j as f64 + 0.5) / g as f64 * hgt;
                let d = match self.spec.field {
                    FieldKind::OneD(f) => [1.0, f.f(px, py)],
                    FieldKind::Phase(f) => f.f([px, py]),
                };
                // normalise in view units, so the mark has the same on-screen length everywhere
                let (u, v) = (d[0] / w, d[1] / hgt);
                let n = u.hypot(v);
                if !(n.is_finite() && n > 0.0) {
                    continue;
                }
                let (dx, dy) = (u / n * len * w * 0.5, v / n * len * hgt * 0.5);
                origins.push([px - dx, py - dy]);
                tips.push([px + dx, py + dy]);
            }
        }
        (origins, tips)
    }
}

impl SlideWidget for SlopeField {
    fn ui(&mut self, ui: &mut egui::Ui) {
        style::projector_text(ui);
        let ink = style::ink(ui);
        let k = style::keys(ui);
        k.step_h(&mut self.spec.h, H_RANGE);
        ui.horizontal(|ui| {
            style::h_slider(ui, &mut self.spec.h, H_RANGE);
            style::method_toggles(
                ui,
                [
                    (&mut self.spec.euler, MethodId::Euler),
                    (&mut self.spec.midpoint, MethodId::Midpoint),
                    (&mut self.spec.rk4, MethodId::Rk4),
                    (&mut self.spec.exact, MethodId::Exact),
                ],
            );
        });
        self.update();
        self.update_marks();
        let Some((_, (origins, tips))) = &self.marks_cache else {
            return;
        };
        let phase = matches!(self.spec.field, FieldKind::Phase(_));
        let Some((_, c)) = &self.cache else { return };
        let (x0, x1, y0, y1) = self.spec.view;
        let label = match self.spec.field {
            FieldKind::OneD(f) => f.label(),
            FieldKind::Phase(f) => f.label(),
        };
        // Errors line first, so the plot can take the rest of the height.
        ui.horizontal(|ui| {
            ui.label(egui::RichText::new(label).strong());
            ui.label("  global error at the end:");
            for p in &c.paths {
                let m = p.method;
                let txt = match (p.error, p.diverged_at) {
                    (_, Some(t)) => format!("{} diverged at t = {}", m.name(), fmt_num(t)),
                    (Some(e), None) => format!("{} {}", m.name(), fmt_num(e)),
                    (None, None) => format!("{} –", m.name()),
                };
                ui.colored_label(style::method_color(m), egui::RichText::new(txt).monospace());
            }
        });
        let show_exact = self.spec.exact;
        let start = self.spec.start;
        let plot = Plot::new("slope-field")
            .allow_drag(false)
            .allow_zoom(false)
            .allow_scroll(false)
            .allow_boxed_zoom(false)
            .allow_double_click_reset(false)
            .show_x(false)
            .show_y(false)
            .x_axis_label(if phase { "x" } else { "t" })
            .y_axis_label(if phase { "y" } else { "x" })
            .default_x_bounds(x0, x1)
            .default_y_bounds(y0, y1);
        let plot = if phase { plot.data_aspect(1.0) } else { plot };
        let resp = plot.show(ui, |p| {
            p.set_plot_bounds(egui_plot::PlotBounds::from_min_max([x0, y0], [x1, y1]));
            p.add(
                Arrows::new(
                    "field",
                    PlotPoints::from(origins.clone()),
                    PlotPoints::from(tips.clone()),
                )
                .color(style::FIELD)
                .tip_length(if phase { 5.0 } else { 0.0 })
                .allow_hover(false),
            );
            if show_exact {
                p.line(
                    Line::new("exact", c.reference.clone())
                        .color(ink)
                        .width(2.0),
                );
            }
            for path in &c.paths {
                let (m, color) = (path.method, style::method_color(path.method));
                p.line(
                    Line::new(m.name(), path.line.clone())
                        .color(color)
                        .width(style::PATH_WIDTH),
                );
                if !path.markers.is_empty() {
                    p.points(
                        Points::new(m.name(), path.markers.clone())
                            .color(color)
                            .radius(3.5),
                    );
                }
            }
            p.points(
                Points::new("start", vec![[start.0, start.1]])
                    .color(ink)
                    .radius(7.0)
                    .shape(egui_plot::MarkerShape::Circle),
            );
            let r = p.response();
            if r.dragged() || r.clicked() {
                p.pointer_coordinate()
            } else {
                None
            }
        });
        if let Some(PlotPoint { x, y }) = resp.inner {
            self.spec.start = (x.clamp(x0, x1), y.clamp(y0, y1));
        }
    }

    fn params(&mut self) -> Vec<Param<'_>> {
        let (x0, x1, y0, y1) = self.spec.view;
        vec![
            Param::f64_log("h", "step h", &mut self.spec.h, H_RANGE.0, H_RANGE.1),
            Param::f64(
                "start.0",
                "start (horizontal)",
                &mut self.spec.start.0,
                x0,
                x1,
            ),
            Param::f64(
                "start.1",
                "start (vertical)",
                &mut self.spec.start.1,
                y0,
                y1,
            ),
            Param::bool("euler", "Euler", &mut self.spec.euler),
            Param::bool("midpoint", "Midpoint", &mut self.spec.midpoint),
            Param::bool("rk4", "RK4", &mut self.spec.rk4),
            Param::bool("exact", "exact", &mut self.spec.exact),
        ]
    }

    spec_plumbing!(SlopeField);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::deck::widgets::{Field1, Field2};

    fn spec(h: f64) -> SlopeFieldSpec {
        SlopeFieldSpec {
            field: FieldKind::OneD(Field1::Forced),
            start: (0.0, 1.5),
            h,
            t_end: 6.0,
            view: (0.0, 6.0, -1.5, 2.0),
            euler: true,
            midpoint: true,
            rk4: true,
            exact: true,
            grid: 15,
        }
    }

    #[test]
    fn errors_rank_by_order_and_shrink_with_h() {
        let (big, _) = SlopeField::new(spec(0.5)).compute();
        let (small, _) = SlopeField::new(spec(0.25)).compute();
        let e = |v: &Vec<(MethodId, Path, Option<f64>)>, i: usize| v[i].2.unwrap();
        assert!(e(&big, 0) > e(&big, 1) && e(&big, 1) > e(&big, 2));
        // halving h: Euler's error halves, RK4's drops ~16×
        let r_euler = e(&big, 0) / e(&small, 0);
        let r_rk4 = e(&big, 2) / e(&small, 2);
        assert!((1.6..2.6).contains(&r_euler), "{r_euler}");
        assert!(r_rk4 > 10.0, "{r_rk4}");
    }

    #[test]
    fn phase_plane_circle_error_uses_exact_solution() {
        let mut s = spec(0.1);
        s.field = FieldKind::Phase(Field2::Circle);
        s.start = (1.0, 0.0);
        s.t_end = std::f64::consts::TAU;
        s.view = (-2.0, 2.0, -2.0, 2.0);
        let (paths, _) = SlopeField::new(s).compute();
        // Euler's radius after ~63 steps: (1 + h²)^(n/2)
        let euler = paths[0].1.last();
        let n = paths[0].1.ts.len() - 1;
        let r = euler[0].hypot(euler[1]);
        assert!((r - 1.01f64.powf(n as f64 / 2.0)).abs() < 1e-9);
    }
}
