//! The one slide renderer: draws slide `index` of a deck on its logical canvas, scaled into the
//! space a `Ui` offers. The window, the presenter view, the overview grid, `lectern export` and
//! the snapshot tests all call [`slide_ui`], so what is tested is what the audience sees.

use egui::{Align, Color32, Rect, Sense, Stroke, UiBuilder, Vec2, vec2};

use super::block_ctx::BlockCtx;
use super::blocks;
use super::formula_view;
use super::ink_draw::{InkView, paint_on_slide};
use super::slide_state::{SlideResponse, SlideState};
use super::theme::{self, Look, Palette, fit_canvas, size};
use super::widget_style::widget_style;
use crate::deck::{Deck, Layout, Slide};

/// How a slide is drawn besides its content.
#[derive(Debug, Clone, Copy)]
pub struct SlideOptions<'a> {
    /// Page number and deck title at the bottom.
    pub footer: bool,
    /// Fill the space around the canvas (when the shapes differ) with the letterbox colour.
    pub letterbox: bool,
    /// Paint the canvas's background colour. The window leaves it to the render pass's clear
    /// colour instead ([`crate::app::LecternApp`]'s `clear_color`): on a software rasteriser
    /// every window-sized rectangle costs tens of milliseconds of CPU.
    pub background: bool,
    /// Ink painted over the slide. (The live windows paint theirs after taking this frame's
    /// pointer input instead, with [`paint_on_slide`], so a stroke shows the frame it is drawn.)
    pub ink: InkView<'a>,
    /// A tool is drawing: the canvas takes every click and drag (see [`SlideResponse::ink`]),
    /// so neither the slide's widgets nor "click to advance" see them.
    pub drawing: bool,
    /// Whether widgets draw their controls: as the deck's `controls:` says, always (the `C`
    /// key on a single screen) or never (the printed handout).
    pub controls: ShowControls,
}

/// Whether a slide's widgets draw their sliders, checkboxes and buttons (see
/// [`crate::widgets::style::controls_shown`]; where they went is in
/// [`crate::widgets::controls::control_rects`] after the slide is drawn).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum ShowControls {
    /// As the deck's `controls:` says: on the slide, or on the presenter's side only.
    #[default]
    AsDeck,
    /// On the slide whatever the deck says.
    Always,
    /// Never: plots, legends and values only.
    Never,
}

impl ShowControls {
    fn shown(self, deck: crate::deck::Controls) -> bool {
        match self {
            ShowControls::AsDeck => deck == crate::deck::Controls::Slide,
            ShowControls::Always => true,
            ShowControls::Never => false,
        }
    }
}

