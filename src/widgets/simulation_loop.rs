//! Widget 11, "simulation overview", which the notes drew as a picture: the loop every frame runs for a
//! rigid body — state → forces and torques → derivative → integrator step → renormalise q and
//! recompute I⁻¹ → render — as a cycle, each stage with the live numbers of one of the scene's
//! floating bodies, stepped by the same code as scene mode (`scene::bodies`).

use std::path::{Path, PathBuf};

use egui::{Pos2, Rect, Stroke, pos2, vec2};
use glam::{DMat3, DQuat, DVec3};

use super::style::{self, fmt_num};
use super::{Param, SlideWidget};
use crate::deck::widgets::SimulationLoopSpec;
use crate::rigid::{Forces, Integrator, Wrench};
use crate::scene::bodies::FloatingBody;
use crate::scene::{Scene, Simulation};
use crate::waves::WaveSum;

/// How often the playing loop redraws its numbers.
const LIVE_FPS: f64 = 20.0;

/// The body and its water, loaded from the scene file the spec names.
struct World {
    waves: WaveSum,
    simulation: Simulation,
    body: FloatingBody,
    steps: u64,
}

fn load_world(base_dir: Option<&Path>, spec: &SimulationLoopSpec) -> Result<World, String> {
    let resolved = match base_dir {
        Some(dir) => crate::paths::resolve_in(dir, &spec.scene),
        None => Ok(PathBuf::from(&spec.scene)),
    };
    let path = crate::bundled::scene_file(resolved, &spec.scene)?.path;
    let scene: Scene = crate::scene::load_scene(&path).map_err(|d| d.to_string())?;
    let level = scene.water.level;
    let body = scene
        .objects
        .iter()
        .enumerate()
        .filter_map(|(i, o)| FloatingBody::from_object(i, o, level))
        .nth(spec.body)
        .ok_or_else(|| {
            format!(
                "{} has no floating body number {} (counting from 0)",
                spec.scene, spec.body
            )
        })?;
    Ok(World {
        waves: WaveSum::new(scene.water.waves.clone(), level),
        simulation: scene.simulation.clone(),
        body,
        steps: 0,
    })
}

/// What each stage of the loop shows, for the body's current state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoopNumbers {
    pub time_secs: f64,
    pub x: DVec3,
    pub q: DQuat,
    pub p: DVec3,
    pub l: DVec3,
    pub wrench: Wrench,
    /// ẋ = P / M
    pub velocity: DVec3,
    /// ω = I⁻¹(t) L with I⁻¹(t) = R I_body⁻¹ Rᵀ
    pub omega: DVec3,
    pub inv_inertia_world: DMat3,
    /// | |q + h q̇| − 1 |: how far one unnormalised quaternion step leaves the unit sphere
    pub q_drift: f64,
    pub h_secs: f64,
    pub integrator: Integrator,
}

/// The numbers of `body` stepping in `waves` with `simulation`'s drag and step.
pub fn loop_numbers(body: &FloatingBody, waves: &WaveSum, simulation: &Simulation) -> LoopNumbers {
    let b = &body.body;
    let s = &b.state;
    let c = &b.constants;
    let wrench = body.water_forces(waves, simulation).wrench(c, s, b.time);
    let r = DMat3::from_quat(s.q);
    let inv_inertia_world = r * c.inv_inertia_body * r.transpose();
    let omega = inv_inertia_world * s.l;
    let h = simulation.body_h_secs as f64;
    let q_dot = DQuat::from_xyzw(omega.x, omega.y, omega.z, 0.0) * s.q * 0.5;
    let q_raw = s.q + q_dot * h;
    LoopNumbers {
        time_secs: b.time,
        x: s.x,
        q: s.q,
        p: s.p,
        l: s.l,
        wrench,
        velocity: s.p * c.inv_mass,
        omega,
        inv_inertia_world,
        q_drift: (q_raw.length() - 1.0).abs(),
        h_secs: h,
        integrator: b.integrator,
    }
}

pub struct SimulationLoop {
    pub spec: SimulationLoopSpec,
    initial: SimulationLoopSpec,
    base_dir: Option<PathBuf>,
    /// keyed by (scene, body): a failed load is not retried every frame
    world: Option<((String, usize), Result<World, String>)>,
}

impl SimulationLoop {
    pub fn new_in(spec: SimulationLoopSpec, base_dir: Option<&Path>) -> Self {
        Self {
            initial: spec.clone(),
            spec,
            base_dir: base_dir.map(Path::to_path_buf),
            world: None,
        }
    }

    fn world(&mut self) -> &mut Result<World, String> {
        let key = (self.spec.scene.clone(), self.spec.body);
        if self.world.as_ref().is_none_or(|(k, _)| *k != key) {
            let loaded = load_world(self.base_dir.as_deref(), &self.spec);
            self.world = Some((key, loaded));
        }
        &mut self.world.as_mut().expect("just filled").1
    }

    /// The load error, if the scene or body could not be had.
    pub fn error(&mut self) -> Option<String> {
        self.world().as_ref().err().cloned()
    }

