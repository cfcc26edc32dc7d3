//! Scene mode inside the eframe app: renders into its own HDR targets and an sRGB texture
//! registered with egui, orbits/zooms with the mouse, hot-reloads `shaders/` and `scenes/`
//! (polled here, on the UI thread: the watcher thread only sends paths), and draws the
//! teaching panel separately so the presenter view can put it on the lecturer's screen.

use std::collections::VecDeque;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use anyhow::Result;

use crate::diag::Diagnostic;
use crate::reload::{DirWatcher, Settled, read_settled};
use crate::rigid::Integrator;
use crate::scene::{self, SceneSim};

use super::frame::{DebugView, RenderSettings};
use super::gpu::UncapturedErrors;
use super::renderer::Renderer;

const OUTPUT_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;

struct Output {
    size: (u32, u32),
    _texture: wgpu::Texture,
    view: wgpu::TextureView,
    id: egui::TextureId,
}

pub struct SceneView {
    renderer: Renderer,
    sim: SceneSim,
    scene_path: PathBuf,
    scene_error: Option<Diagnostic>,
    watcher: Option<DirWatcher>,
    device_errors: UncapturedErrors,
    pub settings: RenderSettings,
    pub paused: bool,
    step_once: bool,
    show_frame_time: bool,
    /// the teaching panel as a floating window over the scene (a "controls" button opens it); a
    /// presenter view that shows [`SceneView::controls_ui`] on its own screen sets
    /// `controls_button` to false
    pub controls_open: bool,
    pub controls_button: bool,
    selected_material: usize,
    output: Option<Output>,
    last_instant: Option<Instant>,
    cpu_ms: VecDeque<f32>,
    interval_ms: VecDeque<f32>,
}

impl SceneView {
    pub fn new(render_state: &egui_wgpu::RenderState, scene_path: &Path) -> Result<Self> {
        let root = scene_path
            .parent()
            .and_then(Path::parent)
            .unwrap_or(Path::new(""));
        let shader_dir = root.join(super::SHADER_DIR);
        let scene = scene::load_scene(scene_path)?;
        let renderer = Renderer::new(
            &render_state.device,
            &render_state.queue,
            &shader_dir,
            &scene,
            OUTPUT_FORMAT,
        )?;
        let scenes_dir = scene_path.parent().unwrap_or(Path::new("."));
        let watcher = DirWatcher::new(&[&shader_dir, scenes_dir], Duration::from_millis(80), || {})
            .map_err(|e| tracing::warn!("not watching shaders/scenes: {e}"))
            .ok();
        Ok(Self {
            renderer,
            sim: SceneSim::new(scene),
            scene_path: scene_path.to_path_buf(),
            scene_error: None,
            watcher,
            device_errors: UncapturedErrors::install(&render_state.device),
            settings: RenderSettings::default(),
            paused: false,
            step_once: false,
            show_frame_time: true,
            controls_open: false,
            controls_button: true,
            selected_material: 0,
            output: None,
            last_instant: None,
            cpu_ms: VecDeque::new(),
            interval_ms: VecDeque::new(),
        })
    }

    /// Applies file changes: shaders rebuild (old pipelines kept on error), the scene re-parses
    /// (last good kept on error; camera and time kept on success).
    fn poll_reload(&mut self) {
        let Some(w) = &self.watcher else { return };
        let changed = w.poll();
        if changed.is_empty() {
            return;
        }
        let shaders: Vec<PathBuf> = changed
            .iter()
            .filter(|p| p.extension().is_some_and(|e| e == "wgsl"))
            .cloned()
            .collect();
        if !shaders.is_empty() {
            self.renderer.reload_shaders(&shaders);
        }
        let ours = self.scene_path.file_name();
        if changed.iter().any(|p| p.file_name() == ours) {
            match read_settled(&self.scene_path) {
                Settled::Text(text) => match scene::parse_scene(&text, &self.scene_path) {
                    Ok(s) => {
                        self.renderer.set_scene(&s);
                        self.sim.replace_scene(s);
                        self.scene_error = None;
                    }
                    Err(d) => self.scene_error = Some(d),
                },
                Settled::NotReady | Settled::Missing => {}
            }
        }
    }

    fn errors(&self) -> Vec<String> {
        let mut v: Vec<String> = self.scene_error.iter().map(|d| d.to_string()).collect();
        v.extend(self.renderer.shader_errors().iter().map(|d| d.to_string()));
        v
    }

