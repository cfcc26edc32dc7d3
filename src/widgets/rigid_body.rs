//! Widget 9: A tumbling box near its intermediate axis (the Dzhanibekov flip), integrated by
//! [`crate::rigid`] from the 13-number state X = (x, q, P, L) with Ẋ = (P/M, ½ ω q, F, τ) and
//! ω = R I_body⁻¹ Rᵀ L (ERRATA 2, 4), by Euler, midpoint, RK4 and symplectic Euler side by
//! side, each with its energy and |L|. Below: the drawn box's inertia exactly from its mesh
//! (Mirtich 1996) vs from n³ points, with the relative error.
//!
//! This module only drives and draws: the state, right-hand side, integrators and inertia
//! formulas are the rigid-body core's, the same code the water scene's floating bodies use.

use glam::{DMat3, DVec3};

use super::style::{self, fmt_num};
use super::{Param, Readout, SlideWidget};
use crate::deck::widgets::RigidBodySpec;
use crate::rigid::{
    Integrator, MassProperties, NoForces, RigidBody, TriMesh, mirtich, point_lattice,
};

/// Steps a frame may take per method; beyond it the view lags rather than stalls the UI.
const MAX_STEPS_PER_FRAME: usize = 1000;
const T_MAX: f64 = 600.0;
const N_MAX: usize = 40;

/// One integrator's body and its values at t = 0.
pub struct Run {
    pub body: RigidBody,
    pub e0: f64,
    pub l0: f64,
}

impl Run {
    /// Kinetic energy relative to its initial value.
    pub fn energy_ratio(&self) -> f64 {
        self.body.energy() / self.e0
    }

    /// |L| relative to its initial value.
    pub fn momentum_ratio(&self) -> f64 {
        self.body.angular_momentum().length() / self.l0
    }
}

/// The drawn box's inertia at mass 1: exactly from its mesh and from n³ points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InertiaComparison {
    /// full side lengths of the drawn box
    pub dims: DVec3,
    pub n: usize,
    /// diagonal of I (kg m², mass 1), Mirtich
    pub exact: DVec3,
    /// diagonal of I (kg m², mass 1), n³ point lattice
    pub points: DVec3,
}

impl InertiaComparison {
    pub fn new(dims: DVec3, n: usize) -> Self {
        let mesh = TriMesh::centred_box(dims);
        let unit_mass = |p: MassProperties| {
            let i = p.with_density(1.0 / p.mass).inertia;
            DVec3::new(i.x_axis.x, i.y_axis.y, i.z_axis.z)
        };
        let n = n.clamp(1, N_MAX);
        Self {
            dims,
            n,
            exact: unit_mass(mirtich(&mesh)),
            points: unit_mass(point_lattice(&mesh, n)),
        }
    }

    /// Largest relative error of the lattice's principal moments.
    pub fn relative_error(&self) -> f64 {
        ((self.points - self.exact) / self.exact)
            .abs()
            .max_element()
    }
}

/// Sides of a box whose principal moments are proportional to `i` (a box of mass m has
/// a² = 6 (I_y + I_z − I_x) / m, …); diag(1, 2, 3) is a flat plate, so every side is kept at
/// least 30 % of the longest to stay visible as a box.
pub fn box_dims(i: DVec3) -> DVec3 {
    let d = DVec3::new(i.y + i.z - i.x, i.x + i.z - i.y, i.x + i.y - i.z)
        .max(DVec3::splat(0.02))
        .powf(0.5);
    d.max(DVec3::splat(0.3 * d.max_element()))
}

pub struct RigidBodyView {
    pub spec: RigidBodySpec,
    initial: RigidBodySpec,
    runs: Vec<Run>,
    /// (inertia, ω₀, h, methods) the runs were started with.
    key: Option<((f64, f64, f64), (f64, f64, f64), f64, Vec<Integrator>)>,
    inertia_cache: Option<InertiaComparison>,
}

impl RigidBodyView {
    pub fn new(spec: RigidBodySpec) -> Self {
        Self {
            initial: spec.clone(),
            spec,
            runs: Vec::new(),
            key: None,
            inertia_cache: None,
        }
    }

    /// Principal moments, kept positive so I⁻¹ exists.
    pub fn inertia(&self) -> DVec3 {
        let (a, b, c) = self.spec.inertia;
        DVec3::new(a, b, c).max(DVec3::splat(1e-6))
    }

