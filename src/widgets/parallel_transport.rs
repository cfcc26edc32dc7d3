//! Widget 10, the lecture's exercise: the same path twice, fish oriented by the Frenet frame (left)
//! and by the parallel-transport frame (right), with one transport step spelled out:
//! R takes the old heading to the new one, q_new = normalize(q(R) · q_old). The frames come
//! from `school::frames`, whose transport step is the school's own, so the slide teaches what
//! the scene runs. `[`/`]` step along the path; drag a view to turn it.

use egui::{Color32, Pos2, Rect, Sense, Stroke, pos2, vec2};
use glam::{Mat3, Quat, Vec3};

use super::style::{self, fmt_num};
use super::{Param, Readout, SlideWidget};
use crate::deck::widgets::ParallelTransportSpec;
use crate::deck::widgets::parallel_transport::{FISH_RANGE, PITCH_RANGE_DEG, PathShape};
use crate::school::frames::{self, FrameSample, TransportStep};
use crate::school::{FISH_FORWARD, FISH_UP};

/// Body colours of the two fish kinds; the dorsal fin is the theme's ink (red when the fish's
/// back points downwards), so "upside down" reads at a glance on either theme.
pub const FRENET: Color32 = style::EULER;
pub const TRANSPORTED: Color32 = style::RK4;
const UNDEFINED: Color32 = Color32::from_gray(150);

/// Points the path line is drawn with (the fish sit on a coarser sampling: one per step).
const LINE_SAMPLES: usize = 240;

pub struct ParallelTransport {
    pub spec: ParallelTransportSpec,
    initial: ParallelTransportSpec,
    cache: Option<((PathShape, usize), Computed)>,
}

struct Computed {
    frames: Vec<FrameSample>,
    line: Vec<Vec3>,
    frenet_flips: Vec<usize>,
}

impl ParallelTransport {
    pub fn new(spec: ParallelTransportSpec) -> Self {
        Self {
            initial: spec.clone(),
            spec,
            cache: None,
        }
    }

    fn fish_count(&self) -> usize {
        self.spec.fish.clamp(FISH_RANGE.0, FISH_RANGE.1)
    }

    /// The frames the widget draws (one per fish), for tests and the step panel.
    pub fn frames(&mut self) -> &[FrameSample] {
        &self.computed().frames
    }

    /// Fish indices where the Frenet fish's up turns by more than 90° from the previous
    /// defined one.
    pub fn frenet_flips(&mut self) -> &[usize] {
        &self.computed().frenet_flips
    }

    /// The transport step shown: from fish `step` to fish `step + 1`.
    pub fn shown_step(&mut self) -> TransportStep {
        let n = self.fish_count();
        let i = self.spec.step.min(n - 2);
        let f = self.frames();
        frames::transport_step(f[i].transported, f[i + 1].tangent)
    }

    fn computed(&mut self) -> &Computed {
        let key = (self.spec.path, self.fish_count());
        if self.cache.as_ref().is_none_or(|(k, _)| *k != key) {
            let frames = frames::frames_along(&key.0.sample(key.1));
            let frenet_flips = frames::flips(frames.iter().map(FrameSample::frenet_up));
            let line = key.0.sample(LINE_SAMPLES);
            self.cache = Some((
                key,
                Computed {
                    frames,
                    line,
                    frenet_flips,
                },
            ));
        }
        &self.cache.as_ref().expect("just filled").1
    }
}

/// An orthographic view: turn by yaw about y, tilt by pitch, fitted to a rectangle.
struct View {
    view_from_world: Mat3,
    centre_world: Vec3,
    centre_px: Pos2,
    px_per_m: f32,
}

