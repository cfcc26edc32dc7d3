//! Widget 12: the water scene on a slide. The deck declares the view (final image or a debug
//! view), the technique toggles, the camera and the simulation time; the widget steps its own
//! [`SceneSim`] to that time (the stepping lives here, never in `render/`) and draws it with the
//! scene renderer, [`crate::render::Renderer`], into an offscreen texture on egui's own wgpu
//! device, shown as an egui image.
//!
//! The device and the renderers come from [`SceneGpu`], which the app (window) and
//! `app::offscreen` (export, tests) put into the egui context: one renderer per scene file, shared
//! by every Scene widget on every slide (two side by side, the presenter's copy), so pipelines
//! and the sky cube are built once. A frame is rendered only when what it shows changed (toggles,
//! camera, time, a larger size) or, in the window, while playing; a slide that does not show the
//! widget never makes one, so it costs nothing there.

pub mod gpu;
pub mod host;
pub mod legend;

use std::path::{Path, PathBuf};

use gpu::Output;
pub use gpu::SceneGpu;

use super::{Param, SlideWidget, style};
use crate::deck::widgets::scene::{
    DISTANCE_RANGE_M, PITCH_RANGE_DEG, SceneSpec, SceneToggles, SceneView, TARGET_RANGE_M,
    TIME_RANGE_S, YAW_RANGE_DEG,
};
use crate::reload::{LiveFile, Reloaded};
use crate::render::{DebugView, RenderSettings};
use crate::scene::{Scene, SceneSim};

/// While playing in the window, at most this many scene frames per second: on a software
/// adapter a frame of the full school costs a large part of a second.
const PLAYING_FPS: f64 = 12.0;

/// What the widget says where it has no device to draw on (a headless path without one; in the
/// web player the device is the page's WebGL2 one, without which no slide draws at all).
const NO_GPU_NOTE: &str = "the live scene needs the window's GPU";
/// Drawn in the slide's first frame: the scene's own first frame (the renderer, and the
/// simulation stepped to `time_s`: 480 steps at 8 s, ~3 s in a browser on SwiftShader) is the
/// next one, so paging shows the slide at once instead of freezing on the previous one.
const PREPARING_NOTE: &str = "preparing the scene…";

/// Everything a frame depends on: when it is unchanged the texture already holds the frame.
#[derive(Debug, Clone, PartialEq)]
struct FrameKey {
    settings: RenderSettings,
    camera: [f32; 3],
    steps_time_s: f64,
    size: (u32, u32),
    /// the shaders and scene file as saved (see [`SceneGpu::poll_files`])
    files_generation: u64,
}

pub struct SceneWidget {
    pub spec: SceneSpec,
    initial: SceneSpec,
    scene_path: Result<PathBuf, String>,
    /// the scene file in the app's one last-good holder (`None` when its path was refused)
    scene_file: Option<LiveFile<Scene>>,
    /// the simulation of the scene file's last good version
    sim: Option<SceneSim>,
    output: Option<Output>,
    drawn: Option<FrameKey>,
    render_error: Option<String>,
    /// egui's clock at the last advanced frame while playing
    last_time: Option<f64>,
    frames_rendered: u64,
    /// the generation of the scene's files the simulation was loaded at
    files_generation: u64,
    /// the device and renderers this widget draws with, from its first frame: its shader
    /// problems are read from the techniques' own holders when asked, never copied
    gpu: Option<SceneGpu>,
    /// a frame has shown the slide with [`PREPARING_NOTE`] where the picture will be
    announced: bool,
}

fn debug_view(view: SceneView) -> DebugView {
    match view {
        SceneView::Final => DebugView::None,
        SceneView::ShadowMap => DebugView::ShadowMap,
        SceneView::Normals => DebugView::Normals,
        SceneView::EnvCube => DebugView::EnvCube,
        SceneView::CausticsMap => DebugView::CausticsMap,
    }
}