    /// Advances the body by `dt_secs` of simulated time; the numbers after it.
    pub fn advance(&mut self, dt_secs: f64) -> Option<LoopNumbers> {
        let integrator = self.spec.integrator;
        let world = self.world().as_mut().ok()?;
        let method = integrator.unwrap_or(world.simulation.integrator);
        let before = world.body.body.time;
        world
            .body
            .advance(before + dt_secs, &world.waves, &world.simulation, method);
        let h = world.simulation.body_h_secs as f64;
        world.steps += ((world.body.body.time - before) / h).round() as u64;
        Some(loop_numbers(&world.body, &world.waves, &world.simulation))
    }

    fn steps(&self) -> u64 {
        match &self.world {
            Some((_, Ok(w))) => w.steps,
            _ => 0,
        }
    }
}

fn v3(v: DVec3) -> String {
    format!("({:+.2}, {:+.2}, {:+.2})", v.x, v.y, v.z)
}

/// One row of the world inverse inertia, as printed: the full matrix, since R I_body⁻¹ Rᵀ is
/// not diagonal once the body has turned (the ω printed beside it is this matrix times L).
fn matrix_row(r: DVec3) -> String {
    format!("[{:+.4}  {:+.4}  {:+.4}]", r.x, r.y, r.z)
}