impl View {
    fn fit(points: &[Vec3], yaw_deg: f64, pitch_deg: f64, rect: Rect) -> Self {
        let view_from_world = Mat3::from_rotation_x(pitch_deg.to_radians() as f32)
            * Mat3::from_rotation_y(yaw_deg.to_radians() as f32);
        let (mut lo, mut hi) = (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN));
        for p in points {
            let v = view_from_world * *p;
            lo = lo.min(v);
            hi = hi.max(v);
        }
        let extent = (hi - lo).max(Vec3::splat(1e-3));
        let px_per_m = (rect.width() / extent.x).min(rect.height() / extent.y) * 0.82;
        let centre_view = (lo + hi) * 0.5;
        Self {
            view_from_world,
            centre_world: view_from_world.transpose() * centre_view,
            centre_px: rect.center(),
            px_per_m,
        }
    }

    /// Screen position and depth (larger is nearer the viewer).
    fn project(&self, p: Vec3) -> (Pos2, f32) {
        let v = self.view_from_world * (p - self.centre_world);
        (
            pos2(
                self.centre_px.x + v.x * self.px_per_m,
                self.centre_px.y - v.y * self.px_per_m,
            ),
            v.z,
        )
    }
}

/// A fish glyph: a flat body (nose forward) and a dorsal fin on its back, so its up shows.
fn fish_shapes(
    view: &View,
    at: Vec3,
    q: Option<Quat>,
    len_m: f32,
    body: Color32,
    ink: Color32,
    unit: f32,
) -> Vec<egui::Shape> {
    let Some(q) = q else {
        let (c, _) = view.project(at);
        return vec![egui::Shape::circle_stroke(
            c,
            len_m * view.px_per_m * 0.35,
            Stroke::new(1.5 * unit, UNDEFINED),
        )];
    };
    let (f, u) = (q * FISH_FORWARD, q * FISH_UP);
    // the back in red when it points below the horizon: a flip shows as a change of colour
    let ink = if u.y < -0.05 { style::DIVERGED } else { ink };
    let s = f.cross(u);
    let p = |v: Vec3| view.project(at + v * len_m).0;
    let nose = p(f * 0.6);
    let tail_l = p(-f * 0.5 + s * 0.28);
    let tail_r = p(-f * 0.5 - s * 0.28);
    let fin = vec![p(f * 0.25), p(u * 0.6 - f * 0.1), p(-f * 0.35)];
    vec![
        egui::Shape::convex_polygon(vec![nose, tail_l, tail_r], body, Stroke::new(unit, body)),
        egui::Shape::convex_polygon(fin, ink, Stroke::NONE),
        egui::Shape::line_segment([p(Vec3::ZERO), p(u * 0.6)], Stroke::new(1.5 * unit, ink)),
    ]
}