/// The toggles as mutable bools, in [`SceneToggles::ALL_IDS`] order; an unset one takes the
/// renderer's default (on). A new technique is one more line here.
fn toggles_mut(t: &mut SceneToggles) -> [(&'static str, &'static str, &mut bool); 6] {
    let on = RenderSettings::default();
    [
        (
            "env_map",
            "environment map",
            t.env_map.get_or_insert(on.env_map),
        ),
        (
            "normal_maps",
            "normal maps",
            t.normal_maps.get_or_insert(on.normal_maps),
        ),
        ("shadows", "shadows", t.shadows.get_or_insert(on.shadows)),
        ("brdf", "Cook–Torrance BRDF", t.brdf.get_or_insert(on.brdf)),
        ("fresnel", "Fresnel", t.fresnel.get_or_insert(on.fresnel)),
        (
            "caustics",
            "caustics",
            t.caustics.get_or_insert(on.caustics),
        ),
    ]
}

/// The render settings `spec` asks for, at `render_scale`.
pub fn render_settings(spec: &SceneSpec, render_scale: f32) -> RenderSettings {
    let on = RenderSettings::default();
    let t = &spec.toggles;
    RenderSettings {
        env_map: t.env_map.unwrap_or(on.env_map),
        normal_maps: t.normal_maps.unwrap_or(on.normal_maps),
        shadows: t.shadows.unwrap_or(on.shadows),
        brdf: t.brdf.unwrap_or(on.brdf),
        fresnel: t.fresnel.unwrap_or(on.fresnel),
        caustics: t.caustics.unwrap_or(on.caustics),
        debug_view: debug_view(spec.view),
        render_scale,
        ..on
    }
}

impl SceneWidget {
    /// The widget; `base_dir` is the deck's folder (the scene file is resolved against it,
    /// inside the project only).
    pub fn new_in(spec: SceneSpec, base_dir: Option<&Path>) -> Self {
        let resolved = match base_dir {
            Some(dir) => crate::paths::resolve_in(dir, &spec.scene),
            None => Ok(PathBuf::from(&spec.scene)),
        };
        let scene_path = crate::bundled::scene_file(resolved, &spec.scene).map(|f| f.path);
        let started = web_time::Instant::now();
        let scene_file = (scene_path.as_ref().ok())
            .map(|p| LiveFile::open(p.clone(), crate::scene::parse_scene));
        let sim = (scene_file.as_ref())
            .and_then(LiveFile::value)
            .map(|scene| SceneSim::new(scene.clone()));
        tracing::debug!("scene widget: scene loaded in {:?}", started.elapsed());
        let mut spec = spec;
        // The camera's unset values are the scene file's, so the presenter's sliders start there.
        if let Some(sim) = &sim {
            let c = &sim.scene.camera;
            let cam = &mut spec.camera;
            cam.yaw_deg.get_or_insert(c.yaw_deg as f64);
            cam.pitch_deg.get_or_insert(c.pitch_deg as f64);
            cam.distance.get_or_insert(c.distance as f64);
        }
        Self {
            initial: spec.clone(),
            spec,
            scene_path,
            scene_file,
            sim,
            output: None,
            drawn: None,
            render_error: None,
            last_time: None,
            frames_rendered: 0,
            files_generation: 0,
            gpu: None,
            announced: false,
        }
    }

    /// After a save of the scene file or a shader: the scene file is re-read through its
    /// holder (the last good scene stays when it does not parse); the renderer's shader errors
    /// stay in its techniques' holders, where [`SlideWidget::problems`] reads them.
    fn reload_files(&mut self, gpu: &SceneGpu) {
        self.gpu.get_or_insert_with(|| gpu.clone());
        let (Ok(path), Some(file)) = (&self.scene_path, &mut self.scene_file) else {
            return;
        };
        let generation = gpu.poll_files(path);
        if generation == self.files_generation {
            return;
        }
        self.files_generation = generation;
        if file.reload() == Reloaded::Updated
            && let Some(scene) = file.value()
        {
            let unchanged = self.sim.as_ref().is_some_and(|s| s.scene == *scene);
            if !unchanged {
                // a new simulation; `prepare` puts it at the deck's time and camera
                self.sim = Some(SceneSim::new(scene.clone()));
                self.last_time = None;
            }
        }
    }

    /// How many scene frames the widget has rendered (it renders only when its picture changes).
    pub fn frames_rendered(&self) -> u64 {
        self.frames_rendered
    }

    /// The simulation the widget shows (after the last `ui`).
    pub fn sim(&self) -> Option<&SceneSim> {
        self.sim.as_ref()
    }