    /// Draws the scene filling the available rect; drag orbits, scroll zooms.
    pub fn ui(&mut self, ui: &mut egui::Ui, render_state: &egui_wgpu::RenderState) {
        self.poll_reload();
        let now = Instant::now();
        let dt = self.last_instant.map_or(0.0, |t| (now - t).as_secs_f64());
        self.last_instant = Some(now);
        push(&mut self.interval_ms, dt as f32 * 1e3);
        if !self.paused {
            self.sim.step(dt);
        } else if self.step_once {
            self.sim.step_once();
        }
        self.step_once = false;

        let (rect, response) =
            ui.allocate_exact_size(ui.available_size(), egui::Sense::click_and_drag());
        if response.dragged() {
            let d = response.drag_delta();
            self.sim.camera.orbit(d.x, d.y);
        }
        let aspect = rect.width() / rect.height().max(1.0);
        if response.clicked()
            && let Some(pos) = response.interact_pointer_pos()
        {
            // a click on the water puts the flee point there, half-way down the water column
            let ndc = glam::Vec2::new(
                2.0 * (pos.x - rect.left()) / rect.width() - 1.0,
                1.0 - 2.0 * (pos.y - rect.top()) / rect.height(),
            );
            let level = self.sim.scene.water.level;
            let mid = 0.5 * (level - self.sim.scene.seabed_depth());
            if let Some(p) = self.sim.camera.pose().pick_plane(ndc, aspect, mid) {
                self.sim.flee_point = Some(p);
            }
        }
        if response.hovered() {
            let scroll = ui.input(|i| i.smooth_scroll_delta.y);
            if scroll != 0.0 {
                self.sim.camera.zoom(scroll / 50.0);
            }
        }
        let ppp = ui.ctx().pixels_per_point();
        let size = (
            (rect.width() * ppp).round().max(1.0) as u32,
            (rect.height() * ppp).round().max(1.0) as u32,
        );
        self.ensure_output(render_state, size);
        let out = self.output.as_ref().expect("made above");
        let t0 = Instant::now();
        let snap = self.sim.snapshot();
        self.renderer
            .render(&self.sim.scene, &snap, &self.settings, &out.view, size);
        push(&mut self.cpu_ms, t0.elapsed().as_secs_f32() * 1e3);
        let uv = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
        ui.painter().image(out.id, rect, uv, egui::Color32::WHITE);

        let painter = ui.painter_at(rect);
        if let Some(p) = self.sim.flee_point
            && let Some(ndc) = snap.camera.project(p, aspect)
        {
            let at = egui::pos2(
                rect.left() + (ndc.x + 1.0) * 0.5 * rect.width(),
                rect.top() + (1.0 - ndc.y) * 0.5 * rect.height(),
            );
            painter.circle_stroke(at, 10.0, egui::Stroke::new(2.0, egui::Color32::YELLOW));
            painter.circle_filled(at, 2.5, egui::Color32::YELLOW);
        }
        if self.show_frame_time {
            let text = format!(
                "frame {:.1} ms · render CPU {:.1} ms · t = {:.2} s · {} fish · {}",
                mean(&self.interval_ms),
                mean(&self.cpu_ms),
                self.sim.time_secs(),
                self.sim.fish_count(),
                self.sim.integrator().name()
            );
            painter.text(
                rect.left_top() + egui::vec2(8.0, 8.0),
                egui::Align2::LEFT_TOP,
                text,
                egui::FontId::monospace(13.0),
                egui::Color32::WHITE,
            );
        }
        let mut errors = self.errors();
        errors.extend(self.device_errors.take());
        for (i, e) in errors.iter().enumerate() {
            let first = e.lines().take(3).collect::<Vec<_>>().join("\n");
            painter.text(
                rect.left_bottom() + egui::vec2(8.0, -8.0 - 48.0 * i as f32),
                egui::Align2::LEFT_BOTTOM,
                first,
                egui::FontId::monospace(12.0),
                egui::Color32::from_rgb(255, 120, 100),
            );
        }
        if self.controls_button {
            let button = egui::Rect::from_min_size(
                rect.right_top() + egui::vec2(-88.0, 8.0),
                egui::vec2(80.0, 24.0),
            );
            if ui
                .put(button, egui::Button::new("controls"))
                .on_hover_text("scene controls")
                .clicked()
            {
                self.controls_open = !self.controls_open;
            }
            let mut open = self.controls_open;
            egui::Window::new("Scene controls")
                .open(&mut open)
                .default_pos(rect.right_top() + egui::vec2(-340.0, 40.0))
                .default_width(320.0)
                .vscroll(true)
                .show(ui.ctx(), |ui| self.controls_ui(ui));
            self.controls_open &= open;
        }
        if !self.paused {
            ui.ctx().request_repaint();
        }
    }

