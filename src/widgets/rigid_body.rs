//! 9. A tumbling box near its intermediate axis (the Dzhanibekov flip), integrated from the
//! 13-number state X = (x, q, P, L) with Ẋ = (P/M, ½ ω q, F, τ), ω = I⁻¹ L and
//! I⁻¹ = R I_body⁻¹ Rᵀ (ERRATA 2, 4), by Euler, midpoint and RK4 side by side, each with its
//! energy and |L|. Below: the box's inertia from its exact formula vs from n³ points.

use glam::{DMat3, DQuat, DVec3};
use serde::{Deserialize, Serialize};

use super::methods::MethodId;
use super::style::{self, fmt_num};
use super::{Param, SlideWidget};
use crate::ode::{ExplicitRk, System};

/// Torque-free rigid body in the 13-number state (x, q = (w, x, y, z), P, L).
pub struct FreeBody {
    pub mass: f64,
    pub i_body: DVec3,
}

pub fn rotation(x: &[f64]) -> DMat3 {
    // normalise on read: the state's q drifts off unit length under any integrator
    DMat3::from_quat(DQuat::from_xyzw(x[4], x[5], x[6], x[3]).normalize())
}

impl FreeBody {
    pub fn omega(&self, x: &[f64]) -> DVec3 {
        let r = rotation(x);
        let i_inv = r * DMat3::from_diagonal(self.i_body.recip()) * r.transpose();
        i_inv * DVec3::new(x[10], x[11], x[12])
    }

    /// Kinetic energy ½ Lᵀ I⁻¹ L + |P|²/2M.
    pub fn energy(&self, x: &[f64]) -> f64 {
        let l = DVec3::new(x[10], x[11], x[12]);
        let p = DVec3::new(x[7], x[8], x[9]);
        0.5 * l.dot(self.omega(x)) + p.length_squared() / (2.0 * self.mass)
    }

    /// The angular velocity in body axes (what the flip is seen in).
    pub fn omega_body(&self, x: &[f64]) -> DVec3 {
        rotation(x).transpose() * self.omega(x)
    }
}

impl System for FreeBody {
    fn dim(&self) -> usize {
        13
    }
    fn rhs(&self, _t: f64, x: &[f64], d: &mut [f64]) {
        for i in 0..3 {
            d[i] = x[7 + i] / self.mass;
        }
        let w = self.omega(x);
        let q = DQuat::from_xyzw(x[4], x[5], x[6], x[3]);
        let dq = DQuat::from_xyzw(w.x, w.y, w.z, 0.0) * q * 0.5;
        d[3] = dq.w;
        d[4] = dq.x;
        d[5] = dq.y;
        d[6] = dq.z;
        for v in &mut d[7..13] {
            *v = 0.0; // no force, no torque
        }
    }
}

/// Inertia of a solid box (sides a, b, c, mass m) about its centre from n³ equal point masses at
/// cell centres: the lecture's "approximation with points".
pub fn lattice_inertia(m: f64, dims: DVec3, n: usize) -> DVec3 {
    let n = n.clamp(1, 200);
    let dm = m / (n * n * n) as f64;
    let mut i = DVec3::ZERO;
    let coord = |k: usize, len: f64| ((k as f64 + 0.5) / n as f64 - 0.5) * len;
    for a in 0..n {
        let x = coord(a, dims.x);
        for b in 0..n {
            let y = coord(b, dims.y);
            for c in 0..n {
                let z = coord(c, dims.z);
                i += dm * DVec3::new(y * y + z * z, x * x + z * z, x * x + y * y);
            }
        }
    }
    i
}

