//! The presenting app: one deck session, the slide (or scene) on screen, keys, overlays and
//! hot reload. `frame_ui` is the whole frame, callable from eframe and from egui_kittest alike.
//!
//! This file holds the state and the frame layout; the other jobs live beside it:
//! key actions and bookmarks in [`super::actions`], window placement and the presenter window
//! in [`super::windows`], export, the tweak file and the rehearsal file in [`super::files`].

use std::path::PathBuf;
use std::time::Duration;

use super::frame_stats::FrameClock;
use super::ink::InkState;
use super::ink_draw::paint_on_slide;
use super::offscreen::OffscreenRenderer;
use super::overlays;
use super::pacing::Pacing;
use super::scene_mode::SceneMode;
use super::screens::{MonitorRect, ScreenPlan};
use super::slide_state::{DeckState, SlideState};
use super::slide_view::{ShowControls, SlideOptions, black_ui, slide_ui_with};
use super::theme::Palette;
use super::tweaks::Bookmarks;
use crate::deck::{DeckSession, Nav};
use crate::reload::Reloaded;

/// How long the deck's folder must be quiet after a change before it is reloaded. Editors
/// finish a save (write, rename) within a few milliseconds; 150 ms made a save take ~300 ms to
/// reach the screen. An empty file mid-save is skipped anyway, and a half-written one shows
/// its error only until the rest of the save arrives a tick later.

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
    /// Ink on the slides (`DECK.ink.ron`) and the drawing tools.
    pub(super) ink: InkState,
    /// Wall time between drawn frames (`--frame-stats`, the scene panel's readout).
    pub(super) frames: FrameClock,
    /// What the window is cleared to before the frame is painted ([`Self::clear_color32`]).
    pub(super) clear: egui::Color32,
    /// Drawing into a window cleared to [`Self::clear_color32`]: what that colour already
    /// covers (the slide's background, the letterbox around the overview and the presenter
    /// view, the black screen) is not painted again. On a software rasteriser each
    /// window-sized rectangle costs tens of milliseconds of CPU per frame.
    pub(super) window_clear: bool,
    /// The web player: only the keys a page can honour, and its own `?` list.
    pub(super) player: bool,
    /// `N`: the speaker notes under the slide.
    pub(super) show_notes: bool,
}