    fn step_h(&self) -> f64 {
        if self.spec.h.is_finite() {
            self.spec.h.clamp(1e-3, 0.5)
        } else {
            0.02
        }
    }

    /// Advances every method to `spec.t` (restarting if time went backwards or inputs changed),
    /// at most MAX_STEPS_PER_FRAME steps each.
    pub fn advance(&mut self) {
        let key = (
            self.spec.inertia,
            self.spec.omega0,
            self.spec.h,
            self.spec.methods.clone(),
        );
        let h = self.step_h();
        let target = if self.spec.t.is_finite() {
            self.spec.t.clamp(0.0, T_MAX)
        } else {
            0.0
        };
        let went_back = self.runs.iter().any(|r| r.body.time > target + 1e-9);
        if self.key.as_ref() != Some(&key) || went_back {
            let (a, b, c) = self.spec.omega0;
            let omega0 = DVec3::new(a, b, c);
            let omega0 = if omega0.is_finite() { omega0 } else { DVec3::Y };
            let inertia = self.inertia();
            self.runs = self
                .spec
                .methods
                .iter()
                .map(|&m| {
                    let body = RigidBody::free_spinning(inertia, omega0, m);
                    Run {
                        e0: body.energy(),
                        l0: body.angular_momentum().length(),
                        body,
                    }
                })
                .collect();
            self.key = Some(key);
        }
        for r in &mut self.runs {
            let mut steps = 0;
            while r.body.time + h <= target + 1e-9 && steps < MAX_STEPS_PER_FRAME {
                r.body.step(h, &NoForces);
                steps += 1;
            }
        }
    }

    pub fn runs(&self) -> &[Run] {
        &self.runs
    }

    /// Mirtich vs n³ points for the drawn box, recomputed only when the box or n changes.
    pub fn inertia_comparison(&mut self) -> InertiaComparison {
        let dims = box_dims(self.inertia());
        let n = self.spec.n.clamp(1, N_MAX);
        match self.inertia_cache {
            Some(c) if c.dims == dims && c.n == n => c,
            _ => {
                let c = InertiaComparison::new(dims, n);
                self.inertia_cache = Some(c);
                c
            }
        }
    }
}

/// The camera the boxes are seen from: looking down 27° onto the world, turned 35° about the
/// vertical, so a box in most orientations shows three faces (top and two sides) at once.
fn view_from_world() -> DMat3 {
    DMat3::from_rotation_x(27f64.to_radians()) * DMat3::from_rotation_y(-35f64.to_radians())
}

/// The fixed light, in view space (z towards the viewer): over the viewer's left shoulder, so
/// the three faces a box shows get three different shades and none goes dark.
fn light_in_view() -> DVec3 {
    DVec3::new(-0.3, 0.4, 0.87).normalize()
}

/// One visible face of a drawn box, in screen points, back to front.
#[derive(Debug, Clone, PartialEq)]
pub struct BoxFace {
    pub corners: [egui::Pos2; 4],
    pub color: egui::Color32,
    /// Lambert term max(0, n·l) of the face (before the ambient floor).
    pub lambert: f64,
}

