//! What the scene shows, for the web player's test hook (`window.lectern.scene()`,
//! `sceneToggle`: `src/web/scene_hook.rs`): where the slide's first Scene widget was drawn and
//! what it reports, and scene mode's frame count, quality rung, render size and backend line.
//! Plain data from the app's state; compiled everywhere so it is tested natively.

use super::lectern_app::{LecternApp, Mode};
use crate::widgets::ParamSnapshot;

impl LecternApp {
    /// The scene as JSON: `{"mode", "gpu", "widget": {x, y, w, h (CSS px), problems} | null,
    /// "sceneMode": {frames, rung, renderSize, backend, errors} | null}`.
    pub fn scene_json(&mut self, ctx: &egui::Context) -> String {
        let widget = super::drawn_widgets(ctx)
            .into_iter()
            .find(|w| w.kind == "scene" && w.slide == self.nav().index());
        let widget = widget.map(|w| {
            let problems = self.scene_widget_problems(w.slide, &w.path);
            serde_json::json!({
                "x": w.drawn.min.x, "y": w.drawn.min.y,
                "w": w.drawn.width(), "h": w.drawn.height(),
                "problems": problems,
            })
        });
        let scene_mode = match &self.scene {
            Some(Ok(view)) => serde_json::json!({
                "frames": view.frames_drawn(),
                "rung": view.quality.rung(),
                "renderSize": view.host.renderer.frame_info().render_size,
                "backend": view.host.backend_line(),
                "errors": view.errors(),
                // means over the last 60 frames: wall time between frames, the simulation
                // step, and recording + submitting the frame (the GPU's work is not in it)
                "frameMs": super::scene_mode::mean(&view.interval_ms),
                "stepMs": super::scene_mode::mean(&view.step_ms),
                "recordMs": super::scene_mode::mean(&view.cpu_ms),
            }),
            Some(Err(e)) => serde_json::json!({ "errors": [e] }),
            None => serde_json::Value::Null,
        };
        serde_json::json!({
            "mode": if self.mode == Mode::Scene { "scene" } else { "slides" },
            "gpu": crate::widgets::scene::SceneGpu::get(ctx).is_some(),
            "widget": widget,
            "sceneMode": scene_mode,
        })
        .to_string()
    }

    /// Sets technique `id` (`shadows`, `caustics`, … as in the deck's `toggles:`) of the
    /// current slide's first drawn Scene widget, or of scene mode when it is shown: what the
    /// controls' tick box does. False when there is no such toggle.
    pub fn set_scene_toggle(&mut self, ctx: &egui::Context, id: &str, on: bool) -> bool {
        if self.mode == Mode::Scene {
            let Some(Ok(view)) = &mut self.scene else {
                return false;
            };
            let s = &mut view.settings;
            let field = match id {
                "env_map" => &mut s.env_map,
                "normal_maps" => &mut s.normal_maps,
                "shadows" => &mut s.shadows,
                "brdf" => &mut s.brdf,
                "fresnel" => &mut s.fresnel,
                "caustics" => &mut s.caustics,
                _ => return false,
            };
            *field = on;
            return true;
        }
        let index = self.nav().index();
        let Some(w) =
            (super::drawn_widgets(ctx).into_iter()).find(|w| w.kind == "scene" && w.slide == index)
        else {
            return false;
        };
        let Some(slide) = self.session.deck().slides.get(index).cloned() else {
            return false;
        };
        let state = self.states.slide(&slide);
        state.set_param(&w.path, &format!("toggles.{id}"), ParamSnapshot::Bool(on))
    }

    /// Scene mode's school size, as its panel's "count" slider sets it (the browser benchmark
    /// measures what fewer fish buy). False when scene mode has not started.
    pub fn set_scene_fish(&mut self, count: usize) -> bool {
        let Some(Ok(view)) = &mut self.scene else {
            return false;
        };
        view.sim.scene.school.count = count.min(crate::scene::model::MAX_FISH);
        true
    }

    fn scene_widget_problems(&mut self, index: usize, path: &[usize]) -> Vec<String> {
        let Some(slide) = self.session.deck().slides.get(index).cloned() else {
            return Vec::new();
        };
        (self.states.slide(&slide).widget_at(path))
            .map(|w| w.problems())
            .unwrap_or_default()
    }
}