impl LecternApp {
    pub fn new(session: DeckSession) -> Self {
        let ink = InkState::for_deck(session.path());
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
            ink,
            frames: FrameClock::default(),
            clear: egui::Color32::BLACK,
            window_clear: false,
            player: false,
            show_notes: false,
        }
    }

    /// The web player's app: the desktop's keys less those a page cannot honour (presenter,
    /// ink, files, quit), and the player's `?` list.
    pub fn set_player(&mut self) {
        self.player = true;
    }

    /// Whether `N` put the speaker notes under the slide.
    pub fn notes_shown(&self) -> bool {
        self.show_notes
    }

    /// See [`Self::clear_color32`]: on in the window (eframe clears it to that colour), off
    /// for headless renders and egui_kittest, whose targets are not cleared to it.
    pub fn set_window_clear(&mut self, on: bool) {
        self.window_clear = on;
    }

    /// The colour under everything the last frame painted: the slide's background, the
    /// letterbox colour, or black.
    pub fn clear_color32(&self) -> egui::Color32 {
        self.clear
    }

    /// `--frame-stats FILE`: append `mode,frame_ms` to `path` for every drawn frame.
    pub fn set_frame_stats(&mut self, path: &std::path::Path) -> std::io::Result<()> {
        self.frames = FrameClock::with_file(path)?;
        Ok(())
    }

    /// Starts hot reload: the deck's folder is watched and `ctx` repainted on each change.
    pub fn watch(&mut self, ctx: &egui::Context) {
        let ctx = ctx.clone();
        if let Err(e) = self
            .session
            .watch(crate::reload::DEBOUNCE, move || ctx.request_repaint())
        {
            tracing::warn!("hot reload is off: {e}");
        }
    }

    pub fn session(&self) -> &DeckSession {
        &self.session
    }

    /// The session, to navigate from outside a frame (the web player's `#/N`).
    pub fn session_mut(&mut self) -> &mut DeckSession {
        &mut self.session
    }

    /// The current slide's first plot widget's points as JSON (the web player's test hook;
    /// the numbers `export --data` writes, see [`super::plot_data`]).
    pub fn first_plot_json(&mut self) -> String {
        let index = self.session.nav().index();
        let Some(slide) = self.session.deck().slides.get(index) else {
            return "null".into();
        };
        super::plot_data::first_plot_json(slide, self.states.slide(slide))
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

    /// The ink and the drawing tools.
    pub fn ink(&self) -> &InkState {
        &self.ink
    }

    /// Applies file changes seen by the watcher. Cheap when nothing changed.
    pub fn pump_reload(&mut self) {
        let (changed, outcome) = self.session.pump_changes();
        if !changed.is_empty() {
            self.ink.on_changes(&changed);
        }
        if let Some(Reloaded::Updated) = outcome {
            self.states.retain_deck(self.session.deck());
            self.session.take_replaced();
            self.pacing
                .set_deck(self.session.deck(), self.session.nav().index());
        }
        // problem files the widgets read (`ode: File(..)`) reload the same way
        let others = self.session.take_other_changes();
        if !others.is_empty() {
            self.states.reload_problem_files(&others);
        }
    }

    /// One whole frame: reload, keys, the slide or scene, overlays.
    pub fn frame_ui(&mut self, ui: &mut egui::Ui) {
        let ctx = ui.ctx().clone();
        self.frames.tick(
            ctx.cumulative_frame_nr(),
            self.mode,
            web_time::Instant::now(),
        );
        self.pump_reload();
        self.handle_keys(&ctx);
        self.track_pace(&ctx);
        self.place_audience(&ctx);
        if self.presenter_window {
            self.show_presenter_window(&ctx);
        }
        if self.presenter_overlay {
            self.clear = Palette::of(crate::deck::Theme::Dark).letterbox;
            self.presenter_ui(ui);
            return;
        }

        let deck = self.session.deck();
        let palette = Palette::of(deck.theme);
        let index = self.session.nav().index();
        let fill = !self.window_clear;
        self.clear = match (self.mode, &self.overlay) {
            _ if self.black => egui::Color32::BLACK,
            (Mode::Slides, Overlay::Overview) | (Mode::Scene, _) => palette.letterbox,
            (Mode::Slides, _) => palette.background,
        };
        match (self.mode, &self.overlay) {
            (_, _) if self.black => {
                if fill {
                    black_ui(ui);
                }
            }
            (Mode::Slides, Overlay::Overview) => {
                let picked = overlays::overview_ui(ui, deck, index, &mut self.states, fill);
                if let Some(i) = picked {
                    self.session.navigate(|nav, deck| nav.go(deck, i));
                    self.overlay = Overlay::None;
                }
            }
            (Mode::Slides, _) => {
                let slide = &deck.slides[index];
                let now = ctx.input(|i| i.time);
                let drawing = self.ink.is_drawing() && self.overlay == Overlay::None;
                let options = SlideOptions {
                    drawing,
                    background: fill,
                    // `C` brings the widgets' controls onto the audience screen
                    controls: match self.show_controls {
                        true => ShowControls::Always,
                        false => ShowControls::AsDeck,
                    },
                    ..SlideOptions::default()
                };
                let (slide_rect, notes_rect) = if self.show_notes {
                    let all = ui.available_rect_before_wrap();
                    let split = all.top() + all.height() * 0.72;
                    let (top, bottom) = all.split_top_bottom_at_y(split);
                    (top, Some(bottom))
                } else {
                    (ui.available_rect_before_wrap(), None)
                };
                let state = self.states.slide(slide);
                let resp = ui
                    .scope_builder(egui::UiBuilder::new().max_rect(slide_rect), |ui| {
                        slide_ui_with(ui, deck, index, state, options)
                    })
                    .inner;
                if let Some(rect) = notes_rect {
                    let editor = self.player.then(|| self.states.slide(slide));
                    overlays::notes_under_slide_ui(ui, rect, &slide.notes, &palette, editor);
                }
                let (key, theme) = (slide.key().to_owned(), deck.theme);
                // The pointer first, then the ink: a stroke shows in the frame it is drawn.
                let mut said = None;
                if drawing {
                    said = self.ink.input_ui(&ctx, &key, &resp);
                } else if self.overlay == Overlay::None {
                    // a click on the slide (not on a widget) is "next"; a swipe pages
                    let paged = match super::actions::swipe(&ctx, &resp.background) {
                        Some(forward) => Some(forward),
                        None => resp.background.clicked().then_some(true),
                    };
                    match paged {
                        Some(true) => {
                            self.session.navigate(|nav, deck| nav.next(deck));
                        }
                        Some(false) => {
                            self.session.navigate(|nav, deck| nav.prev(deck));
                        }
                        None => {}
                    }
                }
                paint_on_slide(ui, &resp, theme, &self.ink.view(&key, now));
                if let Some(msg) = said {
                    self.say(&ctx, msg);
                }
            }
            (Mode::Scene, _) => self.scene_ui(ui, &palette),
        }
        match &self.overlay {
            Overlay::Help => {
                let lines = if self.player {
                    super::keys::PLAYER_HELP
                } else {
                    super::keys::HELP
                };
                overlays::help_ui(ui, &palette, lines)
            }
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
                // The panel belongs to the presenter window, or to `C`: no button for the
                // audience. A page has neither: there the button opens it.
                view.controls_button = self.player;
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
/// `frame_ms` is the app's own wall time between drawn frames (what `--frame-stats` writes):
/// on a software renderer the GPU work dominates and a CPU-side timer would flatter it.
pub(super) fn scene_panel_ui(
    scene: &mut Option<Result<SceneMode, String>>,
    frame_ms: Option<f32>,
    ui: &mut egui::Ui,
) {
    if let Some(ms) = frame_ms {
        ui.label(format!(
            "frame {ms:.0} ms ({:.1} fps), wall time between drawn frames",
            1e3 / ms.max(1e-3)
        ));
    }
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

/// `scenes/water.ron` beside the deck's folder (`slides/../scenes`), else under the current
/// one, else the water scene built into lectern.
fn default_scene_path(session: &DeckSession) -> PathBuf {
    let beside = session.folder().join("../scenes/water.ron");
    let here = PathBuf::from(crate::scene::DEFAULT_SCENE);
    // (project files: in the web player the bundle's, where export put the bundled scene)
    if crate::project_files::is_file(&beside) {
        beside
    } else if crate::project_files::is_file(&here) {
        here
    } else {
        crate::bundled::bundled_scene_file().unwrap_or(here)
    }
}

impl eframe::App for LecternApp {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        if self.render_state.is_none() {
            self.render_state = frame.wgpu_render_state().cloned();
            let software = self.render_state.as_ref().is_some_and(|rs| {
                rs.adapter.get_info().device_type == egui_wgpu::wgpu::DeviceType::Cpu
            });
            self.ink.set_plain_edges(software);
        }
        // Scene widgets on slides render on the window's device and animate there (in a
        // browser: WebGL2, at the browser's render scale).
        if let Some(rs) = &self.render_state
            && crate::widgets::scene::SceneGpu::get(ui.ctx()).is_none()
        {
            let scale = crate::widgets::scene::SceneGpu::render_scale_for(&rs.adapter);
            crate::widgets::scene::SceneGpu::install(ui.ctx(), rs.clone(), scale, true);
        }
        self.window_clear = true;
        self.frame_ui(ui);
    }

    /// The root window is cleared to what lies under the frame (see [`Self::clear_color32`]).
    /// (eframe clears the presenter's window, an immediate viewport, to black.)
    fn clear_color(&self, _visuals: &egui::Visuals) -> [f32; 4] {
        self.clear.to_normalized_gamma_f32()
    }
}
