//! Widget 1: The slope field of ẋ = f(x, t) (t–x plane) or of a system (phase plane of two of its
//! variables), with the paths of the widget's methods and the exact solution over it. Click or
//! drag to move the start point; `h` by slider or `-`/`+`; the equation's parameters by slider
//! and its expressions by typing (presenter side); the global error of each method at the end
//! of the interval is printed live.

use super::problem_files::MadeIn;

use egui_plot::{Arrows, Line, PlotPoint, PlotPoints, Points};

use super::live_ode::LiveOde;
use super::methods::{
    MAX_DRAWN_POINTS, MAX_STEP_MARKERS, MethodSet, Path, decimate, path_to, reference_path,
    truth_at,
};
use super::style::{self, fmt_num};
use super::{Param, PlotData, Readout, SlideWidget};
use crate::deck::widgets::SlopeFieldSpec;
use crate::ode::System;
use crate::ode::problem::Problem;

const H_RANGE: (f64, f64) = (0.01, 2.0);
const MAX_STEPS: usize = 20_000;

/// One method's solve reduced to what a frame needs: the full solve is used for the error
/// and then dropped; only a decimated polyline (and the step markers when few) is kept.
struct DrawnPath {
    name: String,
    color: egui::Color32,
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

/// What the paths depend on: the spec, the equation's revision, the methods switched on.
type Key = (SlopeFieldSpec, u64, Vec<bool>);
/// The slope marks depend on the equation, the view, the grid and the plane only.
type MarksKey = (u64, (f64, f64, f64, f64), usize, (usize, usize));
type Marks = (Vec<[f64; 2]>, Vec<[f64; 2]>);

/// One method's full solve: name, key, colour, path and global error at its end.
pub struct MethodPath {
    pub key: String,
    pub name: String,
    pub color: egui::Color32,
    pub path: Path,
    pub error: Option<f64>,
}

pub struct SlopeField {
    pub spec: SlopeFieldSpec,
    initial: SlopeFieldSpec,
    ode: LiveOde,
    methods: MethodSet,
    cache: Option<(Key, Computed)>,
    marks_cache: Option<(MarksKey, Marks)>,
    /// the plot's transform while the start point is dragged ([`Self::follow_drag`])
    drag_transform: Option<egui_plot::PlotTransform>,
}

/// Which two variables are drawn in the phase plane; `None` for a 1-D problem (t–x plane).
fn plane(spec: &SlopeFieldSpec, p: &Problem) -> Option<(usize, usize)> {
    if p.vars.len() < 2 {
        return None;
    }
    let find = |n: &str| p.vars.iter().position(|v| v == n);
    Some(match &spec.plot {
        Some((a, b)) => (find(a).unwrap_or(0), find(b).unwrap_or(1)),
        None => (0, 1),
    })
}

impl SlopeField {
    pub fn new(spec: SlopeFieldSpec, at: MadeIn<'_>) -> Self {
        let deck_path = at.deck_path;
        let mut ode = LiveOde::new(&spec.ode, at);
        let methods = MethodSet::new(&spec.methods, deck_path);
        let mut spec = spec;
        if let Some(p) = ode.problem() {
            fill_defaults(&mut spec, p);
        }
        Self {
            initial: spec.clone(),
            spec,
            ode,
            methods,
            cache: None,
            marks_cache: None,
            drag_transform: None,
        }
    }

    /// The start the paths on screen were solved from (after a frame: the spec's start).
    pub fn solved_start(&self) -> Option<(f64, f64)> {
        self.cache.as_ref().and_then(|(key, _)| key.0.start)
    }

    /// The start point at plot coordinates `(x, y)`, kept inside the view.
    fn set_start(&mut self, x: f64, y: f64) {
        let (x0, x1, y0, y1) = self.spec.view.unwrap_or((0.0, 1.0, 0.0, 1.0));
        self.spec.start = Some((x.clamp(x0, x1), y.clamp(y0, y1)));
    }

