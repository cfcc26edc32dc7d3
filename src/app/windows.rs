//! Windows and screens: where the audience window goes on the first frame, and the presenter
//! view (in its own window, or in this one with `P`).

use super::ink_draw::paint_on_slide;
use super::lectern_app::{LecternApp, Mode, scene_panel_ui};
use super::presenter::{PresenterInfo, SceneControls, presenter_ui};
use super::screens::{MonitorRect, ScreenPlan};

impl LecternApp {
    /// The monitors found at start and the plan made from them: with a presenter window,
    /// the audience window (this one) goes full-screen on its monitor on the first frame.
    pub fn set_screens(&mut self, monitors: Vec<MonitorRect>, plan: ScreenPlan) {
        self.presenter_window = plan.has_presenter_window();
        self.screens = monitors;
        self.screen_plan = plan;
        self.placed = false;
    }

    pub fn screen_plan(&self) -> &ScreenPlan {
        &self.screen_plan
    }

    /// First frame: move the audience window onto its monitor, size it to it (a bare X server
    /// without a window manager ignores the full-screen hint) and make it full-screen there.
    pub(super) fn place_audience(&mut self, ctx: &egui::Context) {
        if self.placed {
            return;
        }
        self.placed = true;
        let ScreenPlan::Dual {
            audience: Some(i), ..
        } = self.screen_plan
        else {
            return;
        };
        let Some(m) = self.screens.get(i) else {
            return;
        };
        let [x, y] = m.pos_points();
        let [w, h] = m.size_points();
        let root = egui::ViewportId::ROOT;
        ctx.send_viewport_cmd_to(root, egui::ViewportCommand::OuterPosition(egui::pos2(x, y)));
        ctx.send_viewport_cmd_to(root, egui::ViewportCommand::InnerSize(egui::vec2(w, h)));
        ctx.send_viewport_cmd_to(root, egui::ViewportCommand::SetMonitor(i));
    }

    /// The presenter view in `ui`: current and next slide, notes, timer, controls, problems.
    pub fn presenter_ui(&mut self, ui: &mut egui::Ui) {
        let deck = self.session.deck();
        let index = self.session.nav().index();
        let mut problems: Vec<String> = self
            .session
            .error()
            .map(|e| e.to_string())
            .into_iter()
            .chain(self.ink.problem().map(|e| format!("ink ignored: {e}")))
            .collect();
        if let Some(slide) = deck.slides.get(index) {
            problems.extend(self.states.slide(slide).problems().iter().cloned());
        }
        let mut marks: Vec<(u8, String)> = deck
            .bookmarks
            .iter()
            .map(|b| (b.key, format!("{} ({})", b.label, b.slide)))
            .collect();
        for k in 1..=9u8 {
            if let Some((slide, _)) = self.bookmarks.get(k) {
                marks.retain(|(key, _)| *key != k);
                marks.push((k, format!("stored on {slide}")));
            }
        }
        marks.sort();
        let now = ui.input(|i| i.time);
        let key_of = |i: usize| deck.slides.get(i).map_or("", |s| s.key());
        let drawing = self.ink.is_drawing() && self.mode == Mode::Slides;
        let info = PresenterInfo {
            pace: self.pacing.report(),
            problems: &problems,
            bookmarks: &marks,
            ink_next: self.ink.view(key_of(index + 1), now),
            drawing,
            fill_window: !self.window_clear,
        };
        // In scene mode the scene's panel replaces the slide and its controls.
        let frame_ms = self.frames.mean_ms();
        let mut scene_panel = |ui: &mut egui::Ui| scene_panel_ui(&mut self.scene, frame_ms, ui);
        let scene: Option<SceneControls> = (self.mode == Mode::Scene).then_some(&mut scene_panel);
        let resp = presenter_ui(ui, deck, index, &mut self.states, &info, scene);
        // Drawing on the presenter's current slide; the audience window, drawn later in this
        // same pass, shows the new ink at once.
        let Some(resp) = resp else {
            return;
        };
        let ctx = ui.ctx().clone();
        let said = if drawing {
            self.ink.input_ui(&ctx, key_of(index), &resp)
        } else {
            None
        };
        paint_on_slide(ui, &resp, deck.theme, &self.ink.view(key_of(index), now));
        if let Some(msg) = said {
            self.say(&ctx, msg);
        }
    }

    pub(super) fn show_presenter_window(&mut self, ctx: &egui::Context) {
        let id = egui::ViewportId::from_hash_of("lectern-presenter");
        let mut builder = egui::ViewportBuilder::default()
            .with_title("lectern — presenter")
            .with_inner_size([1280.0, 800.0]);
        // On its own monitor (the laptop's), the presenter window fills it.
        if let ScreenPlan::Dual {
            presenter: Some(i), ..
        } = self.screen_plan
            && let Some(m) = self.screens.get(i)
        {
            builder = builder
                .with_position(m.pos_points())
                .with_inner_size(m.size_points())
                .with_maximized(true);
        }
        ctx.show_viewport_immediate(id, builder, |ui, _class| {
            let ctx = ui.ctx().clone();
            if ctx.input(|i| i.viewport().close_requested()) {
                self.presenter_window = false;
                return;
            }
            self.handle_keys(&ctx);
            self.presenter_ui(ui);
        });
    }
}