    /// Puts the simulation where the spec says: camera, and (unless playing in the window)
    /// the time `time_s`. Returns the simulation time shown.
    fn prepare(&mut self, ui: &egui::Ui, gpu: &SceneGpu) -> Option<f64> {
        let sim = self.sim.as_mut()?;
        let cam = &self.spec.camera;
        if let Some(y) = cam.yaw_deg {
            sim.camera.yaw_deg = y as f32;
        }
        if let Some(p) = cam.pitch_deg {
            sim.camera.pitch_deg = p.clamp(PITCH_RANGE_DEG.0, PITCH_RANGE_DEG.1) as f32;
        }
        if let Some(d) = cam.distance {
            sim.camera.distance = d.clamp(DISTANCE_RANGE_M.0, DISTANCE_RANGE_M.1) as f32;
        }
        if let Some(t) = cam.target {
            let at = |v: f64| v.clamp(TARGET_RANGE_M.0, TARGET_RANGE_M.1) as f32;
            sim.camera.target = glam::Vec3::new(at(t[0]), at(t[1]), at(t[2]));
        }
        if self.spec.playing && gpu.animate {
            let now = ui.input(|i| i.time);
            let due = self.last_time.is_none_or(|t| now - t >= 1.0 / PLAYING_FPS);
            match self.last_time {
                None => {
                    sim.set_time(self.spec.time_s.clamp(TIME_RANGE_S.0, TIME_RANGE_S.1));
                    self.last_time = Some(now);
                }
                Some(t) if due => {
                    sim.step((now - t).min(0.25));
                    self.last_time = Some(now);
                }
                Some(_) => {}
            }
            ui.ctx()
                .request_repaint_after(std::time::Duration::from_secs_f64(1.0 / PLAYING_FPS));
        } else {
            self.last_time = None;
            let wanted = self.spec.time_s.clamp(TIME_RANGE_S.0, TIME_RANGE_S.1);
            if (sim.time_secs() - wanted).abs() > 0.5 * sim.dt_secs() {
                sim.set_time(wanted);
            }
        }
        Some(sim.time_secs())
    }

    /// Renders the frame if anything it shows changed since the last one.
    fn render_if_changed(&mut self, gpu: &SceneGpu, size: (u32, u32), time_s: f64) {
        if Output::ensure(&mut self.output, &gpu.render_state, size) {
            self.drawn = None;
        }
        let Some(size) = self.output.as_ref().map(|o| o.size) else {
            return;
        };
        let settings = render_settings(&self.spec, gpu.render_scale);
        let (Some(sim), Ok(path), Some(out)) = (&self.sim, &self.scene_path, &self.output) else {
            return;
        };
        let key = FrameKey {
            settings,
            camera: [
                sim.camera.yaw_deg,
                sim.camera.pitch_deg,
                sim.camera.distance,
            ],
            steps_time_s: time_s,
            size,
            files_generation: self.files_generation,
        };
        if self.drawn.as_ref() == Some(&key) {
            return;
        }
        let started = web_time::Instant::now();
        let snap = sim.snapshot();
        let result = gpu.with_renderer(path, &sim.scene, |r| {
            r.render(&sim.scene, &snap, &settings, &out.view, size);
        });
        tracing::debug!(
            "scene widget: {}x{} frame recorded in {:?}",
            size.0,
            size.1,
            started.elapsed()
        );
        self.render_error = result.err();
        self.drawn = Some(key);
        self.frames_rendered += 1;
    }

    /// Why there is no picture at all: the path refused, the scene never loaded, or the
    /// renderer failed.
    fn problem(&self) -> Option<String> {
        if let Err(why) = &self.scene_path {
            return Some(why.clone());
        }
        if self.sim.is_none() {
            let why = self.scene_file.as_ref().and_then(LiveFile::error);
            return Some(
                why.map_or_else(|| "the scene did not load".to_owned(), |d| d.to_string()),
            );
        }
        self.render_error.clone()
    }
}

/// One line of text where the picture goes (why there is none, or none yet).
fn note_ui(ui: &egui::Ui, rect: egui::Rect, text: &str, color: egui::Color32) {
    ui.painter_at(rect).text(
        rect.center(),
        egui::Align2::CENTER_CENTER,
        text,
        egui::TextStyle::Body.resolve(ui.style()),
        color,
    );
}