impl Default for SlideOptions<'_> {
    fn default() -> Self {
        Self {
            footer: true,
            letterbox: true,
            background: true,
            ink: InkView::default(),
            drawing: false,
            controls: ShowControls::AsDeck,
        }
    }
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
    let fonts_ready = theme::fonts_installed(ui.ctx());
    if !fonts_ready {
        // Text was laid out earlier in this pass, so the fonts arrive with the next one: run it
        // now rather than show (or snapshot) a frame in the wrong face.
        ui.ctx().request_discard("lectern: slide fonts installed");
    }
    let avail = ui.available_rect_before_wrap();
    let palette = Palette::of(deck.theme);
    let (canvas, scale) = fit_canvas(avail, deck.aspect.ratio());
    let look = Look { palette, scale };
    if options.letterbox {
        // Under a painted canvas the bars reach a point into it, so no seam shows at
        // fractional edges; over the clear colour they stop at its edge.
        let under = if options.background { 1.0 } else { 0.0 };
        letterbox_ui(ui, avail, canvas, under, palette.letterbox);
    }
    if options.background {
        ui.painter().rect_filled(canvas, 0.0, palette.background);
    }
    // Registered before the content, so any widget drawn on top takes the click instead.
    let background = ui.interact(
        canvas,
        ui.scope_id().with(("slide-bg", index)),
        Sense::click(),
    );
    ui.advance_cursor_after_rect(avail);

    let Some(slide) = deck.slides.get(index).filter(|_| fonts_ready) else {
        return SlideResponse {
            canvas,
            scale,
            background,
            ink: None,
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
    let mut style = widget_style(ui.style(), &look, deck.theme);
    crate::widgets::controls::begin_controls(ui.ctx());
    if !options.controls.shown(deck.controls) {
        style.text_styles.insert(
            egui::TextStyle::Name(crate::widgets::style::NO_CONTROLS_STYLE.into()),
            egui::FontId::proportional(1.0),
        );
    }
    content.set_style(style);
    content.set_clip_rect(canvas.intersect(ui.clip_rect()));
    state.begin_frame(deck.file.as_deref());
    let bctx = BlockCtx {
        look,
        slide_key: slide.key(),
        base_dir: deck.base_dir.as_deref(),
        deck_file: deck.file.as_deref(),
        slide_index: index,
        widget_problems: &deck.widget_problems,
        content: inner,
    };
    match slide.layout {
        Layout::Content => content_slide_ui(&mut content, slide, &bctx, state),
        Layout::Title => title_slide_ui(&mut content, deck, slide, &bctx, state),
    }
    if options.footer && slide.layout == Layout::Content {
        footer_ui(ui, deck, index, canvas, &look);
    }
    // Typeset the neighbours' formulas in the background, so paging finds them ready.
    formula_view::prefetch_formulas(ui.ctx(), deck, index.saturating_sub(1)..index + 3, &look);
    // Registered after the content, so it is on top: while drawing it takes the pointer.
    let ink = options.drawing.then(|| {
        ui.interact(
            canvas,
            ui.scope_id().with(("slide-ink", index)),
            Sense::click_and_drag(),
        )
    });
    let resp = SlideResponse {
        canvas,
        scale,
        background,
        ink,
    };
    paint_on_slide(ui, &resp, deck.theme, &options.ink);
    resp
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

fn title_slide_ui(
    ui: &mut egui::Ui,
    deck: &Deck,
    slide: &Slide,
    bctx: &BlockCtx,
    state: &mut SlideState,
) {
    let look = &bctx.look;
    let width = ui.available_width();
    let font = look.font(theme::SERIF_BOLD, size::TITLE_SLIDE, ui.ctx());
    let mut job =
        egui::text::LayoutJob::simple(slide.title.clone(), font, look.palette.title, width);
    job.halign = Align::Center;
    let galley = ui.painter().layout_job(job);
    // The title sits a little above the middle, the body below it, then who and when.
    let top = ui.max_rect().top() + ui.max_rect().height() * 0.22;
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
    let who = [
        (
            deck.lecturer.as_deref(),
            theme::SERIF_BOLD,
            look.palette.title,
        ),
        (deck.date.as_deref(), theme::SERIF, look.palette.dim),
    ];
    if who.iter().any(|(t, ..)| t.is_some()) {
        ui.add_space(look.scaled(size::BLOCK_GAP * 2.0));
    }
    for (text, family, color) in who {
        let Some(text) = text else { continue };
        let font = look.font(family, size::BODY, ui.ctx());
        let mut job = egui::text::LayoutJob::simple(text.to_owned(), font, color, width);
        job.halign = Align::Center;
        let galley = ui.painter().layout_job(job);
        let (rect, _) = ui.allocate_exact_size(vec2(width, galley.size().y), Sense::hover());
        ui.painter().galley(rect.center_top(), galley, color);
        ui.add_space(look.scaled(size::BULLET_GAP));
    }
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
        deck.counter(index),
        font,
        look.palette.dim,
    );
}

/// Fills `avail` outside `canvas` with `color`: only the bars, never the area the canvas covers
/// (painting it twice costs a window's worth of pixels on a software rasteriser). Each bar
/// reaches `under` points into the canvas.
fn letterbox_ui(ui: &egui::Ui, avail: Rect, canvas: Rect, under: f32, color: Color32) {
    let bars = [
        Rect::from_min_max(avail.min, egui::pos2(avail.max.x, canvas.min.y + under)),
        Rect::from_min_max(egui::pos2(avail.min.x, canvas.max.y - under), avail.max),
        Rect::from_min_max(
            egui::pos2(avail.min.x, canvas.min.y),
            egui::pos2(canvas.min.x + under, canvas.max.y),
        ),
        Rect::from_min_max(
            egui::pos2(canvas.max.x - under, canvas.min.y),
            egui::pos2(avail.max.x, canvas.max.y),
        ),
    ];
    for bar in bars {
        // A bar thinner than the overlap is only the overlap: the canvas fills its side.
        if bar.width() > under + 0.01 && bar.height() > under + 0.01 {
            // (with `under` = 0: any bar with some area)
            ui.painter().rect_filled(bar, 0.0, color);
        }
    }
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