    fn ensure_output(&mut self, rs: &egui_wgpu::RenderState, size: (u32, u32)) {
        if self.output.as_ref().is_some_and(|o| o.size == size) {
            return;
        }
        let texture = rs.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("scene view"),
            size: wgpu::Extent3d {
                width: size.0,
                height: size.1,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: OUTPUT_FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        });
        let view = texture.create_view(&Default::default());
        let mut egui_renderer = rs.renderer.write();
        let id = match &self.output {
            Some(o) => {
                egui_renderer.update_egui_texture_from_wgpu_texture(
                    &rs.device,
                    &view,
                    wgpu::FilterMode::Linear,
                    o.id,
                );
                o.id
            }
            None => {
                egui_renderer.register_native_texture(&rs.device, &view, wgpu::FilterMode::Linear)
            }
        };
        self.output = Some(Output {
            size,
            _texture: texture,
            view,
            id,
        });
    }

    /// The teaching panel: technique toggles, debug views, material and wave sliders, fish
    /// count, time control, frame-time readout.
    pub fn controls_ui(&mut self, ui: &mut egui::Ui) {
        let s = &mut self.settings;
        ui.heading("Techniques");
        ui.checkbox(&mut s.env_map, "environment map (sky reflections)");
        ui.checkbox(&mut s.normal_maps, "normal maps");
        ui.checkbox(&mut s.shadows, "shadow map (PCF)");
        ui.checkbox(&mut s.brdf, "Cook–Torrance BRDF (off: Lambert)");
        ui.checkbox(&mut s.fresnel, "Fresnel (Schlick)");
        ui.add(egui::Slider::new(&mut s.exposure, 0.1..=4.0).text("exposure"));
        ui.separator();
        ui.label("Debug view");
        ui.horizontal_wrapped(|ui| {
            for v in DebugView::ALL {
                ui.selectable_value(&mut s.debug_view, v, v.label());
            }
        });
        ui.separator();
        ui.heading("Time");
        ui.horizontal(|ui| {
            let label = if self.paused { "▶ play" } else { "⏸ pause" };
            if ui.button(label).clicked() {
                self.paused = !self.paused;
            }
            if ui
                .add_enabled(self.paused, egui::Button::new("step"))
                .clicked()
            {
                self.step_once = true;
            }
            ui.label(format!("t = {:.2} s", self.sim.time_secs()));
        });
        ui.checkbox(&mut self.show_frame_time, "frame-time readout");
        if ui.button("reset camera").clicked() {
            self.sim.camera = scene::OrbitCamera::from_scene(&self.sim.scene.camera);
        }
        ui.separator();
        self.bodies_ui(ui);
        ui.separator();
        self.fish_ui(ui);
        let sc = &mut self.sim.scene;
        ui.separator();
        ui.heading("Material");
        if !sc.materials.is_empty() {
            self.selected_material = self.selected_material.min(sc.materials.len() - 1);
            egui::ComboBox::from_label("material")
                .selected_text(sc.materials[self.selected_material].name.clone())
                .show_ui(ui, |ui| {
                    for (i, m) in sc.materials.iter().enumerate() {
                        ui.selectable_value(&mut self.selected_material, i, m.name.clone());
                    }
                });
            let m = &mut sc.materials[self.selected_material];
            ui.add(egui::Slider::new(&mut m.metallic, 0.0..=1.0).text("metallic"));
            ui.add(egui::Slider::new(&mut m.roughness, 0.0..=1.0).text("roughness"));
            ui.add(egui::Slider::new(&mut m.reflectance, 0.0..=1.0).text("reflectance"));
            ui.add(egui::Slider::new(&mut m.normal_strength, 0.0..=3.0).text("normal strength"));
            ui.horizontal(|ui| {
                ui.label("base colour");
                ui.color_edit_button_rgb(&mut m.base_color);
            });
        }
        ui.separator();
        ui.heading("Waves");
        ui.add(egui::Slider::new(&mut sc.water.size, 4.0..=200.0).text("water patch (m)"));
        ui.add(egui::Slider::new(&mut sc.water.resolution, 8..=512).text("grid vertices per side"));
        for (i, w) in sc.water.waves.iter_mut().enumerate() {
            ui.collapsing(format!("wave {}", i + 1), |ui| {
                ui.add(egui::Slider::new(&mut w.amplitude, 0.0..=0.5).text("amplitude (m)"));
                ui.add(egui::Slider::new(&mut w.wavelength, 0.2..=30.0).text("wavelength (m)"));
                ui.add(egui::Slider::new(&mut w.steepness, 0.0..=1.0).text("steepness Q"));
                ui.add(egui::Slider::new(&mut w.speed, 0.0..=10.0).text("speed (m/s)"));
            });
        }
        let errors = self.errors();
        if !errors.is_empty() {
            ui.separator();
            for e in errors {
                ui.colored_label(egui::Color32::from_rgb(220, 80, 60), e);
            }
        }
    }
}