impl SlideWidget for SceneWidget {
    fn ui(&mut self, ui: &mut egui::Ui) {
        style::projector_text(ui);
        let avail = ui.available_rect_before_wrap();
        let height = avail.height() * self.spec.height.clamp(0.1, 1.0) as f32;
        let rect = egui::Rect::from_min_size(avail.min, egui::vec2(avail.width(), height));
        let response = ui.allocate_rect(rect, egui::Sense::drag());
        if let Some(why) = self.problem() {
            note_ui(ui, rect, &why, style::DIVERGED);
            return;
        }
        let Some(gpu) = SceneGpu::get(ui.ctx()) else {
            note_ui(ui, rect, NO_GPU_NOTE, style::ink(ui));
            return;
        };
        if self.output.is_none() && !self.announced {
            self.announced = true;
            note_ui(ui, rect, PREPARING_NOTE, style::ink(ui));
            ui.ctx().request_repaint();
            return;
        }
        // Drag orbits, as in scene mode (0.3° per point).
        if response.dragged() {
            let d = response.drag_delta();
            let cam = &mut self.spec.camera;
            let yaw = cam.yaw_deg.get_or_insert(0.0);
            *yaw = (*yaw - 0.3 * d.x as f64).rem_euclid(360.0);
            let pitch = cam.pitch_deg.get_or_insert(30.0);
            *pitch = (*pitch + 0.3 * d.y as f64).clamp(PITCH_RANGE_DEG.0, PITCH_RANGE_DEG.1);
        }
        self.reload_files(&gpu);
        let Some(time_s) = self.prepare(ui, &gpu) else {
            return;
        };
        let ppp = ui.ctx().pixels_per_point();
        let size = (
            (rect.width() * ppp).round().clamp(1.0, 4096.0) as u32,
            (rect.height() * ppp).round().clamp(1.0, 4096.0) as u32,
        );
        self.render_if_changed(&gpu, size, time_s);
        if let Some(out) = &self.output {
            let uv = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
            ui.painter_at(rect)
                .image(out.id, rect, uv, egui::Color32::WHITE);
            legend::legend_ui(ui, rect, debug_view(self.spec.view));
        }
    }

    fn params(&mut self) -> Vec<Param<'_>> {
        let spec = &mut self.spec;
        let mut out: Vec<Param<'_>> = toggles_mut(&mut spec.toggles)
            .into_iter()
            .map(|(id, label, v)| Param::bool(format!("toggles.{id}"), label, v))
            .collect();
        let cam = &mut spec.camera;
        out.push(Param::f64(
            "camera.yaw_deg",
            "camera yaw (°)",
            cam.yaw_deg.get_or_insert(0.0),
            YAW_RANGE_DEG.0,
            YAW_RANGE_DEG.1,
        ));
        out.push(Param::f64(
            "camera.pitch_deg",
            "camera pitch (°)",
            cam.pitch_deg.get_or_insert(30.0),
            PITCH_RANGE_DEG.0,
            PITCH_RANGE_DEG.1,
        ));
        out.push(Param::f64_log(
            "camera.distance",
            "camera distance (m)",
            cam.distance.get_or_insert(10.0),
            DISTANCE_RANGE_M.0,
            DISTANCE_RANGE_M.1,
        ));
        out.push(Param::bool("playing", "playing", &mut spec.playing));
        out
    }

    fn reset(&mut self) {
        self.spec = self.initial.clone();
        self.last_time = None;
    }

    fn spec(&self) -> crate::widgets::WidgetSpec {
        crate::widgets::WidgetSpec::Scene(self.spec.clone())
    }

    fn problems(&self) -> Vec<String> {
        let mut out: Vec<String> = self.problem().into_iter().collect();
        // the last good pipelines keep drawing while a technique's shader is broken
        if let (Some(gpu), Ok(path)) = (&self.gpu, &self.scene_path) {
            out.extend(gpu.shader_errors(path));
        }
        // a broken save while the last good scene is shown
        if self.sim.is_some()
            && let Some(d) = self.scene_file.as_ref().and_then(LiveFile::error)
        {
            out.push(d.to_string());
        }
        out
    }
}