/// The faces of a box of sides `dims` turned by `world_from_body` as the camera sees them in
/// `rect`: orthographic, back faces culled, the rest sorted back to front (painter's order)
/// and shaded by Lambert's cosine law with a fixed light, over an ambient floor. The box is
/// scaled so its bounding sphere spans the rect's smaller side: whatever way it turns,
/// it stays inside, at one size (no zoom pumping while it tumbles).
pub fn box_faces(
    rect: egui::Rect,
    world_from_body: DMat3,
    dims: DVec3,
    accent: egui::Color32,
) -> Vec<BoxFace> {
    const AMBIENT: f64 = 0.42;
    let view_from_body = view_from_world() * world_from_body;
    let radius = 0.5 * dims.length().max(1e-9);
    let scale = 0.5 * rect.width().min(rect.height()) as f64 / radius;
    let center = rect.center();
    let corner = |i: usize| {
        DVec3::new(
            if i & 1 == 0 { -0.5 } else { 0.5 },
            if i & 2 == 0 { -0.5 } else { 0.5 },
            if i & 4 == 0 { -0.5 } else { 0.5 },
        ) * dims
    };
    let faces: [([usize; 4], DVec3); 6] = [
        ([0, 2, 6, 4], DVec3::NEG_X),
        ([1, 5, 7, 3], DVec3::X),
        ([0, 4, 5, 1], DVec3::NEG_Y),
        ([2, 3, 7, 6], DVec3::Y),
        ([0, 1, 3, 2], DVec3::NEG_Z),
        ([4, 6, 7, 5], DVec3::Z),
    ];
    let light = light_in_view();
    let mut drawn: Vec<(f64, BoxFace)> = faces
        .iter()
        .filter_map(|(idx, normal_in_body)| {
            let normal_in_view = view_from_body * *normal_in_body;
            if normal_in_view.z <= 1e-3 {
                return None; // a back face (the camera looks down −z), or edge-on
            }
            let corners = idx.map(|i| {
                let p = view_from_body * corner(i);
                egui::pos2(
                    center.x + (p.x * scale) as f32,
                    center.y - (p.y * scale) as f32,
                )
            });
            let depth: f64 = idx.iter().map(|&i| (view_from_body * corner(i)).z).sum();
            // the ±y faces (the intermediate axis) carry the method's colour, so the flip shows
            let base = if normal_in_body.y > 0.0 {
                accent
            } else if normal_in_body.y < 0.0 {
                accent.lerp_to_gamma(egui::Color32::WHITE, 0.55)
            } else {
                egui::Color32::from_gray(225)
            };
            let lambert = normal_in_view.dot(light).max(0.0);
            let k = (AMBIENT + (1.0 - AMBIENT) * lambert) as f32;
            let shade = |c: u8| (f32::from(c) * k).round().min(255.0) as u8;
            let color = egui::Color32::from_rgb(shade(base.r()), shade(base.g()), shade(base.b()));
            Some((
                depth,
                BoxFace {
                    corners,
                    color,
                    lambert,
                },
            ))
        })
        .collect();
    drawn.sort_by(|a, b| a.0.total_cmp(&b.0));
    drawn.into_iter().map(|(_, f)| f).collect()
}

/// Paints [`box_faces`]: filled faces, then their edges outlined (plain segments: a stroked
/// sliver polygon grows miter spikes). No panel fill behind: the view sits on the slide's own
/// background, light or dark.
fn paint_box(
    painter: &egui::Painter,
    rect: egui::Rect,
    world_from_body: DMat3,
    dims: DVec3,
    accent: egui::Color32,
    unit: f32,
) {
    let edge = egui::Stroke::new(2.0 * unit, egui::Color32::from_gray(35));
    for face in box_faces(rect, world_from_body, dims, accent) {
        let pts = face.corners.to_vec();
        painter.add(egui::Shape::convex_polygon(
            pts.clone(),
            face.color,
            egui::Stroke::NONE,
        ));
        for k in 0..pts.len() {
            painter.line_segment([pts[k], pts[(k + 1) % pts.len()]], edge);
        }
    }
}

impl SlideWidget for RigidBodyView {
    fn colours(&self) -> Vec<(String, egui::Color32)> {
        self.runs
            .iter()
            .map(|r| {
                let m = r.body.integrator;
                (format!("{m:?}"), style::integrator_color(m))
            })
            .collect()
    }