impl SceneView {
    /// Rigid bodies: the integrator switch, the step h, drag, and energy / |L| per body.
    fn bodies_ui(&mut self, ui: &mut egui::Ui) {
        ui.heading("Floating bodies");
        let m = &mut self.sim.scene.simulation;
        ui.horizontal_wrapped(|ui| {
            for method in Integrator::ALL {
                ui.selectable_value(&mut m.integrator, method, method.name());
            }
        });
        ui.add(
            egui::Slider::new(&mut m.body_h_secs, 0.002..=0.25)
                .logarithmic(true)
                .text("step h (s)"),
        );
        ui.add(egui::Slider::new(&mut m.linear_drag_per_sec, 0.0..=5.0).text("drag (1/s)"));
        ui.add(
            egui::Slider::new(&mut m.angular_drag_per_sec, 0.0..=5.0).text("angular drag (1/s)"),
        );
        let names: Vec<String> = self
            .sim
            .scene
            .objects
            .iter()
            .map(|o| match o {
                scene::Object::Floating { shape, .. } => match shape {
                    scene::Shape::Box { .. } => "box",
                    scene::Shape::Sphere { .. } => "sphere",
                    scene::Shape::Capsule { .. } => "capsule",
                }
                .to_string(),
                _ => String::new(),
            })
            .collect();
        egui::Grid::new("body readouts")
            .striped(true)
            .show(ui, |ui| {
                for h in [
                    "body",
                    "M (kg)",
                    "E_kin (J)",
                    "M g y (J)",
                    "|L| (kg m²/s)",
                    "resets",
                ] {
                    ui.label(h);
                }
                ui.end_row();
                for r in self.sim.readouts() {
                    ui.label(names.get(r.object_index).cloned().unwrap_or_default());
                    ui.monospace(format!("{:.1}", r.mass_kg));
                    ui.monospace(format!("{:.2}", r.kinetic_j));
                    ui.monospace(format!("{:.2}", r.potential_j));
                    ui.monospace(format!("{:.3}", r.angular_momentum));
                    ui.monospace(format!("{}", r.resets));
                    ui.end_row();
                }
            });
        if ui.button("restart simulation").clicked() {
            self.sim.restart();
        }
    }

    /// The school: count (live; the instance buffer grows), flee point, steering weights.
    fn fish_ui(&mut self, ui: &mut egui::Ui) {
        ui.heading("Fish");
        let p = &mut self.sim.scene.school;
        ui.add(
            egui::Slider::new(&mut p.count, 0..=scene::model::MAX_FISH)
                .logarithmic(true)
                .text("count"),
        );
        ui.add(egui::Slider::new(&mut p.separation_weight, 0.0..=5.0).text("separation"));
        ui.add(egui::Slider::new(&mut p.alignment_weight, 0.0..=5.0).text("alignment"));
        ui.add(egui::Slider::new(&mut p.cohesion_weight, 0.0..=5.0).text("cohesion"));
        ui.add(egui::Slider::new(&mut p.flee_radius, 0.0..=10.0).text("flee radius (m)"));
        let w = self.sim.scene.simulation.school_half_width;
        let mut on = self.sim.flee_point.is_some();
        ui.checkbox(&mut on, "flee point (click on the water to move it)");
        if on {
            let mid = 0.5 * (self.sim.scene.water.level - self.sim.scene.seabed_depth());
            let f = self
                .sim
                .flee_point
                .get_or_insert(glam::Vec3::new(0.0, mid, 0.0));
            ui.add(egui::Slider::new(&mut f.x, -w..=w).text("flee x (m)"));
            ui.add(egui::Slider::new(&mut f.z, -w..=w).text("flee z (m)"));
        } else {
            self.sim.flee_point = None;
        }
    }
}

fn push(q: &mut VecDeque<f32>, v: f32) {
    q.push_back(v);
    if q.len() > 60 {
        q.pop_front();
    }
}

fn mean(q: &VecDeque<f32>) -> f32 {
    if q.is_empty() {
        0.0
    } else {
        q.iter().sum::<f32>() / q.len() as f32
    }
}