    /// While the start point is dragged, it follows the pointer before the frame solves: the
    /// plot's own response comes only after the paths were drawn, which put the picture a frame
    /// behind the pointer (in the browser on a software rasteriser: 143 ms from move to new
    /// paths, twice a key's). Through last frame's transform; the plot rarely moves mid-drag.
    /// True when it moved the start (the plot's response then has nothing newer to say).
    fn follow_drag(&mut self, ui: &egui::Ui) -> bool {
        let Some(transform) = self.drag_transform else {
            return false;
        };
        let (down, pos) = ui.input(|i| (i.pointer.primary_down(), i.pointer.latest_pos()));
        match (down, pos) {
            (true, Some(pos)) => {
                let p = transform.value_from_position(pos);
                self.set_start(p.x, p.y);
                true
            }
            _ => {
                self.drag_transform = None;
                false
            }
        }
    }

    /// The start point and view the deck left out (also after a reload brought the last good
    /// equation back), from the problem.
    fn ensure_defaults(&mut self) {
        if self.spec.start.is_some() && self.spec.view.is_some() {
            return;
        }
        if let Some(p) = self.ode.problem().cloned() {
            fill_defaults(&mut self.spec, &p);
            fill_defaults(&mut self.initial, &p);
        }
    }

    /// (t₀, full initial state) of the paths, from the start point.
    fn start_state(&self, p: &Problem) -> (f64, Vec<f64>) {
        let (a, b) = self.spec.start.unwrap_or((p.t0, p.initial[0]));
        match plane(&self.spec, p) {
            None => (a, vec![b]),
            Some((i, j)) => {
                let mut x = p.initial.clone();
                x[i] = a;
                x[j] = b;
                (p.t0, x)
            }
        }
    }

    /// Full paths of the shown methods with their global error at their last time, and the
    /// reference path.
    pub fn compute(&mut self) -> (Vec<MethodPath>, Path) {
        self.ensure_defaults();
        let Some(p) = self.ode.problem().cloned() else {
            return (Vec::new(), Path::default());
        };
        let s = &self.spec;
        let (t0, x0) = self.start_state(&p);
        let h = s.h.clamp(H_RANGE.0, H_RANGE.1);
        let (vx0, vx1, vy0, vy1) = s.view.unwrap_or((0.0, 1.0, 0.0, 1.0));
        let extent = (vx1 - vx0).abs().max((vy1 - vy0).abs()).max(1.0);
        let bound = 1e3 * extent;
        // `exact: false`: no reference solve and no global error (against a coarse reference
        // it would be a number that means nothing)
        let reference = if s.exact {
            reference_path(&p, t0, &x0, s.t_end.max(t0 + 1e-9))
        } else {
            Path::default()
        };
        let with_error = s.exact;
        let paths = self
            .methods
            .shown()
            .map(|m| {
                let path = path_to(&p, m.method.scheme(), t0, &x0, h, s.t_end, MAX_STEPS, bound);
                let error = if path.diverged_at.is_some() || !with_error {
                    None
                } else {
                    let t_last = *path.ts.last().unwrap_or(&t0);
                    let truth = truth_at(&p, t0, &x0, t_last, &reference);
                    let e = path
                        .last()
                        .iter()
                        .zip(&truth)
                        .map(|(a, b)| (a - b).powi(2))
                        .sum::<f64>();
                    Some(e.sqrt())
                };
                MethodPath {
                    key: m.method.key.clone(),
                    name: m.method.name.clone(),
                    color: m.color,
                    path,
                    error,
                }
            })
            .collect();
        (paths, reference)
    }

    /// Brings the draw data (paths, reference, slope marks) up to date with the spec and the
    /// equation, as a frame does before drawing; cheap when nothing changed.
    pub fn refresh(&mut self) {
        self.update();
        self.update_marks();
    }

    /// The equation, live.
    pub fn live_ode(&mut self) -> &mut LiveOde {
        &mut self.ode
    }