    fn ui(&mut self, ui: &mut egui::Ui) {
        style::projector_text(ui);
        ui.horizontal(|ui| {
            if style::button(ui, if self.spec.playing { "pause" } else { "play" }) {
                self.spec.playing = !self.spec.playing;
            }
            if style::button(ui, "restart") {
                self.spec.t = 0.0;
            }
            style::slider(ui, &mut self.spec.h, 0.002..=0.2, "h", true);
            style::slider(ui, &mut self.spec.n, 1..=N_MAX, "points per axis", false);
            ui.label(format!("t = {:.1}", self.spec.t));
        });
        if self.spec.playing {
            let dt = ui.input(|i| i.stable_dt).min(0.1) as f64;
            self.spec.t = (self.spec.t + dt * self.spec.speed).min(T_MAX);
            ui.ctx().request_repaint();
        }
        self.advance();
        let dims = box_dims(self.inertia());
        let n = self.runs.len().max(1) as f32;
        let w = (ui.available_width() - ui.spacing().item_spacing.x * (n - 1.0)) / n;
        let u = style::unit(ui);
        // below each box: its name and three readouts, then the inertia line under all
        let line_h = ui.text_style_height(&egui::TextStyle::Body) + ui.spacing().item_spacing.y;
        let text_h = 5.0 * line_h + 2.0 * ui.spacing().item_spacing.y;
        let h = (ui.available_height() - text_h).max(80.0 * u);
        let frame = ui.visuals().widgets.noninteractive.bg_stroke;
        ui.horizontal_top(|ui| {
            for run in &self.runs {
                let m = run.body.integrator;
                let color = style::integrator_color(m);
                ui.vertical(|ui| {
                    ui.set_width(w);
                    let (rect, _) =
                        ui.allocate_exact_size(egui::vec2(w, h.min(w)), egui::Sense::hover());
                    ui.painter()
                        .rect_stroke(rect, 8.0, frame, egui::StrokeKind::Inside);
                    paint_box(
                        ui.painter(),
                        rect,
                        DMat3::from_quat(run.body.state.q),
                        dims,
                        color,
                        u,
                    );
                    ui.colored_label(
                        style::text_color(ui, color),
                        egui::RichText::new(m.name()).strong(),
                    );
                    let mono = |ui: &mut egui::Ui, text: String| {
                        ui.add(egui::Label::new(egui::RichText::new(text).monospace()).extend());
                    };
                    mono(ui, format!("E/E₀     {}", fmt_num(run.energy_ratio())));
                    mono(ui, format!("|L|/|L₀| {}", fmt_num(run.momentum_ratio())));
                    let ob = run.body.omega_body();
                    ui.add(
                        egui::Label::new(format!(
                            "ω_body ({:+.2}, {:+.2}, {:+.2})",
                            ob.x, ob.y, ob.z
                        ))
                        .extend(),
                    );
                });
            }
        });
        let c = self.inertia_comparison();
        let (e, p) = (c.exact, c.points);
        ui.label(format!(
            "Inertia of this {:.2}×{:.2}×{:.2} box (m = 1): mesh (Mirtich) ({:.4}, {:.4}, {:.4});  {}³ points ({:.4}, {:.4}, {:.4}), rel. error {}",
            c.dims.x, c.dims.y, c.dims.z, e.x, e.y, e.z, c.n, p.x, p.y, p.z, fmt_num(c.relative_error())
        ));
    }

