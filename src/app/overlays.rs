//! What sits over the slide: the key list, the "go to" prompt, the overview grid, the reload
//! error notice and short messages. Styled like the slides (same palette and serif), never like
//! a debug panel.

use egui::{Align2, Color32, CornerRadius, Rect, Sense, Stroke, vec2};

use super::slide_state::DeckState;
use super::slide_view::{SlideOptions, slide_ui_with};
use super::theme::{self, Palette};
use crate::deck::Deck;
use crate::diag::Diagnostic;

/// A size for overlay text that reads on a projector and in a small window alike.
fn text_size(ui: &egui::Ui) -> f32 {
    (ui.ctx().content_rect().height() / 34.0).clamp(13.0, 30.0)
}

fn card(ui: &egui::Ui, rect: Rect, palette: &Palette) {
    ui.painter().rect_filled(
        rect,
        CornerRadius::same(12),
        palette.panel.gamma_multiply(0.97),
    );
    ui.painter().rect_stroke(
        rect,
        CornerRadius::same(12),
        Stroke::new(1.5, palette.accent.gamma_multiply(0.6)),
        egui::StrokeKind::Inside,
    );
}

fn dim_backdrop(ui: &egui::Ui, alpha: u8) {
    let screen = ui.ctx().content_rect();
    ui.painter()
        .rect_filled(screen, 0.0, Color32::from_black_alpha(alpha));
}

/// The `?` key list, centred.
/// The `?` card listing `lines` (keys, what they do).
pub fn help_ui(ui: &mut egui::Ui, palette: &Palette, lines: &[(&str, &str)]) {
    let ctx = ui.ctx().clone();
    egui::Area::new(egui::Id::unique("lectern-help"))
        .order(egui::Order::Foreground)
        .fixed_pos(egui::Pos2::ZERO)
        .show(&ctx, |ui| {
            dim_backdrop(ui, 170);
            let serif = theme::family_or_default(&ctx, theme::SERIF);
            let bold = theme::family_or_default(&ctx, theme::SERIF_BOLD);
            let screen = ctx.content_rect();
            // As large as the window's text, but every line on the card.
            let rows = lines.len() as f32 + 2.6;
            let s = text_size(ui)
                .min(screen.height() * 0.96 / (1.45 * rows))
                .min(screen.width() * 0.96 / 32.0);
            let row_h = s * 1.45;
            let size = vec2(s * 32.0, row_h * (lines.len() as f32 + 2.6));
            let rect = Rect::from_center_size(screen.center(), size.min(screen.size() * 0.96));
            card(ui, rect, palette);
            let p = ui.painter();
            p.text(
                rect.left_top() + vec2(s * 1.2, s * 1.0),
                Align2::LEFT_TOP,
                "Keys",
                egui::FontId::new(s * 1.3, bold),
                palette.title,
            );
            let col = rect.left() + s * 14.5;
            for (i, (keys, what)) in lines.iter().enumerate() {
                let y = rect.top() + s * 1.2 + row_h * (i as f32 + 1.6);
                p.text(
                    egui::pos2(col - s * 0.8, y),
                    Align2::RIGHT_TOP,
                    *keys,
                    egui::FontId::new(s * 0.85, egui::FontFamily::Monospace),
                    palette.accent,
                );
                p.text(
                    egui::pos2(col, y),
                    Align2::LEFT_TOP,
                    *what,
                    egui::FontId::new(s, serif.clone()),
                    palette.text,
                );
            }
        });
}

/// The prompt while `G` collects a slide number.
pub fn goto_ui(ui: &mut egui::Ui, typed: &str, slides: usize, palette: &Palette) {
    let ctx = ui.ctx().clone();
    egui::Area::new(egui::Id::unique("lectern-goto"))
        .order(egui::Order::Foreground)
        .fixed_pos(egui::Pos2::ZERO)
        .show(&ctx, |ui| {
            let s = text_size(ui) * 1.3;
            let screen = ctx.content_rect();
            let rect = Rect::from_center_size(screen.center(), vec2(s * 12.0, s * 4.0));
            card(ui, rect, palette);
            let serif = theme::family_or_default(&ctx, theme::SERIF);
            ui.painter().text(
                rect.center() - vec2(0.0, s * 0.5),
                Align2::CENTER_CENTER,
                format!("Go to slide  {typed}_"),
                egui::FontId::new(s, serif.clone()),
                palette.title,
            );
            ui.painter().text(
                rect.center() + vec2(0.0, s * 0.9),
                Align2::CENTER_CENTER,
                format!("1 – {slides}, Enter to jump, Esc to cancel"),
                egui::FontId::new(s * 0.55, serif),
                palette.dim,
            );
        });
}

