//! Scene mode in the app: owns the water scene's simulation and steps it, takes the mouse
//! (orbit, zoom, the flee point), reloads `scenes/*.ron` through [`LiveFile`] and `shaders/`
//! through the [`SceneHost`] (the Scene widget's host too: renderer, folders, one watcher
//! polled on the UI thread), holds the quality controller, and draws the renderer's output
//! straight into egui's pass over the window (a paint callback: on a software rasteriser a full-window texture drawn again by
//! egui cost ~30 ms a frame). The renderer only draws what it is given. Its teaching panel is
//! in [`super::scene_panel`].

use std::collections::VecDeque;
use std::path::{Path, PathBuf};
use web_time::Instant;

use anyhow::Result;

use crate::reload::{LiveFile, Reloaded};
use crate::render::gpu::UncapturedErrors;
use crate::render::{OutputDraw, RenderSettings};
use crate::scene::{self, FrameSnapshot, QualityController, Scene, SceneSim};
use crate::widgets::scene::host::SceneHost;

/// The scene's output drawn inside egui's render pass, over the rect it was added for.
struct SceneOutput(OutputDraw);

impl egui_wgpu::CallbackTrait for SceneOutput {
    fn paint(
        &self,
        _info: egui::PaintCallbackInfo,
        pass: &mut wgpu::RenderPass<'static>,
        _resources: &egui_wgpu::CallbackResources,
    ) {
        // egui has set the viewport to the rect: the full-screen triangle fills just that
        self.0.draw(pass);
    }
}

pub struct SceneMode {
    /// the renderer and the watched shader and scene folders (shared with the Scene widget's)
    pub(super) host: SceneHost,
    pub(super) sim: SceneSim,
    /// the scene file, last good version and newest error
    scene_file: LiveFile<Scene>,
    device_errors: UncapturedErrors,
    pub settings: RenderSettings,
    pub(super) quality: QualityController,
    pub paused: bool,
    pub(super) step_once: bool,
    /// the frame-time line over the picture (off: the audience does not see it)
    pub show_frame_time: bool,
    /// the teaching panel as a floating window over the scene (a "controls" button opens it);
    /// a presenter view that shows the panel on its own screen sets `controls_button` false
    pub controls_open: bool,
    pub controls_button: bool,
    pub(super) selected_material: usize,
    snapshot: Option<FrameSnapshot>,
    last_instant: Option<Instant>,
    pub(super) cpu_ms: VecDeque<f32>,
    pub(super) interval_ms: VecDeque<f32>,
    /// the simulation's share of a frame (the school, the bodies), ms
    pub(super) step_ms: VecDeque<f32>,
    /// the interval before the newest drawn frame, until [`Self::take_drawn_frame`] reads it
    drawn: Option<f32>,
    /// scene frames drawn so far (the web player's hook measures fps in the page from it)
    frames_drawn: u64,
}

impl SceneMode {
    /// Loads the scene (an error here is fatal: there is no last good scene yet), builds the
    /// renderer and starts watching `scenes/` and `shaders/` (`wake` is called on a change).
    pub fn new(
        render_state: &egui_wgpu::RenderState,
        scene_path: &Path,
        wake: impl Fn() + Send + 'static,
    ) -> Result<Self> {
        let scene_file = LiveFile::open(scene_path, scene::parse_scene);
        let scene = match (scene_file.value(), scene_file.error()) {
            (Some(s), _) => s.clone(),
            (None, Some(d)) => return Err(d.clone().into()),
            (None, None) => anyhow::bail!("{}: no scene", scene_path.display()),
        };
        let host = SceneHost::new(
            render_state,
            scene_path,
            &scene,
            // the output is drawn into egui's pass over the window
            render_state.target_format,
            Some(Box::new(wake)),
        )
        .map_err(anyhow::Error::msg)?;
        Ok(Self {
            host,
            quality: QualityController::new(scene.quality),
            sim: SceneSim::new(scene),
            scene_file,
            device_errors: UncapturedErrors::install(&render_state.device),
            settings: RenderSettings::default(),
            paused: false,
            step_once: false,
            // off the audience's picture: the presenter panel and the controls (`C`) show it
            show_frame_time: false,
            controls_open: false,
            controls_button: true,
            selected_material: 0,
            snapshot: None,
            last_instant: None,
            cpu_ms: VecDeque::new(),
            interval_ms: VecDeque::new(),
            step_ms: VecDeque::new(),
            drawn: None,
            frames_drawn: 0,
        })
    }

    /// Applies file changes: shaders rebuild (old pipelines kept on error), the scene reloads
    /// through its [`LiveFile`] (last good kept on error; camera and time kept on success).
    fn poll_reload(&mut self) {
        // the host has applied the shaders among them
        let changed = self.host.poll();
        if !changed.is_empty() {
            self.apply_scene_changes(&changed);
        }
    }

    /// What a batch of changed paths does (public for tests that drive reloads directly).
    pub fn apply_changes(&mut self, changed: &[PathBuf]) {
        self.host.apply_shaders(changed);
        self.apply_scene_changes(changed);
    }

    fn apply_scene_changes(&mut self, changed: &[PathBuf]) {
        if self.scene_file.on_changes(changed) == Reloaded::Updated
            && let Some(s) = self.scene_file.value()
        {
            let s = s.clone();
            self.host.renderer.set_scene(&s);
            self.quality.set_mode(s.quality);
            self.sim.replace_scene(s);
        }
    }

