//! The presenting app: one deck session, the slide (or scene) on screen, keys, overlays and
//! hot reload. `frame_ui` is the whole frame, callable from eframe and from egui_kittest alike.
//!
//! This file holds the state and the frame layout; the other jobs live beside it:
//! key actions and bookmarks in [`super::actions`], window placement and the presenter window
//! in [`super::windows`], export, the tweak file and the rehearsal file in [`super::files`].

use std::path::PathBuf;
use std::time::Duration;

use super::offscreen::OffscreenRenderer;
use super::overlays;
use super::pacing::Pacing;
use super::scene_mode::SceneMode;
use super::screens::{MonitorRect, ScreenPlan};
use super::slide_view::{DeckState, SlideState, black_ui, slide_ui};
use super::theme::Palette;
use super::tweaks::Bookmarks;
use crate::deck::{DeckSession, Nav};
use crate::reload::Reloaded;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    Slides,
    Scene,
}

#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Overlay {
    None,
    Help,
    Overview,
    /// `G` pressed; the digits typed so far.
    Goto(String),
}

pub struct LecternApp {
    pub(super) session: DeckSession,
    pub(super) states: DeckState,
    pub(super) mode: Mode,
    pub(super) overlay: Overlay,
    pub(super) black: bool,
    /// A short message and the time (egui seconds) it disappears.
    pub(super) toast: Option<(String, f64)>,
    /// The eframe wgpu state, for scene mode; `None` in tests without a window.
    pub render_state: Option<egui_wgpu::RenderState>,
    /// The water scene file scene mode shows.
    pub scene_path: PathBuf,
    /// Created on the first `Tab` (it needs the GPU); an error is shown in its place.
    pub(super) scene: Option<Result<SceneMode, String>>,
    /// `C`: the live controls (scene panel) on the audience screen.
    pub(super) show_controls: bool,
    pub(super) pacing: Pacing,
    /// The slide the pacing clock is counting for.
    pub(super) paced_index: usize,
    pub(super) bookmarks: Bookmarks,
    /// `P` on a single screen: the window shows the presenter view instead of the slide.
    pub(super) presenter_overlay: bool,
    /// A second window with the presenter view (the main window stays the audience's).
    pub presenter_window: bool,
    /// Rehearsal: actual times per slide are written to this file on every slide change.
    pub rehearsal_file: Option<PathBuf>,
    pub(super) offscreen: Option<OffscreenRenderer>,
    /// The monitors seen at start and where the windows go (see [`super::screens`]).
    pub(super) screens: Vec<MonitorRect>,
    pub(super) screen_plan: ScreenPlan,
    /// The audience window was sent to its monitor.
    pub(super) placed: bool,
}

impl LecternApp {
    pub fn new(session: DeckSession) -> Self {
        Self {
            states: DeckState::default(),
            mode: Mode::Slides,
            overlay: Overlay::None,
            black: false,
            toast: None,
            render_state: None,
            scene_path: default_scene_path(&session),
            pacing: Pacing::new(session.deck()),
            paced_index: session.nav().index(),
            session,
            scene: None,
            show_controls: false,
            bookmarks: Bookmarks::default(),
            presenter_overlay: false,
            presenter_window: false,
            rehearsal_file: None,
            offscreen: None,
            screens: Vec::new(),
            screen_plan: ScreenPlan::Single,
            placed: false,
        }
    }

    /// Starts hot reload: the deck's folder is watched and `ctx` repainted on each change.
    pub fn watch(&mut self, ctx: &egui::Context) {
        let ctx = ctx.clone();
        if let Err(e) = self
            .session
            .watch(Duration::from_millis(150), move || ctx.request_repaint())
        {
            tracing::warn!("hot reload is off: {e}");
        }
    }

    pub fn session(&self) -> &DeckSession {
        &self.session
    }

    pub fn nav(&self) -> &Nav {
        self.session.nav()
    }

    pub fn mode(&self) -> Mode {
        self.mode
    }

    pub fn overlay(&self) -> &Overlay {
        &self.overlay
    }

    pub fn is_black(&self) -> bool {
        self.black
    }

    /// Applies file changes seen by the watcher. Cheap when nothing changed.
    pub fn pump_reload(&mut self) {
        if let Some(Reloaded::Updated) = self.session.pump() {
            self.states.retain_deck(self.session.deck());
            self.session.take_replaced();
            self.pacing
                .set_deck(self.session.deck(), self.session.nav().index());
        }
    }