    /// A path as plot points: (t, x) in the t–x plane, (xᵢ, xⱼ) in the phase plane.
    fn plot_points(&self, plane: Option<(usize, usize)>, path: &Path) -> Vec<[f64; 2]> {
        match plane {
            Some((i, j)) => path.xs.iter().map(|x| [x[i], x[j]]).collect(),
            None => path
                .ts
                .iter()
                .zip(&path.xs)
                .map(|(t, x)| [*t, x[0]])
                .collect(),
        }
    }

    /// Re-solves only when the parameters changed; frames in between only draw.
    fn update(&mut self) {
        self.ensure_defaults();
        let key = (
            self.spec.clone(),
            self.ode.revision(),
            self.methods.switches(),
        );
        if self.cache.as_ref().is_some_and(|(k, _)| *k == key) {
            return;
        }
        let Some(p) = self.ode.problem().cloned() else {
            return;
        };
        let pl = plane(&self.spec, &p);
        let (paths, reference) = self.compute();
        let paths = paths
            .into_iter()
            .map(|m| {
                let pts = self.plot_points(pl, &m.path);
                DrawnPath {
                    name: m.name,
                    color: m.color,
                    line: decimate(&pts, MAX_DRAWN_POINTS),
                    markers: if pts.len() <= MAX_STEP_MARKERS {
                        pts
                    } else {
                        Vec::new()
                    },
                    error: m.error,
                    diverged_at: m.path.diverged_at,
                }
            })
            .collect();
        let reference = decimate(&self.plot_points(pl, &reference), MAX_DRAWN_POINTS);
        self.cache = Some((key, Computed { paths, reference }));
    }