    /// The reload problems: the scene file's, then the shaders'.
    pub fn errors(&self) -> Vec<String> {
        let mut v: Vec<String> = self
            .scene_file
            .error()
            .iter()
            .map(|d| d.to_string())
            .collect();
        v.extend(
            self.host
                .renderer
                .shader_errors()
                .iter()
                .map(|d| d.to_string()),
        );
        v
    }

    /// Once per drawn scene frame: the wall time since the previous one, ms (for
    /// `--frame-stats`, which labels it `scene`). `None` when no frame was drawn since.
    pub fn take_drawn_frame(&mut self) -> Option<f32> {
        self.drawn.take()
    }

    /// How many scene frames [`Self::ui`] has drawn.
    pub fn frames_drawn(&self) -> u64 {
        self.frames_drawn
    }

    /// Steps the simulation by the real time since the last frame (or one step when asked).
    fn step(&mut self) -> f32 {
        let now = Instant::now();
        let dt = self.last_instant.map_or(0.0, |t| (now - t).as_secs_f64());
        self.last_instant = Some(now);
        if !self.paused {
            self.sim.step(dt);
        } else if self.step_once {
            self.sim.step_once();
        }
        self.step_once = false;
        dt as f32 * 1e3
    }

    /// Orbit on drag, zoom on scroll, and a click on the water puts the flee point there,
    /// half-way down the water column.
    fn input(&mut self, ui: &egui::Ui, response: &egui::Response, rect: egui::Rect) {
        if response.dragged() {
            let d = response.drag_delta();
            self.sim.camera.orbit(d.x, d.y);
        }
        let aspect = rect.width() / rect.height().max(1.0);
        if response.clicked()
            && let Some(pos) = response.interact_pointer_pos()
        {
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
    }

    /// Draws the scene filling the available rect; drag orbits, scroll zooms.
    pub fn ui(&mut self, ui: &mut egui::Ui, render_state: &egui_wgpu::RenderState) {
        self.poll_reload();
        let t_step = Instant::now();
        let interval = self.step();
        push(&mut self.step_ms, t_step.elapsed().as_secs_f32() * 1e3);
        push(&mut self.interval_ms, interval);
        if self.last_instant.is_some() && interval > 0.0 {
            self.quality.observe(interval);
            self.drawn = Some(interval);
        }
        let rung = self.quality.settings();
        self.settings.apply_rung(&rung);
        self.sim.set_school_every(rung.school_every);

        let (rect, response) =
            ui.allocate_exact_size(ui.available_size(), egui::Sense::click_and_drag());
        self.input(ui, &response, rect);
        let ppp = ui.ctx().pixels_per_point();
        let size = (
            (rect.width() * ppp).round().max(1.0) as u32,
            (rect.height() * ppp).round().max(1.0) as u32,
        );
        let t0 = Instant::now();
        let snap = self.snapshot.get_or_insert_with(|| self.sim.snapshot());
        self.sim.snapshot_into(snap);
        let enc = self
            .host
            .renderer
            .encode_scene(&self.sim.scene, snap, &self.settings, size);
        render_state.queue.submit([enc.finish()]);
        self.frames_drawn += 1;
        if let Some(output) = self.host.renderer.output(&self.settings) {
            ui.painter().add(egui_wgpu::Callback::new_paint_callback(
                rect,
                SceneOutput(output),
            ));
        }
        push(&mut self.cpu_ms, t0.elapsed().as_secs_f32() * 1e3);
        crate::widgets::scene::legend::legend_ui(ui, rect, self.settings.debug_view);
        self.overlay_ui(ui, rect);
        if self.controls_button {
            self.controls_window_ui(ui, rect);
        }
        if !self.paused {
            ui.ctx().request_repaint();
        }
    }

    /// The flee point's ring, the frame-time line and the reload errors over the scene.
    fn overlay_ui(&mut self, ui: &egui::Ui, rect: egui::Rect) {
        let painter = ui.painter_at(rect);
        let aspect = rect.width() / rect.height().max(1.0);
        if let Some(p) = self.sim.flee_point
            && let Some(ndc) = self.sim.camera.pose().project(p, aspect)
        {
            let at = egui::pos2(
                rect.left() + (ndc.x + 1.0) * 0.5 * rect.width(),
                rect.top() + (1.0 - ndc.y) * 0.5 * rect.height(),
            );
            painter.circle_stroke(at, 10.0, egui::Stroke::new(2.0, egui::Color32::YELLOW));
            painter.circle_filled(at, 2.5, egui::Color32::YELLOW);
        }
        if self.show_frame_time {
            let info = self.host.renderer.frame_info();
            let text = format!(
                "frame {:.1} ms · render CPU {:.1} ms · {}×{} px · t = {:.2} s · {} fish · {}",
                mean(&self.interval_ms),
                mean(&self.cpu_ms),
                info.render_size.0,
                info.render_size.1,
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
    }

    /// The "controls" button and the floating panel it opens (when no presenter view shows
    /// the panel).
    fn controls_window_ui(&mut self, ui: &mut egui::Ui, rect: egui::Rect) {
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
}

pub(super) fn push(q: &mut VecDeque<f32>, v: f32) {
    q.push_back(v);
    if q.len() > 60 {
        q.pop_front();
    }
}

pub(super) fn mean(q: &VecDeque<f32>) -> f32 {
    if q.is_empty() {
        0.0
    } else {
        q.iter().sum::<f32>() / q.len() as f32
    }
}
