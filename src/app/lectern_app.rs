//! The presenting app: one deck session, the slide (or scene) on screen, keys, overlays and
//! hot reload. `frame_ui` is the whole frame, callable from eframe and from egui_kittest alike.

use std::path::PathBuf;
use std::time::Duration;

use super::keys::{self, Action};
use super::offscreen::OffscreenRenderer;
use super::overlays;
use super::pacing::Pacing;
use super::presenter::{PresenterInfo, presenter_ui};
use super::screens::{MonitorRect, ScreenPlan};
use super::slide_view::{DeckState, SlideState, black_ui, slide_ui};
use super::theme::Palette;
use super::tweak_file::{TweakFile, tweak_file_path};
use super::tweaks::{Bookmarks, apply_declared, write_back};
use crate::deck::{DeckSession, Nav};
use crate::reload::Reloaded;
use crate::render::SceneView;

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
    session: DeckSession,
    states: DeckState,
    mode: Mode,
    overlay: Overlay,
    black: bool,
    /// A short message and the time (egui seconds) it disappears.
    toast: Option<(String, f64)>,
    /// The eframe wgpu state, for scene mode; `None` in tests without a window.
    pub render_state: Option<egui_wgpu::RenderState>,
    /// The water scene file scene mode shows.
    pub scene_path: PathBuf,
    /// Created on the first `Tab` (it needs the GPU); an error is shown in its place.
    scene: Option<Result<SceneView, String>>,
    /// `C`: the live controls (scene panel) on the audience screen.
    show_controls: bool,
    pacing: Pacing,
    /// The slide the pacing clock is counting for.
    paced_index: usize,
    bookmarks: Bookmarks,
    /// `P` on a single screen: the window shows the presenter view instead of the slide.
    presenter_overlay: bool,
    /// A second window with the presenter view (the main window stays the audience's).
    pub presenter_window: bool,
    /// Rehearsal: actual times per slide are written to this file on every slide change.
    pub rehearsal_file: Option<PathBuf>,
    offscreen: Option<OffscreenRenderer>,
    /// The monitors seen at start and where the windows go (see [`super::screens`]).
    screens: Vec<MonitorRect>,
    screen_plan: ScreenPlan,
    /// The audience window was sent to its monitor.
    placed: bool,
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
    fn place_audience(&mut self, ctx: &egui::Context) {
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

    /// Takes the keys the app handles out of this frame's input (so slide widgets never see
    /// them) and applies them one by one: after `G` the digits that follow in the same frame
    /// belong to the number, not to bookmarks.
    fn handle_keys(&mut self, ctx: &egui::Context) {
        let events = ctx.input(|i| i.events.clone());
        let mut handled = Vec::with_capacity(events.len());
        for event in &events {
            let typing = matches!(self.overlay, Overlay::Goto(_));
            handled.push(keys::is_handled(event, typing));
            for action in keys::actions(std::slice::from_ref(event), typing) {
                self.apply(action, ctx);
            }
        }
        ctx.input_mut(|i| {
            let mut flags = handled.into_iter();
            i.events.retain(|_| !flags.next().unwrap_or(false));
        });
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

    fn write_rehearsal(&self) {
        if let Some(file) = &self.rehearsal_file {
            let text = self.pacing.rehearsal_ron(self.session.deck());
            if let Err(e) = crate::deck::write_back::write_atomic(file, &text) {
                tracing::warn!("cannot write {}: {e}", file.display());
            }
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

    /// The presenter view in `ui`: current and next slide, notes, timer, controls, problems.
    pub fn presenter_ui(&mut self, ui: &mut egui::Ui) {
        let deck = self.session.deck();
        let index = self.session.nav().index();
        let mut problems: Vec<String> = self
            .session
            .error()
            .map(|e| e.to_string())
            .into_iter()
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
        let info = PresenterInfo {
            pace: self.pacing.report(),
            problems: &problems,
            bookmarks: &marks,
        };
        // In scene mode the scene's panel replaces the slide and its controls.
        let mut scene_panel = |ui: &mut egui::Ui| match &mut self.scene {
            Some(Ok(view)) => view.controls_ui(ui),
            Some(Err(e)) => {
                ui.label(format!("The scene could not start: {e}"));
            }
            None => {
                ui.label("The scene is starting…");
            }
        };
        let scene: Option<super::presenter::SceneControls> =
            (self.mode == Mode::Scene).then_some(&mut scene_panel);
        presenter_ui(ui, deck, index, &mut self.states, &info, scene);
    }

    fn show_presenter_window(&mut self, ctx: &egui::Context) {
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

    /// Writes the live tweaks of every slide to `DECK.tweaks.ron` beside the deck (for
    /// `lectern export --with-tweaks`); returns the file, or why it could not be written.
    pub fn save_tweak_file(&mut self) -> Result<PathBuf, String> {
        let file = tweak_file_path(self.session.path());
        let tweaks = TweakFile::from_states(self.session.deck(), &mut self.states);
        crate::deck::write_back::write_atomic(&file, &tweaks.to_ron())
            .map_err(|e| format!("cannot write {}: {e}", file.display()))?;
        Ok(file)
    }

    /// `E`: the current slide, exactly as shown (live tweaks included), to a PNG beside the
    /// deck, and the live tweaks of all slides to `DECK.tweaks.ron`.
    fn export_current(&mut self, ctx: &egui::Context) {
        if let Err(e) = self.save_tweak_file() {
            tracing::warn!("{e}");
        }
        let index = self.session.nav().index();
        let folder = self.session.folder();
        if self.offscreen.is_none() {
            match OffscreenRenderer::new() {
                Ok(r) => self.offscreen = Some(r),
                Err(e) => return self.say(ctx, e.to_string()),
            }
        }
        let deck = self.session.deck();
        let slide = &deck.slides[index];
        let state = self.states.slide(slide);
        let Some(r) = self.offscreen.as_mut() else {
            return;
        };
        let file = folder.join(format!("{}-live.png", slide.key()));
        let msg = match r.render_slide(deck, index, state, [1920, 1080]) {
            Ok(img) => match img.save(&file) {
                Ok(()) => format!("exported {}", file.display()),
                Err(e) => format!("cannot write {}: {e}", file.display()),
            },
            Err(e) => e.to_string(),
        };
        self.say(ctx, msg);
    }

    /// Scene mode: the water scene (made on first use), with its panel when `C` is on.
    fn scene_ui(&mut self, ui: &mut egui::Ui, palette: &Palette) {
        let Some(rs) = self.render_state.clone() else {
            overlays::scene_placeholder_ui(ui, palette, "Scene mode needs the window's GPU.");
            return;
        };
        let path = self.scene_path.clone();
        let scene = self
            .scene
            .get_or_insert_with(|| SceneView::new(&rs, &path).map_err(|e| format!("{e:#}")));
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

    fn say(&mut self, ctx: &egui::Context, message: impl Into<String>) {
        let now = ctx.input(|i| i.time);
        self.toast = Some((message.into(), now + 2.5));
    }

    /// Does what a key asks.
    pub fn apply(&mut self, action: Action, ctx: &egui::Context) {
        use Action::*;
        // The number prompt takes digits, Enter, Backspace and Esc; everything else closes it.
        if let Overlay::Goto(typed) = &mut self.overlay {
            match action {
                GotoDigit(d) => {
                    if typed.len() < 4 {
                        typed.push(char::from(b'0' + d));
                    }
                    return;
                }
                GotoBackspace => {
                    typed.pop();
                    return;
                }
                GotoConfirm => {
                    let typed = std::mem::take(typed);
                    self.overlay = Overlay::None;
                    if let Ok(n) = typed.parse::<usize>() {
                        let r = self.session.navigate(|nav, deck| nav.goto_number(deck, n));
                        if let Err(msg) = r {
                            self.say(ctx, msg);
                        }
                    }
                    return;
                }
                _ => self.overlay = Overlay::None,
            }
            if action == Escape {
                return;
            }
        }
        match action {
            Next => {
                self.session.navigate(|nav, deck| nav.next(deck));
            }
            Prev => {
                self.session.navigate(|nav, deck| nav.prev(deck));
            }
            First => {
                self.session.navigate(|nav, deck| nav.first(deck));
            }
            Last => {
                self.session.navigate(|nav, deck| nav.last(deck));
            }
            GotoStart => self.overlay = Overlay::Goto(String::new()),
            ToggleOverview => self.toggle_overlay(Overlay::Overview),
            ToggleHelp => self.toggle_overlay(Overlay::Help),
            ToggleFullscreen => {
                let full = ctx.input(|i| i.viewport().fullscreen.unwrap_or(false));
                ctx.send_viewport_cmd(egui::ViewportCommand::Fullscreen(!full));
            }
            ToggleBlack => self.black = !self.black,
            ToggleMode => {
                self.mode = match self.mode {
                    Mode::Slides => Mode::Scene,
                    Mode::Scene => Mode::Slides,
                }
            }
            Escape => {
                let full = ctx.input(|i| i.viewport().fullscreen.unwrap_or(false));
                if self.overlay != Overlay::None {
                    self.overlay = Overlay::None;
                } else if self.black {
                    self.black = false;
                } else if full {
                    ctx.send_viewport_cmd(egui::ViewportCommand::Fullscreen(false));
                }
            }
            GotoDigit(_) | GotoBackspace | GotoConfirm => {}
            ToggleControls => self.show_controls = !self.show_controls,
            TogglePresenter => self.presenter_overlay = !self.presenter_overlay,
            ResetTweaks => {
                let index = self.session.nav().index();
                if let Some(state) = self.slide_state(index) {
                    state.reset();
                }
                self.say(ctx, "tweaks reset to the file's values");
            }
            BookmarkStore(k) => {
                let deck = self.session.deck();
                let slide = &deck.slides[self.session.nav().index()];
                self.bookmarks.store(k, slide, self.states.slide(slide));
                self.say(ctx, format!("bookmark {k} stored"));
            }
            BookmarkRecall(k) => self.recall(k, ctx),
            TimerPause => {
                let now = ctx.input(|i| i.time);
                self.pacing.toggle_pause(now);
            }
            TimerReset => {
                let now = ctx.input(|i| i.time);
                self.pacing.reset(now);
            }
            ExportSlide => self.export_current(ctx),
            WriteBack => {
                // The tweaks file first: once written back they are no longer tweaks.
                if let Err(e) = self.save_tweak_file() {
                    tracing::warn!("{e}");
                }
                let deck = self.session.deck();
                let slide = &deck.slides[self.session.nav().index()];
                let path = self.session.path().to_path_buf();
                let msg = match write_back(&path, slide, self.states.slide(slide)) {
                    Ok(0) => "nothing tweaked on this slide".to_owned(),
                    Ok(n) => format!("wrote {n} value(s) into {}", path.display()),
                    Err(e) => format!("write-back failed: {e}"),
                };
                self.say(ctx, msg);
            }
        }
    }

    /// `1…9`: a stored bookmark if there is one, else the deck's declared one.
    fn recall(&mut self, k: u8, ctx: &egui::Context) {
        if let Some((key, snapshot)) = self.bookmarks.get(k).cloned() {
            let Some(i) = self.session.deck().find(&key) else {
                return self.say(ctx, format!("bookmark {k}: slide {key} is gone"));
            };
            self.session.navigate(|nav, deck| nav.go(deck, i));
            let slide = &self.session.deck().slides[i];
            self.states.slide(slide).restore(slide, &snapshot);
            return self.say(ctx, format!("bookmark {k}"));
        }
        let Some(decl) = self
            .session
            .deck()
            .bookmarks
            .iter()
            .find(|b| b.key == k)
            .cloned()
        else {
            return self.say(ctx, format!("no bookmark {k} (Ctrl+{k} stores one)"));
        };
        let Some(i) = self.session.deck().find(&decl.slide) else {
            return self.say(ctx, format!("bookmark {k}: no slide {}", decl.slide));
        };
        self.session.navigate(|nav, deck| nav.go(deck, i));
        let slide = &self.session.deck().slides[i];
        apply_declared(&decl, slide, self.states.slide(slide));
        self.say(ctx, format!("bookmark {k}: {}", decl.label));
    }

    fn toggle_overlay(&mut self, overlay: Overlay) {
        self.overlay = if self.overlay == overlay {
            Overlay::None
        } else {
            overlay
        };
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