    fn params(&mut self) -> Vec<Param<'_>> {
        vec![
            Param::f64_log("h", "step h", &mut self.spec.h, 0.002, 0.2),
            Param::f64("t", "time", &mut self.spec.t, 0.0, T_MAX),
            Param::bool("playing", "playing", &mut self.spec.playing),
            Param::usize("n", "points per axis", &mut self.spec.n, 1, N_MAX),
        ]
    }

    spec_plumbing!(RigidBody);

    /// What the panels print, per method (series `euler`, …, `symplectic-euler`):
    /// `energy_ratio`, `momentum_ratio`, `omega_body_x/y/z`, and the state they come from
    /// (`time`, `q_w/x/y/z`, `l_x/y/z`: ω = R I_body⁻¹ Rᵀ L is checkable); then `t` and the
    /// inertia line: `dims_*`, `n`, `inertia_mesh_*`, `inertia_points_*`, `inertia_rel_error`.
    fn readouts(&mut self) -> Vec<Readout> {
        self.advance();
        let xyz = |name: &str, series: &str, v: DVec3| {
            ["x", "y", "z"]
                .into_iter()
                .zip(v.to_array())
                .map(|(axis, value)| Readout::new(format!("{name}_{axis}"), series, value))
                .collect::<Vec<_>>()
        };
        let mut v = vec![Readout::new("t", "", self.spec.t)];
        for run in &self.runs {
            let key = run.body.integrator.method().name();
            let q = run.body.state.q;
            v.push(Readout::new("energy_ratio", key, run.energy_ratio()));
            v.push(Readout::new("momentum_ratio", key, run.momentum_ratio()));
            v.extend(xyz("omega_body", key, run.body.omega_body()));
            v.push(Readout::new("time", key, run.body.time));
            for (c, value) in ["w", "x", "y", "z"].into_iter().zip([q.w, q.x, q.y, q.z]) {
                v.push(Readout::new(format!("q_{c}"), key, value));
            }
            v.extend(xyz("l", key, run.body.angular_momentum()));
        }
        let c = self.inertia_comparison();
        v.extend(xyz("dims", "", c.dims));
        v.push(Readout::new("n", "", c.n as f64));
        v.extend(xyz("inertia_mesh", "", c.exact));
        v.extend(xyz("inertia_points", "", c.points));
        v.push(Readout::new("inertia_rel_error", "", c.relative_error()));
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::deck::widgets::rigid_body::default_methods;

    fn view(h: f64, t: f64) -> RigidBodyView {
        let mut v = RigidBodyView::new(RigidBodySpec {
            inertia: (1.0, 2.0, 3.0),
            omega0: (0.02, 2.0, 0.02),
            h,
            t,
            playing: false,
            speed: 1.0,
            n: 4,
            methods: default_methods(),
        });
        // a frame takes at most MAX_STEPS_PER_FRAME steps: let a few frames catch up
        for _ in 0..(t / h / MAX_STEPS_PER_FRAME as f64).ceil() as usize + 1 {
            v.advance();
        }
        v
    }

    fn run(v: &RigidBodyView, m: Integrator) -> &Run {
        v.runs().iter().find(|r| r.body.integrator == m).unwrap()
    }

    #[test]
    fn rk4_conserves_energy_and_momentum_and_flips() {
        let v = view(0.01, 20.0);
        let rk4 = run(&v, Integrator::Rk4);
        let euler = run(&v, Integrator::Euler);
        assert!((rk4.body.time - 20.0).abs() < 1e-6, "{}", rk4.body.time);
        assert!(
            (rk4.energy_ratio() - 1.0).abs() < 1e-4 && (rk4.momentum_ratio() - 1.0).abs() < 1e-12,
            "{:?}",
            (rk4.energy_ratio(), rk4.momentum_ratio())
        );
        // |L| is exact for every method (no torque: L' = 0); energy drifts with the method
        assert!((euler.momentum_ratio() - 1.0).abs() < 1e-12);
        assert!(
            (euler.energy_ratio() - 1.0).abs() > 100.0 * (rk4.energy_ratio() - 1.0).abs(),
            "Euler {} vs RK4 {}",
            euler.energy_ratio(),
            rk4.energy_ratio()
        );
        // symplectic Euler rotates by the symplectic splitting of the free body: its energy
        // error oscillates, bounded and O(h²), instead of growing (measured here at t = 20:
        // E/E₀ − 1 = 8.0e-10 vs Euler's 0.1057), and L is untouched
        let se = run(&v, Integrator::SymplecticEuler);
        assert!((se.momentum_ratio() - 1.0).abs() < 1e-12);
        assert!(
            (se.energy_ratio() - 1.0).abs() < 1e-4
                && (euler.energy_ratio() - 1.0).abs() > 1000.0 * (se.energy_ratio() - 1.0).abs(),
            "symplectic Euler {} vs Euler {}",
            se.energy_ratio(),
            euler.energy_ratio()
        );
        // the intermediate-axis component changes sign within 20 s (the flip)
        let mut w = view(0.01, 0.0);
        let mut flipped = false;
        for k in 1..=200 {
            w.spec.t = k as f64 * 0.1;
            w.advance();
            if run(&w, Integrator::Rk4).body.omega_body().y < 0.0 {
                flipped = true;
            }
        }
        assert!(flipped, "no Dzhanibekov flip");
    }

    #[test]
    fn time_going_back_restarts_from_the_initial_state() {
        let mut v = view(0.05, 3.0);
        v.spec.t = 1.0;
        v.advance();
        let r = run(&v, Integrator::Rk4);
        assert!((r.body.time - 1.0).abs() < 1e-9, "{}", r.body.time);
        // non-finite inputs neither panic nor poison the state
        v.spec.h = f64::NAN;
        v.spec.t = f64::INFINITY;
        v.advance();
        assert!(v.runs().iter().all(|r| r.body.energy().is_finite()));
    }

    #[test]
    fn mesh_inertia_is_the_box_formula_and_points_converge_at_second_order() {
        let d = DVec3::new(2.0, 1.0, 0.5);
        let formula = DVec3::new(
            d.y * d.y + d.z * d.z,
            d.x * d.x + d.z * d.z,
            d.x * d.x + d.y * d.y,
        ) / 12.0;
        let c4 = InertiaComparison::new(d, 4);
        assert!(((c4.exact - formula) / formula).abs().max_element() < 1e-12);
        // midpoint-rule lattice: I = m/12 (b²+c²)(1 − 1/n²)
        assert!(
            (c4.relative_error() - 1.0 / 16.0).abs() < 1e-9,
            "{}",
            c4.relative_error()
        );
        let c8 = InertiaComparison::new(d, 8);
        assert!((c4.relative_error() / c8.relative_error() - 4.0).abs() < 1e-6);
    }
}