/// The overview grid: every slide live and small; returns the slide clicked, if any.
/// `fill`: paint the letterbox colour behind the grid (a window cleared to it skips that).
pub fn overview_ui(
    ui: &mut egui::Ui,
    deck: &Deck,
    current: usize,
    states: &mut DeckState,
    fill: bool,
) -> Option<usize> {
    let palette = Palette::of(deck.theme);
    let avail = ui.available_rect_before_wrap();
    if fill {
        ui.painter().rect_filled(avail, 0.0, palette.letterbox);
    }
    let cells = overview_cells(deck.slides.len(), deck.aspect.ratio(), avail);
    let mut clicked = None;
    for ((i, slide), rect) in deck.slides.iter().enumerate().zip(cells) {
        let mut child = ui.new_child(
            egui::UiBuilder::new()
                .id_salt(("overview", i))
                .max_rect(rect),
        );
        child.set_clip_rect(rect);
        let options = SlideOptions {
            footer: true,
            letterbox: false,
            ..SlideOptions::default()
        };
        slide_ui_with(&mut child, deck, i, states.slide(slide), options);
        // On top of the thumbnail's widgets: a click anywhere picks the slide.
        let resp = ui.interact(
            rect,
            ui.scope_id().with(("overview-pick", i)),
            Sense::click(),
        );
        let stroke = if i == current {
            Stroke::new(4.0, palette.accent)
        } else if resp.hovered() {
            Stroke::new(2.0, palette.accent.gamma_multiply(0.6))
        } else {
            Stroke::new(1.0, palette.dim.gamma_multiply(0.4))
        };
        ui.painter()
            .rect_stroke(rect, 0.0, stroke, egui::StrokeKind::Outside);
        if slide.skip {
            // optional slides: reachable from here, passed over by paging
            let tag = (rect.height() / 9.0).clamp(9.0, 20.0);
            let galley = ui.painter().layout_no_wrap(
                "optional".into(),
                egui::FontId::proportional(tag),
                palette.text,
            );
            // top right: the title starts at the left and must stay readable
            let at = rect.right_top() + egui::vec2(-galley.size().x - tag * 0.4, tag * 0.3);
            let bg = egui::Rect::from_min_size(at, galley.size()).expand(tag * 0.25);
            ui.painter().rect_filled(bg, tag * 0.2, palette.letterbox);
            ui.painter().galley(at, galley, palette.text);
        }
        if resp.clicked() {
            clicked = Some(i);
        }
    }
    ui.advance_cursor_after_rect(avail);
    clicked
}

/// Where the overview grid puts each of `n` slides of aspect `ratio` inside `avail`: the column
/// count that makes the thumbnails largest while all of them fit, centred.
pub fn overview_cells(n: usize, ratio: f32, avail: Rect) -> Vec<Rect> {
    let n = n.max(1);
    let gap = (avail.width() / 80.0).max(6.0);
    let area = avail.shrink(gap * 2.0);
    let (cols, cell_w) = (1..=n)
        .map(|cols| {
            let rows = n.div_ceil(cols) as f32;
            let w_by_width = (area.width() - gap * (cols as f32 - 1.0)) / cols as f32;
            let w_by_height = ((area.height() - gap * (rows - 1.0)) / rows) * ratio;
            (cols, w_by_width.min(w_by_height))
        })
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap_or((1, area.width()));
    let cell = vec2(cell_w, cell_w / ratio);
    let rows = n.div_ceil(cols);
    let grid = vec2(
        cols as f32 * cell.x + (cols as f32 - 1.0) * gap,
        rows as f32 * cell.y + (rows as f32 - 1.0) * gap,
    );
    let origin = area.center() - grid * 0.5;
    (0..n)
        .map(|i| {
            let (r, c) = (i / cols, i % cols);
            Rect::from_min_size(
                origin + vec2(c as f32 * (cell.x + gap), r as f32 * (cell.y + gap)),
                cell,
            )
        })
        .collect()
}

/// The reload error: small, bottom left, with file:line:col, until the file is fixed.
pub fn error_notice_ui(ui: &mut egui::Ui, error: &Diagnostic, palette: &Palette) {
    notice_ui(
        ui,
        "Not reloaded",
        &error.to_string(),
        "showing the last good version; fix and save",
        palette,
    );
}

/// A problem of the slide on screen (e.g. a formula stopped at its time budget, at its
/// file:line:col), in the same place as the reload error, while it lasts.
pub fn slide_problem_notice_ui(ui: &mut egui::Ui, problem: &str, palette: &Palette) {
    notice_ui(
        ui,
        "Slide problem",
        problem,
        "the slide stays on screen; fix and save",
        palette,
    );
}

