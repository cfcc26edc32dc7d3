//! The one slide renderer: draws slide `index` of a deck on its logical canvas, scaled into the
//! space a `Ui` offers. The window, the presenter view, the overview grid, `lectern export` and
//! the snapshot tests all call [`slide_ui`], so what is tested is what the audience sees.

use std::collections::HashMap;

use egui::{Align, Color32, Rect, Sense, Stroke, UiBuilder, Vec2, vec2};

use super::blocks::{self, BlockCtx};
use super::theme::{self, Look, Palette, fit_canvas, size};
use crate::deck::{Deck, Layout, Slide};
use crate::widgets::{SlideWidget, WidgetSpec};

/// The live state of one slide: its widgets, created from their specs the first time the slide
/// is drawn and kept while presenting (so a dragged slider stays where the lecturer left it).
#[derive(Default)]
pub struct SlideState {
    pub(crate) widgets: HashMap<Vec<usize>, WidgetSlot>,
}

pub(crate) struct WidgetSlot {
    pub spec: WidgetSpec,
    pub widget: Box<dyn SlideWidget>,
}

impl SlideState {
    /// The widget at block path `path` (indices into the body, then into columns), made from
    /// `spec` if it is new or its spec in the file changed.
    pub(crate) fn widget(
        &mut self,
        path: &[usize],
        spec: &WidgetSpec,
        base_dir: Option<&std::path::Path>,
    ) -> &mut dyn SlideWidget {
        let slot = self
            .widgets
            .entry(path.to_vec())
            .and_modify(|slot| {
                if slot.spec != *spec {
                    *slot = WidgetSlot {
                        spec: spec.clone(),
                        widget: spec.instantiate_in(base_dir),
                    };
                }
            })
            .or_insert_with(|| WidgetSlot {
                spec: spec.clone(),
                widget: spec.instantiate_in(base_dir),
            });
        slot.widget.as_mut()
    }

    /// How many widgets are alive (for tests of the keep-alive rule).
    pub fn widget_count(&self) -> usize {
        self.widgets.len()
    }
}

/// The states of every slide of a deck, by slide key (id, else title), so they survive moving
/// between slides and reloads that insert slides.
#[derive(Default)]
pub struct DeckState {
    slides: HashMap<String, SlideState>,
}

impl DeckState {
    pub fn slide(&mut self, slide: &Slide) -> &mut SlideState {
        self.slides.entry(slide.key().to_owned()).or_default()
    }

    /// After a reload: forget the states of slides that no longer exist. Widgets whose spec
    /// changed are recreated lazily by [`SlideState::widget`].
    pub fn retain_deck(&mut self, deck: &Deck) {
        self.slides.retain(|key, _| deck.find(key).is_some());
    }
}

/// How a slide is drawn besides its content.
#[derive(Debug, Clone, Copy)]
pub struct SlideOptions {
    /// Page number and deck title at the bottom.
    pub footer: bool,
    /// Fill the space around the canvas (when the shapes differ) with the letterbox colour.
    pub letterbox: bool,
}

impl Default for SlideOptions {
    fn default() -> Self {
        Self {
            footer: true,
            letterbox: true,
        }
    }
}

/// What drawing a slide gave back.
pub struct SlideResponse {
    /// Where the canvas landed, in points.
    pub canvas: Rect,
    /// Points per canvas unit.
    pub scale: f32,
    /// The slide's background: `clicked()` is a click that hit no widget.
    pub background: egui::Response,
}

/// Draws slide `index` of `deck` into all the space `ui` has left, with default options.
pub fn slide_ui(
    ui: &mut egui::Ui,
    deck: &Deck,
    index: usize,
    state: &mut SlideState,
) -> SlideResponse {
    slide_ui_with(ui, deck, index, state, SlideOptions::default())
}

/// Draws slide `index` of `deck` into all the space `ui` has left.
pub fn slide_ui_with(
    ui: &mut egui::Ui,
    deck: &Deck,
    index: usize,
    state: &mut SlideState,
    options: SlideOptions,
) -> SlideResponse {
    theme::install_fonts(ui.ctx());
    let avail = ui.available_rect_before_wrap();
    let palette = Palette::of(deck.theme);
    let (canvas, scale) = fit_canvas(avail, deck.aspect.ratio());
    let look = Look { palette, scale };
    if options.letterbox {
        ui.painter().rect_filled(avail, 0.0, palette.letterbox);
    }
    ui.painter().rect_filled(canvas, 0.0, palette.background);
    // Registered before the content, so any widget drawn on top takes the click instead.
    let background = ui.interact(
        canvas,
        ui.scope_id().with(("slide-bg", index)),
        Sense::click(),
    );
    ui.advance_cursor_after_rect(avail);

    let Some(slide) = deck.slides.get(index) else {
        return SlideResponse {
            canvas,
            scale,
            background,
        };
    };
    let inner = Rect::from_min_max(
        canvas.min + vec2(look.scaled(size::MARGIN_X), look.scaled(size::MARGIN_TOP)),
        canvas.max
            - vec2(
                look.scaled(size::MARGIN_X),
                look.scaled(size::MARGIN_BOTTOM),
            ),
    );
    let mut content = ui.new_child(
        UiBuilder::new()
            .id_salt(("slide", index))
            .max_rect(inner)
            .layout(egui::Layout::top_down(Align::Min)),
    );
    content.set_style(blocks::widget_style(ui.style(), &look, deck.theme));
    content.set_clip_rect(canvas.intersect(ui.clip_rect()));
    let bctx = BlockCtx {
        look,
        base_dir: deck.base_dir.as_deref(),
        slide_key: slide.key(),
    };
    match slide.layout {
        Layout::Content => content_slide_ui(&mut content, slide, &bctx, state),
        Layout::Title => title_slide_ui(&mut content, slide, &bctx, state),
    }
    if options.footer && slide.layout == Layout::Content {
        footer_ui(ui, deck, index, canvas, &look);
    }
    SlideResponse {
        canvas,
        scale,
        background,
    }
}