    fn update_marks(&mut self) {
        let revision = self.ode.revision();
        let Some(p) = self.ode.problem().cloned() else {
            return;
        };
        let pl = plane(&self.spec, &p);
        let view = self.spec.view.unwrap_or((0.0, 1.0, 0.0, 1.0));
        let key = (revision, view, self.spec.grid, pl.unwrap_or((0, 0)));
        if self.marks_cache.as_ref().is_some_and(|(k, _)| *k == key) {
            return;
        }
        let marks = marks(&p, pl, view, self.spec.grid);
        self.marks_cache = Some((key, marks));
    }
}

/// The start point and view the deck left out, from the problem: the start at its `t0` and
/// `initial`, the view around the exact (or reference) path.
fn fill_defaults(spec: &mut SlopeFieldSpec, p: &Problem) {
    let pl = plane(spec, p);
    if spec.start.is_none() {
        spec.start = Some(match pl {
            None => (p.t0, p.initial[0]),
            Some((i, j)) => (p.initial[i], p.initial[j]),
        });
    }
    if spec.view.is_none() {
        let t_end = spec.t_end.max(p.t0 + 1e-9);
        let r = reference_path(p, p.t0, &p.initial, t_end);
        let pts: Vec<[f64; 2]> = match pl {
            None => r.ts.iter().zip(&r.xs).map(|(t, x)| [*t, x[0]]).collect(),
            Some((i, j)) => r.xs.iter().map(|x| [x[i], x[j]]).collect(),
        };
        let range = |k: usize| {
            let lo = pts.iter().map(|q| q[k]).fold(f64::INFINITY, f64::min);
            let hi = pts.iter().map(|q| q[k]).fold(f64::NEG_INFINITY, f64::max);
            if !(lo.is_finite() && hi.is_finite()) {
                return (-1.0, 1.0);
            }
            let pad = ((hi - lo) * 0.15).max(0.5);
            (lo - pad, hi + pad)
        };
        let (y0, y1) = range(1);
        spec.view = Some(match pl {
            None => (p.t0, t_end, y0, y1),
            Some(_) => {
                let (x0, x1) = range(0);
                (x0, x1, y0, y1)
            }
        });
    }
}

/// Short marks along the field, centred on a grid, their length a fixed share of a cell in
/// screen-proportional units so steep slopes don't shoot out of their cell. In a phase plane of
/// more than two variables the others are held at their initial values.
fn marks(
    p: &Problem,
    plane: Option<(usize, usize)>,
    view: (f64, f64, f64, f64),
    grid: usize,
) -> Marks {
    let (x0, x1, y0, y1) = view;
    let (w, hgt) = (x1 - x0, y1 - y0);
    let g = grid.clamp(3, 60);
    let len = 0.8 / g as f64;
    let mut origins = Vec::with_capacity(g * g);
    let mut tips = Vec::with_capacity(g * g);
    let mut state = p.initial.clone();
    let mut d = vec![0.0; p.dim()];
    for i in 0..g {
        for j in 0..g {
            let px = x0 + (i as f64 + 0.5) / g as f64 * w;
            let py = y0 + (j as f64 + 0.5) / g as f64 * hgt;
            let dir = match plane {
                None => {
                    p.rhs(px, &[py], &mut d);
                    [1.0, d[0]]
                }
                Some((a, b)) => {
                    state[a] = px;
                    state[b] = py;
                    p.rhs(p.t0, &state, &mut d);
                    [d[a], d[b]]
                }
            };
            // normalise in view units, so the mark has the same on-screen length everywhere
            let (u, v) = (dir[0] / w, dir[1] / hgt);
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

impl SlideWidget for SlopeField {
    fn ui(&mut self, ui: &mut egui::Ui) {
        style::projector_text(ui);
        let ink = style::ink(ui);
        let k = style::keys(ui);
        k.step_h(&mut self.spec.h, H_RANGE);
        ui.horizontal(|ui| {
            style::h_slider(ui, &mut self.spec.h, H_RANGE);
            self.methods.toggles_ui(ui);
            style::toggle(
                ui,
                &mut self.spec.exact,
                egui::RichText::new("exact")
                    .color(style::text_color(ui, style::EXACT))
                    .strong(),
            );
        });
        style::problems_ui(ui, self.ode.load_error(), &self.methods.errors);
        let followed = self.follow_drag(ui);
        self.update();
        self.update_marks();
        let Some((_, (origins, tips))) = &self.marks_cache else {
            return;
        };
        let Some((_, c)) = &self.cache else { return };
        let phase = self.ode.problem().and_then(|p| plane(&self.spec, p));
        let axis_names = self.ode.def().map(|d| match phase {
            Some((i, j)) => (d.vars[i].clone(), d.vars[j].clone()),
            None => ("t".to_string(), d.vars[0].clone()),
        });
        let (x_name, y_name) = axis_names.unwrap_or_default();
        let (x0, x1, y0, y1) = self.spec.view.unwrap_or((0.0, 1.0, 0.0, 1.0));
        let label = self.ode.label();
        // Errors line first, so the plot can take the rest of the height.
        ui.horizontal(|ui| {
            ui.label(egui::RichText::new(label).strong());
            if self.spec.exact && self.ode.dropped_exact().is_some() {
                // the typed equation has no exact solution of its own
                ui.label("  global error vs a fine RK4 reference (exact dropped):");
            } else if self.spec.exact {
                ui.label("  global error at the end:");
            }
            for p in &c.paths {
                let txt = match (p.error, p.diverged_at) {
                    (_, Some(t)) => format!("{} diverged at t = {}", p.name, fmt_num(t)),
                    (Some(e), None) => format!("{} {}", p.name, fmt_num(e)),
                    // no reference asked for: nothing to say but that it did not diverge
                    (None, None) if !self.spec.exact => continue,
                    (None, None) => format!("{} –", p.name),
                };
                ui.colored_label(
                    style::text_color(ui, p.color),
                    egui::RichText::new(txt).monospace(),
                );
            }
        });
        let show_exact = self.spec.exact;
        let start = self.spec.start.unwrap_or((x0, y0));
        let u = style::unit(ui);
        style::y_name_ui(ui, &y_name);
        let is_phase = phase.is_some();
        // Free by default: the plot fills its slot and shows exactly `view` (a t–x plot, or a
        // phase plane of mixed units); Equal on request for geometry.
        let aspect = self
            .spec
            .aspect
            .unwrap_or(crate::deck::widgets::Aspect::Free);
        let plot = style::with_aspect(style::plot(ui, "slope-field", &x_name), aspect)
            .default_x_bounds(x0, x1)
            .default_y_bounds(y0, y1);
        let resp = plot.show(ui, |p| {
            // `view`, with room for a marker's radius on every side: a start or end point on
            // the view's edge is drawn whole, not cut in half by the frame
            let (pad_x, pad_y) = style::marker_pad(p.transform(), (x1 - x0, y1 - y0), u);
            p.set_plot_bounds(egui_plot::PlotBounds::from_min_max(
                [x0 - pad_x, y0 - pad_y],
                [x1 + pad_x, y1 + pad_y],
            ));
            p.add(
                Arrows::new(
                    "field",
                    PlotPoints::from(origins.clone()),
                    PlotPoints::from(tips.clone()),
                )
                .color(style::thin(style::FIELD, u))
                .tip_length(if is_phase { 5.0 * u } else { 0.0 })
                .allow_hover(false),
            );
            if show_exact {
                p.line(
                    Line::new("exact", c.reference.clone())
                        .color(ink)
                        .width(style::REFERENCE_WIDTH * u),
                );
            }
            let n_paths = c.paths.len();
            for (i, path) in c.paths.iter().enumerate() {
                p.line(
                    Line::new(path.name.as_str(), path.line.clone())
                        .color(path.color)
                        .width(style::stacked_width(i, n_paths) * u),
                );
                if !path.markers.is_empty() {
                    p.points(
                        Points::new(path.name.as_str(), path.markers.clone())
                            .color(path.color)
                            .radius(style::MARKER_RADIUS * 0.7 * u),
                    );
                }
            }
            p.points(
                Points::new("start", vec![[start.0, start.1]])
                    .color(ink)
                    .radius(style::KEY_MARKER_RADIUS * u)
                    .shape(egui_plot::MarkerShape::Circle),
            );
            let r = p.response();
            if r.dragged() || r.clicked() {
                p.pointer_coordinate()
            } else {
                None
            }
        });
        self.drag_transform = resp.response.dragged().then_some(resp.transform);
        if let Some(PlotPoint { x, y }) = resp.inner.filter(|_| !followed) {
            self.set_start(x, y);
        }
    }

    fn params(&mut self) -> Vec<Param<'_>> {
        self.ensure_defaults();
        let (x0, x1, y0, y1) = self.spec.view.unwrap_or((0.0, 1.0, 0.0, 1.0));
        let mut v = vec![Param::step_h(&mut self.spec.h, H_RANGE)];
        if let Some(start) = self.spec.start.as_mut() {
            v.push(Param::f64(
                "start.0",
                "start (horizontal)",
                &mut start.0,
                x0,
                x1,
            ));
            v.push(Param::f64(
                "start.1",
                "start (vertical)",
                &mut start.1,
                y0,
                y1,
            ));
        }
        v.extend(self.methods.params());
        v.push(Param::bool("exact", "exact", &mut self.spec.exact));
        v.extend(self.ode.params());
        v
    }

    ode_plumbing!(SlopeField);

    fn data(&mut self) -> Option<PlotData> {
        let p = self.ode.problem().cloned()?;
        let (t0, x0) = self.start_state(&p);
        let (paths, reference) = self.compute();
        let mut series: Vec<(String, Path)> = paths.into_iter().map(|m| (m.key, m.path)).collect();
        if self.spec.exact {
            series.push(exact_series(&p, t0, &x0, reference));
        }
        Some(PlotData {
            vars: p.vars.clone(),
            series,
        })
    }

    /// What the errors line prints: each method's global error at the end (`error_at_end`,
    /// at `t_end`, the time the path ends) or where it diverged (`diverged_at`).
    fn readouts(&mut self) -> Vec<Readout> {
        let (paths, _) = self.compute();
        let mut v = vec![Readout::new("t_end", "", self.spec.t_end)];
        for m in paths {
            match (m.error, m.path.diverged_at) {
                (_, Some(t)) => v.push(Readout::new("diverged_at", m.key, t)),
                (Some(e), None) => v.push(Readout::new("error_at_end", m.key, e)),
                (None, None) => {}
            }
        }
        v
    }
}

/// The exact solution at the reference path's times as the series `exact`, or the fine RK4
/// reference itself as `reference` when the problem has no closed form.
pub fn exact_series(p: &Problem, t0: f64, x0: &[f64], reference: Path) -> (String, Path) {
    if !p.has_exact() {
        return ("reference".into(), reference);
    }
    let xs = reference
        .ts
        .iter()
        .map(|&t| p.exact_from(t0, x0, t).unwrap_or_default())
        .collect();
    (
        "exact".into(),
        Path {
            ts: reference.ts,
            xs,
            f_evals: 0,
            diverged_at: None,
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path as FsPath;

    fn deck() -> &'static FsPath {
        FsPath::new(concat!(env!("CARGO_MANIFEST_DIR"), "/slides/lecture.ron"))
    }

    fn widget(ron: &str) -> SlopeField {
        SlopeField::new(
            ron::from_str(ron).unwrap(),
            crate::widgets::MadeIn::deck(Some(deck())),
        )
    }

    fn forced(h: f64) -> SlopeField {
        widget(&format!(
            "(ode: File(\"problems/forced.ron\"), start: Some((0.0, 1.5)), h: {h}, t_end: 6.0, view: Some((0.0, 6.0, -1.5, 2.0)), grid: 15)"
        ))
    }

    #[test]
    fn errors_rank_by_order_and_shrink_with_h() {
        let (big, _) = forced(0.5).compute();
        let (small, _) = forced(0.25).compute();
        let e = |v: &Vec<MethodPath>, i: usize| v[i].error.unwrap();
        assert!(e(&big, 0) > e(&big, 1) && e(&big, 1) > e(&big, 2));
        // halving h: Euler's error halves, RK4's drops ~16×
        let r_euler = e(&big, 0) / e(&small, 0);
        let r_rk4 = e(&big, 2) / e(&small, 2);
        assert!((1.6..2.6).contains(&r_euler), "{r_euler}");
        assert!(r_rk4 > 10.0, "{r_rk4}");
    }

    #[test]
    fn phase_plane_circle_error_uses_exact_solution() {
        let (paths, _) = widget(
            "(ode: File(\"problems/circle.ron\"), h: 0.1, t_end: 6.283185307179586, view: Some((-2.0, 2.0, -2.0, 2.0)))",
        )
        .compute();
        // Euler's radius after 62 steps of h and a last short one to t_end = 2π: the product
        // of √(1 + Δt²) over the steps
        let euler = paths[0].path.last();
        let ts = &paths[0].path.ts;
        assert_eq!(
            *ts.last().unwrap(),
            6.283185307179586,
            "the path ends at t_end"
        );
        let want: f64 = ts
            .windows(2)
            .map(|w| (1.0 + (w[1] - w[0]).powi(2)).sqrt())
            .product();
        let r = euler[0].hypot(euler[1]);
        assert!((r - want).abs() < 1e-9, "{r} vs {want}");
        assert!((want / 1.01f64.powf(31.0) - 1.0).abs() < 1e-2);
        // the exact circle is the error's reference: RK4's error is tiny but not zero
        let rk4 = paths[2].error.unwrap();
        assert!(rk4 > 0.0 && rk4 < 1e-5, "{rk4}");
    }

    #[test]
    fn defaults_come_from_the_problem() {
        let w = widget(
            "(ode: Inline((vars: [\"x\"], rhs: [\"-x\"], initial: [0.8], t0: 1.0)), t_end: 5.0)",
        );
        assert_eq!(w.spec.start, Some((1.0, 0.8)));
        let (a, b, lo, hi) = w.spec.view.unwrap();
        assert_eq!((a, b), (1.0, 5.0));
        assert!(lo < 0.0 && hi > 0.8, "{lo} {hi}");
    }
}
