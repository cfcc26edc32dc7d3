//! What the keys do: the app's input is turned into [`Action`]s by the pure key map in
//! [`super::keys`], and applied here, bookmarks included.

use super::ink::InkTool;
use super::keys::{self, Action, KeyMode};
use super::lectern_app::{LecternApp, Mode, Overlay};
use super::tweaks::{apply_declared, write_back};

impl LecternApp {
    /// Takes the keys the app handles out of this frame's input (so slide widgets never see
    /// them) and applies them one by one: after `G` the digits that follow in the same frame
    /// belong to the number, not to bookmarks.
    pub(super) fn handle_keys(&mut self, ctx: &egui::Context) {
        let events = ctx.input(|i| i.events.clone());
        // a text field (the presenter's equation editor) has the keyboard: keys are text
        let editing = ctx.text_edit_focused();
        let mut handled = Vec::with_capacity(events.len());
        for event in &events {
            if editing {
                let action = keys::while_editing(event);
                handled.push(action.is_some());
                if let Some(action) = action {
                    self.apply(action, ctx);
                }
                continue;
            }
            let mode = if matches!(self.overlay, Overlay::Goto(_)) {
                KeyMode::TypingNumber
            } else if self.ink.is_drawing() {
                KeyMode::Drawing
            } else {
                KeyMode::Normal
            };
            handled.push(keys::is_handled(event, mode));
            for action in keys::actions(std::slice::from_ref(event), mode) {
                if self.player && !keys::in_player(action) {
                    continue;
                }
                self.apply(action, ctx);
            }
        }
        ctx.input_mut(|i| {
            let mut flags = handled.into_iter();
            i.events.retain(|_| !flags.next().unwrap_or(false));
            // The window drops these keys' releases: never leave them held in egui's state.
            i.keys_down.retain(|k| !keys::release_is_ignored(*k));
        });
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
            ToggleNotes => self.show_notes = !self.show_notes,
            ToggleFullscreen => {
                let full = ctx.input(|i| i.viewport().fullscreen.unwrap_or(false));
                ctx.send_viewport_cmd(egui::ViewportCommand::Fullscreen(!full));
            }
            ToggleBlack => self.black = !self.black,
            Quit => ctx.send_viewport_cmd(egui::ViewportCommand::Close),
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
                } else if self.ink.stop() {
                    self.say(ctx, "drawing off");
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
            TogglePen => self.toggle_ink(InkTool::Pen, ctx),
            ToggleHighlighter => self.toggle_ink(InkTool::Highlighter, ctx),
            ToggleLaser => self.toggle_ink(InkTool::Laser, ctx),
            InkColor(slot) => {
                self.ink.set_color(slot);
                self.say(ctx, format!("ink colour {}", slot + 1));
            }
            UndoInk => {
                let key = self.current_key();
                let msg = self.ink.undo(&key);
                self.say(ctx, msg);
                ctx.request_repaint();
            }
            ClearInk => {
                let key = self.current_key();
                let msg = self.ink.clear(&key);
                self.say(ctx, msg);
                ctx.request_repaint();
            }
        }
    }

    fn toggle_ink(&mut self, tool: InkTool, ctx: &egui::Context) {
        let msg = self.ink.toggle(tool);
        if self.mode == Mode::Scene {
            self.say(
                ctx,
                format!("{msg} (ink is drawn on slides; Tab returns to them)"),
            );
        } else {
            self.say(ctx, msg);
        }
    }

    /// The key (id, else title) of the slide on screen.
    fn current_key(&self) -> String {
        let deck = self.session.deck();
        deck.slides
            .get(self.session.nav().index())
            .map(|s| s.key().to_owned())
            .unwrap_or_default()
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

/// A swipe across the slide's background that just ended: `Some(true)` for "next" (finger
/// moved left), `Some(false)` for "previous". Mostly sideways and at least a tenth of the
/// slide's width, so a tap or a slip is no swipe.
pub(super) fn swipe(ctx: &egui::Context, background: &egui::Response) -> Option<bool> {
    if !background.drag_stopped() {
        return None;
    }
    let moved = ctx.input(|i| {
        let from = i.pointer.press_origin()?;
        let to = i.pointer.interact_pos()?;
        Some(to - from)
    })?;
    let enough = background.rect.width() * 0.1;
    (moved.x.abs() >= enough && moved.x.abs() > 2.0 * moved.y.abs()).then_some(moved.x < 0.0)
}