fn view_ui(
    ui: &mut egui::Ui,
    spec: &mut ParallelTransportSpec,
    c: &Computed,
    rect: Rect,
    frenet: bool,
    step: usize,
) {
    let ink = style::ink(ui);
    let resp = ui.interact(rect, ui.scope_id().with(("pt-view", frenet)), Sense::drag());
    if resp.dragged() {
        let d = resp.drag_delta();
        spec.yaw_deg += d.x as f64 * 0.4;
        spec.pitch_deg =
            (spec.pitch_deg + d.y as f64 * 0.4).clamp(PITCH_RANGE_DEG.0, PITCH_RANGE_DEG.1);
    }
    let painter = ui.painter_at(rect);
    painter.rect_stroke(
        rect,
        8.0,
        ui.visuals().widgets.noninteractive.bg_stroke,
        egui::StrokeKind::Inside,
    );
    let u = style::unit(ui);
    // the panel's title takes the top line; the fish are fitted below it, never over it
    let title_h = ui.text_style_height(&egui::TextStyle::Body) + 16.0 * u;
    let fish_rect = Rect::from_min_max(rect.min + vec2(0.0, title_h), rect.max).shrink(8.0 * u);
    let view = View::fit(&c.line, spec.yaw_deg, spec.pitch_deg, fish_rect);
    let line: Vec<Pos2> = c.line.iter().map(|p| view.project(*p).0).collect();
    painter.add(egui::Shape::line(
        line,
        Stroke::new(style::REFERENCE_WIDTH * u, style::FIELD),
    ));
    let len_m = {
        let total: f32 = c.line.windows(2).map(|w| (w[1] - w[0]).length()).sum();
        (total / c.frames.len() as f32 * 1.1).min(1.5)
    };
    let body = if frenet { FRENET } else { TRANSPORTED };
    let mut order: Vec<usize> = (0..c.frames.len()).collect();
    order.sort_by(|&a, &b| {
        let za = view.project(c.frames[a].position).1;
        let zb = view.project(c.frames[b].position).1;
        za.total_cmp(&zb)
    });
    for i in order {
        let s = &c.frames[i];
        let q = if frenet {
            s.frenet
        } else {
            Some(s.transported)
        };
        let shown = i == step || i == step + 1;
        let len = if shown { len_m * 1.5 } else { len_m };
        for shape in fish_shapes(&view, s.position, q, len, body, ink, u) {
            painter.add(shape);
        }
        if shown {
            let (c, _) = view.project(s.position);
            painter.circle_stroke(
                c,
                len * view.px_per_m * 0.75,
                Stroke::new(1.5 * u, style::ink(ui).gamma_multiply(0.6)),
            );
        }
    }
    if frenet {
        for &i in &c.frenet_flips {
            let (at, _) = view.project(c.frames[i].position);
            painter.circle_stroke(
                at,
                len_m * view.px_per_m,
                Stroke::new(2.5 * u, style::DIVERGED),
            );
            painter.text(
                at + vec2(0.0, -len_m * view.px_per_m * 1.2),
                egui::Align2::CENTER_BOTTOM,
                "flip",
                egui::TextStyle::Body.resolve(ui.style()),
                style::text_color(ui, style::DIVERGED),
            );
        }
    }
    let title = if frenet {
        "Frenet frame: up = T × N"
    } else {
        "parallel transport: q ← normalize(q(R) q)"
    };
    painter.text(
        rect.left_top() + vec2(10.0, 8.0) * u,
        egui::Align2::LEFT_TOP,
        title,
        egui::TextStyle::Body.resolve(ui.style()),
        style::text_color(ui, body),
    );
}

fn vec_text(v: Vec3) -> String {
    format!("({:+.2}, {:+.2}, {:+.2})", v.x, v.y, v.z)
}

fn quat_text(q: Quat) -> String {
    format!("({:+.2}, {:+.2}, {:+.2}, {:+.2})", q.w, q.x, q.y, q.z)
}

/// The rotation line: axis and angle of R, or, on a straight stretch (t_old ∥ t_new), that R
/// is the identity: the cross product vanishes, so there is no axis to print.
pub fn rotation_text(step: &TransportStep) -> String {
    match step.axis {
        Some(axis) => format!(
            "R: axis t_old×t_new {}, angle acos(t_old·t_new) = {:.1}°",
            vec_text(axis),
            step.angle_rad.to_degrees()
        ),
        None => "R = identity: t_old ∥ t_new (straight), t_old×t_new = 0, no axis".into(),
    }
}