    /// One whole frame: reload, keys, the slide or scene, overlays.
    pub fn frame_ui(&mut self, ui: &mut egui::Ui) {
        self.pump_reload();
        let ctx = ui.ctx().clone();
        self.handle_keys(&ctx);
        self.track_pace(&ctx);
        self.place_audience(&ctx);
        if self.presenter_window {
            self.show_presenter_window(&ctx);
        }
        if self.presenter_overlay {
            self.presenter_ui(ui);
            return;
        }

        let deck = self.session.deck();
        let palette = Palette::of(deck.theme);
        let index = self.session.nav().index();
        match (self.mode, &self.overlay) {
            (_, _) if self.black => black_ui(ui),
            (Mode::Slides, Overlay::Overview) => {
                let picked = overlays::overview_ui(ui, deck, index, &mut self.states);
                if let Some(i) = picked {
                    self.session.navigate(|nav, deck| nav.go(deck, i));
                    self.overlay = Overlay::None;
                }
            }
            (Mode::Slides, _) => {
                let slide = &deck.slides[index];
                let resp = slide_ui(ui, deck, index, self.states.slide(slide));
                if resp.background.clicked() && self.overlay == Overlay::None {
                    self.session.navigate(|nav, deck| nav.next(deck));
                }
            }
            (Mode::Scene, _) => self.scene_ui(ui, &palette),
        }
        match &self.overlay {
            Overlay::Help => overlays::help_ui(ui, &palette),
            Overlay::Goto(typed) => {
                overlays::goto_ui(ui, typed, self.session.deck().slides.len(), &palette)
            }
            Overlay::None | Overlay::Overview => {}
        }
        // With a presenter window the audience never sees errors; alone, a small notice.
        if let Some(err) = self.session.error()
            && !self.presenter_window
        {
            overlays::error_notice_ui(ui, err, &palette);
        } else if !self.presenter_window
            && self.mode == Mode::Slides
            && !self.black
            && self.overlay != Overlay::Overview
            && let Some(slide) = self.session.deck().slides.get(index)
            && let Some(problem) = self.states.slide(slide).problems().first()
        {
            // e.g. a formula over its time budget: alone, the lecturer must see it too
            overlays::slide_problem_notice_ui(ui, &problem.clone(), &palette);
        }
        let now = ctx.input(|i| i.time);
        if let Some((msg, until)) = &self.toast {
            if now < *until {
                overlays::toast_ui(ui, msg, &palette);
                ctx.request_repaint_after(Duration::from_secs_f64(until - now));
            } else {
                self.toast = None;
            }
        }
    }

    /// Feeds the pacing clock: time since the last frame counts for the slide on screen.
    fn track_pace(&mut self, ctx: &egui::Context) {
        let now = ctx.input(|i| i.time);
        let index = self.session.nav().index();
        if index != self.paced_index {
            self.pacing.goto(index, now);
            self.paced_index = index;
            self.write_rehearsal();
        } else {
            self.pacing.tick(now);
        }
        if self.presenter_window || self.presenter_overlay {
            ctx.request_repaint_after(Duration::from_millis(500));
        }
    }

    /// The pacing state (for tests and the presenter view).
    pub fn pacing(&self) -> &Pacing {
        &self.pacing
    }

    /// The live state of slide `index` (its widgets and tweaks).
    pub fn slide_state(&mut self, index: usize) -> Option<&mut SlideState> {
        let slide = self.session.deck().slides.get(index)?;
        Some(self.states.slide(slide))
    }

    pub(super) fn say(&mut self, ctx: &egui::Context, message: impl Into<String>) {
        let now = ctx.input(|i| i.time);
        self.toast = Some((message.into(), now + 2.5));
    }
}

// ---- Scene mode: everything the app does for the water scene, kept together. ----

impl LecternApp {
    /// Scene mode: the water scene (made on first use), with its panel when `C` is on.
    fn scene_ui(&mut self, ui: &mut egui::Ui, palette: &Palette) {
        let Some(rs) = self.render_state.clone() else {
            overlays::scene_placeholder_ui(ui, palette, "Scene mode needs the window's GPU.");
            return;
        };
        let path = self.scene_path.clone();
        let ctx = ui.ctx().clone();
        let scene = self.scene.get_or_insert_with(|| {
            SceneMode::new(&rs, &path, move || ctx.request_repaint()).map_err(|e| format!("{e:#}"))
        });
        match scene {
            Ok(view) => {
                // The panel belongs to the presenter window, or to `C`: no button for the audience.
                view.controls_button = false;
                if self.show_controls {
                    egui::Panel::right("lectern-scene-controls")
                        .resizable(true)
                        .show(ui, |ui| {
                            egui::ScrollArea::vertical().show(ui, |ui| view.controls_ui(ui));
                        });
                }
                view.ui(ui, &rs);
            }
            Err(e) => {
                let msg = format!("The scene could not start: {e}");
                overlays::scene_placeholder_ui(ui, palette, &msg);
            }
        }
    }
}

/// The scene's panel for the presenter view (it takes the place of the current slide).
/// A free function so the presenter view can borrow the scene beside the deck state.
pub(super) fn scene_panel_ui(scene: &mut Option<Result<SceneMode, String>>, ui: &mut egui::Ui) {
    match scene {
        Some(Ok(view)) => view.controls_ui(ui),
        Some(Err(e)) => {
            ui.label(format!("The scene could not start: {e}"));
        }
        None => {
            ui.label("The scene is starting…");
        }
    }
}

/// `scenes/water.ron` beside the deck's folder (`slides/../scenes`), else under the current one.
fn default_scene_path(session: &DeckSession) -> PathBuf {
    let beside = session.folder().join("../scenes/water.ron");
    if beside.exists() {
        beside
    } else {
        PathBuf::from("scenes/water.ron")
    }
}

impl eframe::App for LecternApp {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        if self.render_state.is_none() {
            self.render_state = frame.wgpu_render_state().cloned();
        }
        self.frame_ui(ui);
    }
}