/// The exact inertia m/12 (b²+c², a²+c², a²+b²) (ERRATA 7; Mirtich's mesh integrals give it
/// exactly for the box's mesh).
pub fn box_inertia(m: f64, d: DVec3) -> DVec3 {
    m / 12.0
        * DVec3::new(
            d.y * d.y + d.z * d.z,
            d.x * d.x + d.z * d.z,
            d.x * d.x + d.y * d.y,
        )
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RigidBodySpec {
    /// Principal moments of the body (the diag(1, 2, 3)).
    #[serde(default = "default_i")]
    pub inertia: (f64, f64, f64),
    /// Initial angular velocity in body axes: mostly about the intermediate axis.
    #[serde(default = "default_omega")]
    pub omega0: (f64, f64, f64),
    #[serde(default = "default_h")]
    pub h: f64,
    /// Simulated time shown (advances while `playing`).
    #[serde(default)]
    pub t: f64,
    #[serde(default = "yes")]
    pub playing: bool,
    /// Simulated seconds per real second.
    #[serde(default = "default_speed")]
    pub speed: f64,
    /// Points per axis for the inertia approximation.
    #[serde(default = "default_n")]
    pub n: usize,
}

fn default_i() -> (f64, f64, f64) {
    (1.0, 2.0, 3.0)
}
fn default_omega() -> (f64, f64, f64) {
    (0.02, 2.0, 0.02)
}
fn default_h() -> f64 {
    0.02
}
fn default_speed() -> f64 {
    2.0
}
fn default_n() -> usize {
    4
}
fn yes() -> bool {
    true
}

/// Steps a frame may take per method; beyond it the view lags rather than stalls the UI.
const MAX_STEPS_PER_FRAME: usize = 1000;
const T_MAX: f64 = 600.0;

struct Run {
    method: MethodId,
    rk: ExplicitRk,
    x: Vec<f64>,
    t: f64,
    e0: f64,
    l0: f64,
}

pub struct RigidBodyView {
    pub spec: RigidBodySpec,
    initial: RigidBodySpec,
    runs: Vec<Run>,
    /// (inertia, ω₀, h) the runs were started with.
    key: Option<((f64, f64, f64), (f64, f64, f64), f64)>,
}

impl RigidBodyView {
    pub fn new(spec: RigidBodySpec) -> Self {
        Self {
            initial: spec.clone(),
            spec,
            runs: Vec::new(),
            key: None,
        }
    }

    pub fn body(&self) -> FreeBody {
        let (a, b, c) = self.spec.inertia;
        FreeBody {
            mass: 1.0,
            i_body: DVec3::new(a, b, c).max(DVec3::splat(1e-6)),
        }
    }

    fn initial_state(&self) -> Vec<f64> {
        let body = self.body();
        let (a, b, c) = self.spec.omega0;
        let l = body.i_body * DVec3::new(a, b, c); // R = identity at t = 0
        vec![
            0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, l.x, l.y, l.z,
        ]
    }

    /// Advances every method to `spec.t` (restarting if time went backwards or inputs changed),
    /// at most MAX_STEPS_PER_FRAME steps each.
    pub fn advance(&mut self) {
        let key = (self.spec.inertia, self.spec.omega0, self.spec.h);
        let h = self.spec.h.clamp(1e-3, 0.5);
        if self.key != Some(key) || self.runs.iter().any(|r| r.t > self.spec.t + 1e-9) {
            let body = self.body();
            let x0 = self.initial_state();
            self.runs = MethodId::INTEGRATORS
                .iter()
                .map(|&m| Run {
                    method: m,
                    rk: ExplicitRk::new(m.tableau().unwrap(), 13),
                    x: x0.clone(),
                    t: 0.0,
                    e0: body.energy(&x0),
                    l0: DVec3::new(x0[10], x0[11], x0[12]).length(),
                })
                .collect();
            self.key = Some(key);
        }
        let body = self.body();
        for r in &mut self.runs {
            let mut steps = 0;
            while r.t + h <= self.spec.t + 1e-9 && steps < MAX_STEPS_PER_FRAME {
                r.rk.step(&body, r.t, &mut r.x, h);
                r.t += h;
                steps += 1;
            }
        }
    }

    /// (method, state, E/E₀, |L|/|L₀|) of each run.
    pub fn states(&self) -> Vec<(MethodId, Vec<f64>, f64, f64)> {
        let body = self.body();
        self.runs
            .iter()
            .map(|r| {
                let l = DVec3::new(r.x[10], r.x[11], r.x[12]).length();
                (r.method, r.x.clone(), body.energy(&r.x) / r.e0, l / r.l0)
            })
            .collect()
    }
}

/// Paints the box (sides ∝ √ of the inertia it models) rotated by R, in an orthographic view
/// from a fixed oblique camera, faces sorted back to front and shaded by their normal.
fn paint_box(
    painter: &egui::Painter,
    rect: egui::Rect,
    r: DMat3,
    dims: DVec3,
    accent: egui::Color32,
) {
    let cam = DMat3::from_rotation_x(-0.45) * DMat3::from_rotation_y(0.6);
    let scale = rect.width().min(rect.height()) as f64 * 0.33 / dims.max_element().max(1e-9);
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
    let view_from_body = cam * r;
    let mut drawn: Vec<(f64, Vec<egui::Pos2>, egui::Color32)> = faces
        .iter()
        .filter_map(|(idx, n)| {
            let n_view = view_from_body * *n;
            if n_view.z < 0.02 {
                return None; // facing away or edge-on (camera looks down −z)
            }
            let pts: Vec<egui::Pos2> = idx
                .iter()
                .map(|&i| {
                    let p = view_from_body * corner(i);
                    egui::pos2(
                        center.x + (p.x * scale) as f32,
                        center.y - (p.y * scale) as f32,
                    )
                })
                .collect();
            let depth = idx
                .iter()
                .map(|&i| (view_from_body * corner(i)).z)
                .sum::<f64>();
            // the ±y faces (the intermediate axis) carry the method's colour, so the flip shows
            let base = if n.y > 0.0 {
                accent
            } else if n.y < 0.0 {
                accent.lerp_to_gamma(egui::Color32::WHITE, 0.6)
            } else {
                egui::Color32::from_gray(200)
            };
            let light =
                (0.45 + 0.55 * n_view.dot(DVec3::new(0.3, 0.5, 0.8).normalize()).max(0.0)) as f32;
            let c = egui::Color32::from_rgb(
                (base.r() as f32 * light) as u8,
                (base.g() as f32 * light) as u8,
                (base.b() as f32 * light) as u8,
            );
            Some((depth, pts, c))
        })
        .collect();
    drawn.sort_by(|a, b| a.0.total_cmp(&b.0));
    // Fill, then outline with plain segments: a stroked sliver polygon grows miter spikes.
    let edge = egui::Stroke::new(1.5, egui::Color32::from_gray(40));
    for (_, pts, c) in drawn {
        painter.add(egui::Shape::convex_polygon(
            pts.clone(),
            c,
            egui::Stroke::NONE,
        ));
        for k in 0..pts.len() {
            painter.line_segment([pts[k], pts[(k + 1) % pts.len()]], edge);
        }
    }
}

impl SlideWidget for RigidBodyView {
    fn ui(&mut self, ui: &mut egui::Ui) {
        style::projector_text(ui);
        ui.horizontal(|ui| {
            if ui
                .button(if self.spec.playing { "pause" } else { "play" })
                .clicked()
            {
                self.spec.playing = !self.spec.playing;
            }
            if ui.button("restart").clicked() {
                self.spec.t = 0.0;
            }
            ui.add(
                egui::Slider::new(&mut self.spec.h, 0.002..=0.2)
                    .logarithmic(true)
                    .text("h"),
            );
            ui.add(egui::Slider::new(&mut self.spec.n, 1..=40).text("points per axis"));
            ui.label(format!("t = {:.1}", self.spec.t));
        });
        if self.spec.playing {
            let dt = ui.input(|i| i.stable_dt).min(0.1) as f64;
            self.spec.t = (self.spec.t + dt * self.spec.speed).min(T_MAX);
            ui.ctx().request_repaint();
        }
        self.advance();
        let (ia, ib, ic) = self.spec.inertia;
        // a box of mass 12 with these moments has sides² = (b+c−a, a+c−b, a+b−c)/2 · (12/12·…);
        // clamp the degenerate plate of diag(1,2,3) to a visible thickness
        let dims = DVec3::new(ib + ic - ia, ia + ic - ib, ia + ib - ic)
            .max(DVec3::splat(0.02))
            .powf(0.5);
        let dims = dims.max(DVec3::splat(0.3 * dims.max_element()));
        let states = self.states();
        let n = states.len().max(1) as f32;
        let w = (ui.available_width() - ui.spacing().item_spacing.x * (n - 1.0)) / n;
        let h = (ui.available_height() - 120.0).max(80.0);
        ui.horizontal_top(|ui| {
            for (m, x, e, l) in &states {
                ui.vertical(|ui| {
                    ui.set_width(w);
                    let (rect, _) =
                        ui.allocate_exact_size(egui::vec2(w, h.min(w)), egui::Sense::hover());
                    ui.painter()
                        .rect_filled(rect, 8.0, egui::Color32::from_gray(248));
                    paint_box(
                        ui.painter(),
                        rect,
                        rotation(x),
                        dims,
                        style::method_color(*m),
                    );
                    let ob = self.body().omega_body(x);
                    ui.colored_label(
                        style::method_color(*m),
                        egui::RichText::new(m.name()).strong(),
                    );
                    ui.label(
                        egui::RichText::new(format!(
                            "E/E₀ = {}   |L|/|L₀| = {}",
                            fmt_num(*e),
                            fmt_num(*l)
                        ))
                        .monospace(),
                    );
                    ui.label(
                        egui::RichText::new(format!(
                            "ω_body = ({:+.2}, {:+.2}, {:+.2})",
                            ob.x, ob.y, ob.z
                        ))
                        .monospace(),
                    );
                });
            }
        });
        let d = dims;
        let exact = box_inertia(1.0, d);
        let pts = lattice_inertia(1.0, d, self.spec.n);
        let rel = ((pts - exact) / exact).abs().max_element();
        ui.label(format!(
            "Inertia of this box (m = 1): exact m/12(b²+c², …) = ({:.4}, {:.4}, {:.4});  {}³ points: ({:.4}, {:.4}, {:.4}), rel. error {}",
            exact.x, exact.y, exact.z, self.spec.n, pts.x, pts.y, pts.z, fmt_num(rel)
        ));
    }

    fn params(&mut self) -> Vec<Param<'_>> {
        vec![
            Param::f64_log("h", "step h", &mut self.spec.h, 0.002, 0.2),
            Param::f64("t", "time", &mut self.spec.t, 0.0, T_MAX),
            Param::bool("playing", "playing", &mut self.spec.playing),
            Param::usize("n", "points per axis", &mut self.spec.n, 1, 40),
        ]
    }

    spec_plumbing!(RigidBody);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn view(h: f64, t: f64) -> RigidBodyView {
        let mut v = RigidBodyView::new(RigidBodySpec {
            inertia: (1.0, 2.0, 3.0),
            omega0: (0.02, 2.0, 0.02),
            h,
            t,
            playing: false,
            speed: 1.0,
            n: 4,
        });
        v.advance();
        v
    }

    #[test]
    fn rk4_conserves_energy_and_momentum_and_flips() {
        let v = view(0.01, 20.0);
        let s = v.states();
        let rk4 = s.iter().find(|s| s.0 == MethodId::Rk4).unwrap();
        assert!(
            (rk4.2 - 1.0).abs() < 1e-4 && (rk4.3 - 1.0).abs() < 1e-12,
            "{:?}",
            (rk4.2, rk4.3)
        );
        // the intermediate-axis component changes sign at least once within 20 s (the flip)
        let mut flipped = false;
        let body = v.body();
        let mut w = view(0.01, 0.0);
        for k in 1..=200 {
            w.spec.t = k as f64 * 0.1;
            w.advance();
            let x = &w.states()[2].1;
            if body.omega_body(x).y < 0.0 {
                flipped = true;
            }
        }
        assert!(flipped, "no Dzhanibekov flip");
        let euler = s.iter().find(|s| s.0 == MethodId::Euler).unwrap();
        // |L| is exact for every method (no torque: L' = 0); energy drifts with the method
        assert!((euler.3 - 1.0).abs() < 1e-12);
        assert!(
            (euler.2 - 1.0).abs() > 100.0 * (rk4.2 - 1.0).abs(),
            "Euler {} vs RK4 {}",
            euler.2,
            rk4.2
        );
    }

    #[test]
    fn point_lattice_inertia_converges_to_the_box_formula_at_second_order() {
        let d = DVec3::new(2.0, 1.0, 0.5);
        let exact = box_inertia(3.0, d);
        let err = |n| {
            ((lattice_inertia(3.0, d, n) - exact) / exact)
                .abs()
                .max_element()
        };
        // midpoint-rule lattice: I = m/12 (b²+c²)(1 − 1/n²)
        assert!((err(4) - 1.0 / 16.0).abs() < 1e-12, "{}", err(4));
        assert!((err(4) / err(8) - 4.0).abs() < 1e-9);
    }
}