fn content_slide_ui(ui: &mut egui::Ui, slide: &Slide, bctx: &BlockCtx, state: &mut SlideState) {
    let look = &bctx.look;
    let width = ui.available_width();
    let font = look.font(theme::SERIF_BOLD, size::TITLE, ui.ctx());
    let galley = ui
        .painter()
        .layout(slide.title.clone(), font, look.palette.title, width);
    let (rect, _) = ui.allocate_exact_size(galley.size(), Sense::hover());
    ui.painter().galley(rect.min, galley, look.palette.title);
    // A short accent rule under the title: structure without a heavy bar.
    let rule_y = rect.bottom() + look.scaled(18.0);
    ui.painter().line_segment(
        [
            egui::pos2(rect.left(), rule_y),
            egui::pos2(rect.left() + look.scaled(140.0), rule_y),
        ],
        Stroke::new(look.scaled(5.0), look.palette.accent),
    );
    ui.add_space(look.scaled(18.0 + size::AFTER_TITLE));
    blocks::blocks_ui(ui, &slide.body, &[], bctx, state, Align::Min);
}

fn title_slide_ui(ui: &mut egui::Ui, slide: &Slide, bctx: &BlockCtx, state: &mut SlideState) {
    let look = &bctx.look;
    let width = ui.available_width();
    let font = look.font(theme::SERIF_BOLD, size::TITLE_SLIDE, ui.ctx());
    let mut job =
        egui::text::LayoutJob::simple(slide.title.clone(), font, look.palette.title, width);
    job.halign = Align::Center;
    let galley = ui.painter().layout_job(job);
    // The title sits a little above the middle, the body below it.
    let top = ui.max_rect().top() + ui.max_rect().height() * 0.30;
    ui.add_space((top - ui.cursor().top()).max(0.0));
    let (rect, _) = ui.allocate_exact_size(vec2(width, galley.size().y), Sense::hover());
    ui.painter()
        .galley(rect.center_top(), galley, look.palette.title);
    let rule_y = rect.bottom() + look.scaled(34.0);
    let half = look.scaled(90.0);
    ui.painter().line_segment(
        [
            egui::pos2(rect.center().x - half, rule_y),
            egui::pos2(rect.center().x + half, rule_y),
        ],
        Stroke::new(look.scaled(5.0), look.palette.accent),
    );
    ui.add_space(look.scaled(34.0 + 56.0));
    blocks::blocks_ui(ui, &slide.body, &[], bctx, state, Align::Center);
}

fn footer_ui(ui: &egui::Ui, deck: &Deck, index: usize, canvas: Rect, look: &Look) {
    let font = look.font(theme::SERIF, size::FOOTER, ui.ctx());
    let y = canvas.bottom() - look.scaled(size::MARGIN_BOTTOM * 0.5);
    let x_left = canvas.left() + look.scaled(size::MARGIN_X);
    let x_right = canvas.right() - look.scaled(size::MARGIN_X);
    let painter = ui.painter().with_clip_rect(canvas);
    painter.text(
        egui::pos2(x_left, y),
        egui::Align2::LEFT_CENTER,
        &deck.title,
        font.clone(),
        look.palette.dim,
    );
    painter.text(
        egui::pos2(x_right, y),
        egui::Align2::RIGHT_CENTER,
        format!("{} / {}", index + 1, deck.slides.len()),
        font,
        look.palette.dim,
    );
}

/// A slide-sized black rectangle (the `B` key).
pub fn black_ui(ui: &mut egui::Ui) {
    let rect = ui.available_rect_before_wrap();
    ui.painter().rect_filled(rect, 0.0, Color32::BLACK);
    ui.advance_cursor_after_rect(rect);
}

/// The size in points a canvas of `ratio` gets inside `avail` (for layouts that place slides).
pub fn fitted_size(avail: Vec2, ratio: f32) -> Vec2 {
    fit_canvas(Rect::from_min_size(egui::Pos2::ZERO, avail), ratio)
        .0
        .size()
}