impl SlideWidget for ParallelTransport {
    fn ui(&mut self, ui: &mut egui::Ui) {
        style::projector_text(ui);
        ui.set_max_width(ui.available_width());
        let n = self.fish_count();
        let k = style::keys(ui);
        if k.forward {
            self.spec.step += 1;
        }
        if k.back {
            self.spec.step = self.spec.step.saturating_sub(1);
        }
        self.spec.step = self.spec.step.min(n - 2);
        ui.horizontal_wrapped(|ui| {
            for shape in PathShape::ALL {
                if style::choice(ui, self.spec.path == shape, shape.label()) {
                    self.spec.path = shape;
                    self.spec.step = 0;
                }
            }
            style::slider(ui, &mut self.spec.step, 0..=n - 2, "step  [ ]", false);
        });
        let step = self.shown_step();
        let i = self.spec.step;
        // the five readout lines below the views, with their spacing: they must end above the
        // slot's bottom (the footer), not under it
        let line_h =
            ui.text_style_height(&egui::TextStyle::Monospace) + ui.spacing().item_spacing.y;
        let text_h = 5.0 * line_h + ui.spacing().item_spacing.y;
        let avail = ui.available_rect_before_wrap();
        let views_h = (avail.height() - text_h).max(80.0);
        let gap = ui.spacing().item_spacing.x;
        let w = (avail.width() - gap) / 2.0;
        let left = Rect::from_min_size(avail.min, vec2(w, views_h));
        let right = Rect::from_min_size(avail.min + vec2(w + gap, 0.0), vec2(w, views_h));
        self.computed();
        let (spec, c) = (&mut self.spec, &self.cache.as_ref().expect("computed").1);
        view_ui(ui, spec, c, left, true, i);
        view_ui(ui, spec, c, right, false, i);
        ui.allocate_rect(
            Rect::from_min_size(avail.min, vec2(avail.width(), views_h)),
            Sense::hover(),
        );
        let mono = |ui: &mut egui::Ui, s: String| {
            ui.add(egui::Label::new(egui::RichText::new(s).monospace()).extend());
        };
        mono(
            ui,
            format!(
                "step {i}→{}: t_old {}  t_new {}",
                i + 1,
                vec_text(step.heading_old),
                vec_text(step.heading_new),
            ),
        );
        mono(ui, rotation_text(&step));
        mono(
            ui,
            format!(
                "q(R) = {}   q_old = {}",
                quat_text(step.q_rotation),
                quat_text(step.q_old)
            ),
        );
        mono(
            ui,
            format!("q_new = normalize(q(R)·q_old) = {}", quat_text(step.q_new)),
        );
        let flips = self.frenet_flips().len();
        ui.label(format!(
            "Frenet flips: {flips}   ·   transported flips: 0   ·   curvature here {} /m",
            fmt_num(self.frames()[i].curvature_per_m as f64)
        ));
    }

    fn params(&mut self) -> Vec<Param<'_>> {
        let s = &mut self.spec;
        vec![
            Param::usize("step", "step", &mut s.step, 0, FISH_RANGE.1 - 2),
            Param::usize("fish", "fish", &mut s.fish, FISH_RANGE.0, FISH_RANGE.1),
            Param::f64("yaw_deg", "yaw (°)", &mut s.yaw_deg, -180.0, 180.0),
            Param::f64(
                "pitch_deg",
                "pitch (°)",
                &mut s.pitch_deg,
                PITCH_RANGE_DEG.0,
                PITCH_RANGE_DEG.1,
            ),
        ]
    }

    spec_plumbing!(ParallelTransport);

    /// The step panel's numbers: `step`, `t_old_*`, `t_new_*`, `angle_deg`, `axis_*` (absent
    /// on a straight step, where none is printed), `q_rotation_*`, `q_old_*`, `q_new_*`
    /// (w, x, y, z), `frenet_flips` and `curvature_per_m` at the step.
    fn readouts(&mut self) -> Vec<Readout> {
        let n = self.fish_count();
        let i = self.spec.step.min(n - 2);
        let step = self.shown_step();
        let mut v = vec![Readout::new("step", "", i as f64)];
        let mut vec3 = |name: &str, x: Vec3| {
            for (c, value) in ["x", "y", "z"].into_iter().zip(x.to_array()) {
                v.push(Readout::new(format!("{name}_{c}"), "", f64::from(value)));
            }
        };
        vec3("t_old", step.heading_old);
        vec3("t_new", step.heading_new);
        if let Some(axis) = step.axis {
            vec3("axis", axis);
        }
        v.push(Readout::new(
            "angle_deg",
            "",
            f64::from(step.angle_rad).to_degrees(),
        ));
        for (name, q) in [
            ("q_rotation", step.q_rotation),
            ("q_old", step.q_old),
            ("q_new", step.q_new),
        ] {
            for (c, value) in ["w", "x", "y", "z"].into_iter().zip([q.w, q.x, q.y, q.z]) {
                v.push(Readout::new(format!("{name}_{c}"), "", f64::from(value)));
            }
        }
        v.push(Readout::new(
            "frenet_flips",
            "",
            self.frenet_flips().len() as f64,
        ));
        v.push(Readout::new(
            "curvature_per_m",
            "",
            f64::from(self.frames()[i].curvature_per_m),
        ));
        v
    }
}
