//! The presenter's screen: the current slide with its live controls, the next slide, the
//! speaker notes, the timer (per slide and overall, ahead or behind plan) and any problems
//! (reload errors, formulas that do not typeset). Never shown to the audience unless asked.

use egui::{Color32, Rect, RichText, UiBuilder, vec2};

use super::ink_draw::InkView;
use super::pacing::{PaceReport, clock};
use super::slide_state::{DeckState, SlideResponse};
use super::slide_view::{SlideOptions, slide_ui_with};
use super::theme::{self, Palette};
use crate::deck::{Deck, Theme};

/// Everything the presenter view shows besides the deck itself.
pub struct PresenterInfo<'a> {
    pub pace: PaceReport,
    pub problems: &'a [String],
    /// Labels of the bookmarks set (key, label).
    pub bookmarks: &'a [(u8, String)],
    /// Ink on the next slide. (The current slide's is painted by the caller, after it has
    /// taken the pointer: see [`presenter_ui`]'s result.)
    pub ink_next: InkView<'a>,
    /// A drawing tool is on: the current slide takes the pointer for ink.
    pub drawing: bool,
    /// Paint the window's background. A window that is cleared to (nearly) that colour anyway
    /// skips it: on a software rasteriser a window-sized rectangle costs tens of ms of CPU.
    pub fill_window: bool,
}

impl<'a> PresenterInfo<'a> {
    /// The timer, problems and bookmarks; no ink, not drawing, the window's background painted.
    pub fn new(pace: PaceReport, problems: &'a [String], bookmarks: &'a [(u8, String)]) -> Self {
        Self {
            pace,
            problems,
            bookmarks,
            ink_next: InkView::default(),
            drawing: false,
            fill_window: true,
        }
    }
}

/// In scene mode: the scene's control panel, which takes the place of the current slide.
pub type SceneControls<'a> = &'a mut dyn FnMut(&mut egui::Ui);