/// The six stages, each a title and its lines.
fn stages(n: &LoopNumbers, steps: u64) -> [(&'static str, Vec<String>); 6] {
    let w = &n.wrench;
    let i = n.inv_inertia_world;
    [
        (
            "state X(t) = (x, q, P, L)",
            vec![
                format!("x {} m", v3(n.x)),
                format!(
                    "q ({:+.2}, {:+.2}, {:+.2}, {:+.2})",
                    n.q.w, n.q.x, n.q.y, n.q.z
                ),
                format!("P {} kg m/s", v3(n.p)),
                format!("L {} kg m²/s", v3(n.l)),
            ],
        ),
        (
            "forces and torques",
            vec![
                format!("F {} N", v3(w.force)),
                format!("τ {} N m", v3(w.torque)),
                "gravity + buoyancy + drag".into(),
            ],
        ),
        (
            "derivative Ẋ = (P/M, ½ωq, F, τ)",
            vec![
                format!("ẋ = P/M {} m/s", v3(n.velocity)),
                format!("ω = I⁻¹L {} rad/s", v3(n.omega)),
            ],
        ),
        (
            "integrator step",
            vec![
                format!("{}, h = {:.1} ms", n.integrator.name(), n.h_secs * 1e3),
                format!("t = {:.2} s", n.time_secs),
            ],
        ),
        (
            "renormalise q, recompute I⁻¹",
            vec![
                format!("|q + h dq/dt| − 1 = {}", fmt_num(n.q_drift)),
                "I⁻¹ = R I_body⁻¹ Rᵀ (1/(kg m²)) =".into(),
                matrix_row(i.row(0)),
                matrix_row(i.row(1)),
                matrix_row(i.row(2)),
            ],
        ),
        (
            "render",
            vec![
                format!("mesh at x, turned by R(q)"),
                format!("step {steps}"),
            ],
        ),
    ]
}

/// Where the six stages sit: round an ellipse, clockwise from the top left.
pub fn stage_centres(rect: Rect) -> [Pos2; 6] {
    let c = rect.center();
    let (rx, ry) = (rect.width() * 0.34, rect.height() * 0.34);
    std::array::from_fn(|k| {
        let a = (-150.0 + 60.0 * k as f32).to_radians();
        pos2(c.x + rx * a.cos(), c.y + ry * a.sin())
    })
}

fn arrow(painter: &egui::Painter, from: Pos2, to: Pos2, stroke: Stroke) {
    painter.line_segment([from, to], stroke);
    let dir = (to - from).normalized();
    let side = vec2(-dir.y, dir.x);
    let head = stroke.width * 4.0;
    painter.add(egui::Shape::convex_polygon(
        vec![
            to,
            to - dir * head + side * head * 0.5,
            to - dir * head - side * head * 0.5,
        ],
        stroke.color,
        Stroke::NONE,
    ));
}

fn loop_ui(ui: &mut egui::Ui, n: &LoopNumbers, steps: u64) {
    let ink = style::ink(ui);
    let accent = style::RK4;
    let title_color = style::text_color(ui, accent);
    let avail = ui.available_rect_before_wrap();
    let u = style::unit(ui);
    let rect = Rect::from_min_size(
        avail.min,
        vec2(avail.width(), avail.height().max(200.0 * u)),
    );
    ui.allocate_rect(rect, egui::Sense::hover());
    let painter = ui.painter_at(rect);
    let title_font = egui::TextStyle::Body.resolve(ui.style());
    let mono = egui::TextStyle::Monospace.resolve(ui.style());
    let centres = stage_centres(rect);
    let mut boxes = Vec::new();
    for ((title, lines), centre) in stages(n, steps).into_iter().zip(centres) {
        let t = painter.layout_no_wrap(title.into(), title_font.clone(), title_color);
        let body = painter.layout_no_wrap(lines.join("\n"), mono.clone(), ink);
        let size =
            vec2(t.size().x.max(body.size().x), t.size().y + body.size().y) + vec2(16.0, 12.0) * u;
        let r = Rect::from_center_size(centre, size);
        boxes.push(r);
        painter.rect_filled(r, 8.0 * u, ui.visuals().extreme_bg_color);
        painter.rect_stroke(
            r,
            8.0 * u,
            Stroke::new(1.5 * u, accent),
            egui::StrokeKind::Inside,
        );
        painter.galley(r.min + vec2(8.0, 6.0) * u, t.clone(), title_color);
        painter.galley(r.min + vec2(8.0 * u, 6.0 * u + t.size().y), body, ink);
    }
    let stroke = Stroke::new(2.0 * u, ink.gamma_multiply(0.7));
    for k in 0..6 {
        let (a, b) = (boxes[k], boxes[(k + 1) % 6]);
        let (from, to) = (a.center(), b.center());
        // from the edge of one box to the edge of the next
        let clip = |r: Rect, p: Pos2, towards: Pos2| {
            let d = towards - p;
            let tx = if d.x.abs() > 1e-3 {
                (r.width() * 0.5 + 6.0 * u) / d.x.abs()
            } else {
                f32::MAX
            };
            let ty = if d.y.abs() > 1e-3 {
                (r.height() * 0.5 + 6.0 * u) / d.y.abs()
            } else {
                f32::MAX
            };
            p + d * tx.min(ty).min(0.45)
        };
        arrow(&painter, clip(a, from, to), clip(b, to, from), stroke);
    }
    painter.text(
        rect.center(),
        egui::Align2::CENTER_CENTER,
        "every frame",
        title_font,
        ink.gamma_multiply(0.6),
    );
}

impl SlideWidget for SimulationLoop {
    fn problems(&self) -> Vec<String> {
        match &self.world {
            Some((_, Err(e))) => vec![e.clone()],
            _ => Vec::new(),
        }
    }
    fn ui(&mut self, ui: &mut egui::Ui) {
        style::projector_text(ui);
        ui.set_max_width(ui.available_width());
        ui.horizontal_wrapped(|ui| {
            let label = if self.spec.playing { "pause" } else { "play" };
            if style::button(ui, label) {
                self.spec.playing = !self.spec.playing;
            }
            if style::button(ui, "restart") {
                self.world = None; // the body again as the scene file starts it
            }
            let current = self.spec.integrator.or(match &self.world {
                Some((_, Ok(w))) => Some(w.simulation.integrator),
                _ => None,
            });
            for m in Integrator::ALL {
                let on = current == Some(m);
                let color = match on {
                    true => style::selected_label_color(ui, style::integrator_color(m)),
                    false => style::text_color(ui, style::integrator_color(m)),
                };
                let text = egui::RichText::new(m.name()).color(color);
                if style::choice(ui, on, text) {
                    self.spec.integrator = Some(m);
                }
            }
        });
        let dt = if self.spec.playing {
            // numbers that change 20 times a second read as live; every display frame would
            // keep a software renderer busy redrawing the whole slide (135 % CPU measured)
            ui.ctx()
                .request_repaint_after(std::time::Duration::from_secs_f64(1.0 / LIVE_FPS));
            ui.input(|i| i.stable_dt).min(0.1) as f64
        } else {
            0.0
        };
        match self.advance(dt) {
            Some(n) => loop_ui(ui, &n, self.steps()),
            None => {
                let why = self.error().unwrap_or_default();
                ui.colored_label(style::text_color(ui, style::DIVERGED), why);
            }
        }
    }

    fn params(&mut self) -> Vec<Param<'_>> {
        vec![Param::bool("playing", "playing", &mut self.spec.playing)]
    }

    fn reset(&mut self) {
        self.spec = self.initial.clone();
        self.world = None;
    }

    fn spec(&self) -> crate::widgets::WidgetSpec {
        crate::widgets::WidgetSpec::SimulationLoop(self.spec.clone())
    }

    /// The numbers of the loop as printed at the body's current time: L, ω and the world
    /// inverse inertia `inv_inertia_world` (series `r0c0` … `r2c2`), with ω = I⁻¹ L.
    fn readouts(&mut self) -> Vec<super::Readout> {
        use super::Readout;
        let Some(n) = self.advance(0.0) else {
            return Vec::new();
        };
        let mut v = vec![Readout::new("t", "", n.time_secs)];
        for (name, vec) in [("l", n.l), ("omega", n.omega)] {
            for (axis, value) in ["x", "y", "z"].iter().zip(vec.to_array()) {
                v.push(Readout::new(name, *axis, value));
            }
        }
        for r in 0..3 {
            for (c, value) in n.inv_inertia_world.row(r).to_array().iter().enumerate() {
                v.push(Readout::new(
                    "inv_inertia_world",
                    format!("r{r}c{c}"),
                    *value,
                ));
            }
        }
        v
    }
}