fn notice_ui(ui: &mut egui::Ui, heading: &str, text: &str, hint: &str, palette: &Palette) {
    let ctx = ui.ctx().clone();
    let screen = ctx.content_rect();
    let s = (text_size(ui) * 0.72).max(12.0);
    egui::Area::new(egui::Id::unique("lectern-reload-error"))
        .order(egui::Order::Foreground)
        .anchor(Align2::LEFT_BOTTOM, vec2(s, -s))
        .interactable(false)
        .show(&ctx, |ui| {
            egui::Frame::new()
                .fill(Color32::from_rgb(0x4a, 0x17, 0x1b).gamma_multiply(0.95))
                .stroke(Stroke::new(1.0, Color32::from_rgb(0xe0, 0x6c, 0x6c)))
                .corner_radius(CornerRadius::same(8))
                .inner_margin(egui::Margin::symmetric(12, 8))
                .show(ui, |ui| {
                    ui.set_max_width(screen.width() * 0.6);
                    ui.label(
                        egui::RichText::new(heading)
                            .size(s)
                            .strong()
                            .color(Color32::from_rgb(0xff, 0x9c, 0x8f)),
                    );
                    ui.label(
                        egui::RichText::new(text)
                            .font(egui::FontId::monospace(s))
                            .color(Color32::from_rgb(0xff, 0xdc, 0xd6)),
                    );
                    ui.label(egui::RichText::new(hint).size(s * 0.9).color(palette.dim));
                });
        });
}

/// A short message (e.g. "no slide 42") at the top, for a moment.
pub fn toast_ui(ui: &mut egui::Ui, message: &str, palette: &Palette) {
    let ctx = ui.ctx().clone();
    let s = text_size(ui) * 0.8;
    egui::Area::new(egui::Id::unique("lectern-toast"))
        .order(egui::Order::Foreground)
        .anchor(Align2::CENTER_TOP, vec2(0.0, s))
        .interactable(false)
        .show(&ctx, |ui| {
            egui::Frame::new()
                .fill(palette.panel)
                .stroke(Stroke::new(1.0, palette.accent.gamma_multiply(0.6)))
                .corner_radius(CornerRadius::same(8))
                .inner_margin(egui::Margin::symmetric(14, 8))
                .show(ui, |ui| {
                    ui.label(egui::RichText::new(message).size(s).color(palette.text));
                });
        });
}

/// Scene mode when the scene cannot be shown: says why, in the slides' style.
pub fn scene_placeholder_ui(ui: &mut egui::Ui, palette: &Palette, why: &str) {
    let rect = ui.available_rect_before_wrap();
    ui.painter()
        .rect_filled(rect, 0.0, Color32::from_rgb(0x0b, 0x1e, 0x2d));
    let s = (rect.height() / 18.0).clamp(14.0, 64.0);
    let ctx = ui.ctx().clone();
    ui.painter().text(
        rect.center() - vec2(0.0, s * 0.6),
        Align2::CENTER_CENTER,
        "Scene mode",
        egui::FontId::new(s, theme::family_or_default(&ctx, theme::SERIF_BOLD)),
        palette.title,
    );
    ui.painter().text(
        rect.center() + vec2(0.0, s * 0.6),
        Align2::CENTER_CENTER,
        format!("{why}  Tab returns to the slides."),
        egui::FontId::new(s * 0.45, theme::family_or_default(&ctx, theme::SERIF)),
        palette.dim,
    );
    ui.advance_cursor_after_rect(rect);
}

/// `N`: the slide's speaker notes in `rect`, under the slide (self-study, the web player);
/// with `editor`, first the equation editor of the slide's ODE widgets (the web player, where
/// a student types their own right-hand side).
pub fn notes_under_slide_ui(
    ui: &mut egui::Ui,
    rect: Rect,
    notes: &str,
    palette: &Palette,
    editor: Option<&mut super::SlideState>,
) {
    let ctx = ui.ctx().clone();
    let serif = theme::family_or_default(&ctx, theme::SERIF);
    let s = (rect.height() / 7.0).clamp(11.0, 22.0);
    let text = if notes.trim().is_empty() {
        "(no notes for this slide)"
    } else {
        notes.trim()
    };
    ui.painter().rect_filled(rect, 0.0, palette.letterbox);
    ui.scope_builder(egui::UiBuilder::new().max_rect(rect.shrink(s)), |ui| {
        egui::ScrollArea::vertical()
            .id_salt("lectern-notes")
            .show(ui, |ui| {
                if let Some(state) = editor {
                    ui.style_mut().override_font_id = Some(egui::FontId::proportional(s));
                    // the editor's labels in the slide's text colour, on the letterbox
                    ui.visuals_mut().override_text_color = Some(palette.text);
                    super::ode_editor::ode_editor_ui(ui, state);
                }
                ui.label(
                    egui::RichText::new(text)
                        .font(egui::FontId::new(s, serif))
                        .color(palette.text),
                );
            });
    });
}