pub fn presenter_ui(
    ui: &mut egui::Ui,
    deck: &Deck,
    index: usize,
    states: &mut DeckState,
    info: &PresenterInfo,
    scene: Option<SceneControls>,
) -> Option<SlideResponse> {
    let mut now_response = None;
    theme::install_fonts(ui.ctx());
    let palette = Palette::of(Theme::Dark);
    let full = ui.available_rect_before_wrap();
    if info.fill_window {
        ui.painter().rect_filled(full, 0.0, palette.letterbox);
    }
    let pad = (full.width() / 80.0).max(8.0);
    let area = full.shrink(pad);
    let left_w = area.width() * 0.62;
    let left = Rect::from_min_size(area.min, vec2(left_w - pad * 0.5, area.height()));
    let right = Rect::from_min_max(
        egui::pos2(area.min.x + left_w + pad * 0.5, area.min.y),
        area.max,
    );
    let text = (full.height() / 40.0).clamp(12.0, 26.0);
    let serif = theme::family_or_default(ui.ctx(), theme::SERIF);

    // Left: the current slide as the audience sees it, then its controls.
    let ratio = deck.aspect.ratio();
    // A slide with live widgets leaves half the height to its controls (sliders and equation
    // fields), so at 1280×720 they are in view without scrolling; one without takes more.
    // While a typed equation is previewed, the slide shrinks further: the preview's plot is
    // what the lecturer reads then (the room's view is unchanged).
    let now_slide = deck.slides.get(index);
    let has_controls = now_slide.is_some_and(|s| !s.widgets().is_empty());
    let typing = now_slide
        .and_then(|s| states.existing(s))
        .is_some_and(|s| s.has_preview());
    let now_share = match (typing, has_controls) {
        (true, _) => 0.3,
        (false, true) => 0.5,
        (false, false) => 0.68,
    };
    let now_h = (left.width() / ratio).min(left.height() * now_share);
    let now_rect =
        Rect::from_min_size(left.min + vec2(0.0, text * 1.5), vec2(now_h * ratio, now_h));
    if let Some(scene_controls) = scene {
        // The audience sees the water scene: its panel fills the left side.
        heading(
            ui,
            left.min,
            &format!(
                "Now: water scene (Tab returns to slide {})",
                deck.counter(index)
            ),
            text,
            &palette,
        );
        let controls = Rect::from_min_max(left.min + vec2(0.0, text * 1.8), left.max);
        let mut child = ui.new_child(
            UiBuilder::new()
                .id_salt("presenter-scene-controls")
                .max_rect(controls),
        );
        child.style_mut().visuals = egui::Visuals::dark();
        child.style_mut().override_font_id = Some(egui::FontId::proportional(text * 0.8));
        egui::ScrollArea::vertical().show(&mut child, |ui| scene_controls(ui));
    } else {
        heading(
            ui,
            left.min,
            &format!("Now: {}", deck.counter(index)),
            text,
            &palette,
        );
        if let Some(slide) = deck.slides.get(index) {
            let mut child =
                ui.new_child(UiBuilder::new().id_salt("presenter-now").max_rect(now_rect));
            now_response = Some(slide_ui_with(
                &mut child,
                deck,
                index,
                states.slide(slide),
                SlideOptions {
                    drawing: info.drawing,
                    ..SlideOptions::default()
                },
            ));
            let controls =
                Rect::from_min_max(egui::pos2(left.min.x, now_rect.max.y + pad), left.max);
            let mut child = ui.new_child(
                UiBuilder::new()
                    .id_salt("presenter-controls")
                    .max_rect(controls),
            );
            child.style_mut().visuals = egui::Visuals::dark();
            child.style_mut().override_font_id = Some(egui::FontId::proportional(text * 0.8));
            // what does not fit still scrolls, with the bar always shown so it is seen
            egui::ScrollArea::vertical()
                .auto_shrink([false, false])
                .scroll_bar_visibility(egui::scroll_area::ScrollBarVisibility::AlwaysVisible)
                .show(&mut child, |ui| {
                    ui.label(
                        RichText::new("Live controls (R resets, Ctrl+S writes back)")
                            .color(palette.dim),
                    );
                    let state = states.slide(slide);
                    if state.widget_count() == 0 {
                        ui.label(RichText::new("no live widgets on this slide").color(palette.dim));
                    }
                    super::ode_editor::ode_editor_ui(ui, state);
                    state.controls_ui(ui);
                });
        }
    }

    // Right: next slide, timer, notes, problems.
    let next_h = (right.width() / ratio).min(right.height() * 0.3);
    heading(ui, right.min, "Next", text, &palette);
    let next_rect = Rect::from_min_size(
        right.min + vec2(0.0, text * 1.5),
        vec2(next_h * ratio, next_h),
    );
    if let Some(next) = deck.slides.get(index + 1) {
        let mut child = ui.new_child(
            UiBuilder::new()
                .id_salt("presenter-next")
                .max_rect(next_rect),
        );
        slide_ui_with(
            &mut child,
            deck,
            index + 1,
            states.slide(next),
            SlideOptions {
                ink: info.ink_next,
                ..SlideOptions::default()
            },
        );
        // The next slide is a preview: a click must not reach its widgets.
        ui.interact(
            next_rect,
            ui.scope_id().with("presenter-next-shield"),
            egui::Sense::click(),
        );
    } else {
        ui.painter().text(
            next_rect.center(),
            egui::Align2::CENTER_CENTER,
            "end of the deck",
            egui::FontId::new(text, serif.clone()),
            palette.dim,
        );
    }
    let mut y = next_rect.max.y + pad;
    let p = &info.pace;
    let behind = p.ahead < -1.0;
    let status = if p.ahead.abs() <= 1.0 {
        ("on time".to_owned(), palette.text)
    } else if behind {
        (
            format!("{} behind", clock(-p.ahead)),
            Color32::from_rgb(0xff, 0x8a, 0x7a),
        )
    } else {
        (
            format!("{} ahead", clock(p.ahead)),
            Color32::from_rgb(0x8f, 0xd6, 0x9c),
        )
    };
    let big = egui::FontId::new(text * 2.0, egui::FontFamily::Monospace);
    ui.painter().text(
        egui::pos2(right.min.x, y),
        egui::Align2::LEFT_TOP,
        clock(p.total_elapsed),
        big,
        if p.running {
            palette.title
        } else {
            palette.dim
        },
    );
    ui.painter().text(
        egui::pos2(right.max.x, y + text * 0.4),
        egui::Align2::RIGHT_TOP,
        if p.running {
            status.0.clone()
        } else {
            format!("paused · {}", status.0)
        },
        egui::FontId::new(text * 1.1, serif.clone()),
        status.1,
    );
    y += text * 2.4;
    // an optional (skip: true) slide has no budget: say so rather than "of 0:00"
    let this_slide = if p.slide_budget > 0.0 {
        format!(
            "this slide {} of {} ({} left)",
            clock(p.slide_elapsed),
            clock(p.slide_budget),
            clock(p.slide_left)
        )
    } else {
        format!(
            "this slide {} (optional: outside the plan)",
            clock(p.slide_elapsed)
        )
    };
    for line in [
        this_slide,
        format!(
            "talk {} of {} ({} left)",
            clock(p.total_elapsed),
            clock(p.planned_total),
            clock(p.total_left)
        ),
    ] {
        ui.painter().text(
            egui::pos2(right.min.x, y),
            egui::Align2::LEFT_TOP,
            line,
            egui::FontId::new(text * 0.85, egui::FontFamily::Monospace),
            palette.text,
        );
        y += text * 1.2;
    }
    y += pad * 0.5;
    let notes_rect = Rect::from_min_max(egui::pos2(right.min.x, y), right.max);
    let mut child = ui.new_child(
        UiBuilder::new()
            .id_salt("presenter-notes")
            .max_rect(notes_rect),
    );
    egui::ScrollArea::vertical().show(&mut child, |ui| {
        // widgets of this slide whose equation or tableau did not load, at the deck's line:col
        let widget_problems = deck.widget_problems.iter().filter(|p| p.slide == index);
        let widget_lines = widget_problems.map(|p| p.diagnostic.to_string());
        for problem in widget_lines.chain(info.problems.iter().cloned()) {
            ui.label(
                RichText::new(problem)
                    .font(egui::FontId::monospace(text * 0.7))
                    .color(Color32::from_rgb(0xff, 0x9c, 0x8f)),
            );
        }
        let notes = deck
            .slides
            .get(index)
            .map(|s| s.notes.as_str())
            .unwrap_or("");
        ui.label(
            RichText::new(if notes.is_empty() {
                "(no notes)"
            } else {
                notes
            })
            .font(egui::FontId::new(text * 1.05, serif.clone()))
            .color(palette.title),
        );
        if !info.bookmarks.is_empty() {
            ui.add_space(text * 0.5);
            for (k, label) in info.bookmarks {
                ui.label(
                    RichText::new(format!("{k}: {label}"))
                        .font(egui::FontId::new(text * 0.8, serif.clone()))
                        .color(palette.dim),
                );
            }
        }
    });
    ui.advance_cursor_after_rect(full);
    now_response
}

fn heading(ui: &egui::Ui, at: egui::Pos2, label: &str, size: f32, palette: &Palette) {
    ui.painter().text(
        at,
        egui::Align2::LEFT_TOP,
        label,
        egui::FontId::new(size, theme::family_or_default(ui.ctx(), theme::SERIF_BOLD)),
        palette.accent,
    );
}
