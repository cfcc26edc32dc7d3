//! The one slide renderer: draws slide `index` of a deck on its logical canvas, scaled into the
//! space a `Ui` offers. The window, the presenter view, the overview grid, `lectern export` and
//! the snapshot tests all call [`slide_ui`], so what is tested is what the audience sees.

use std::collections::HashMap;

use egui::{Align, Color32, Rect, Sense, Stroke, UiBuilder, Vec2, vec2};

use super::blocks::{self, BlockCtx};
use super::ink_draw::{InkView, paint_on_slide};
use super::theme::{self, Look, Palette, fit_canvas, size};
use crate::deck::{Deck, Layout, Slide};
use crate::widgets::{ParamSnapshot, SlideWidget, WidgetSpec, params};

/// The live state of one slide: its widgets, created from their specs the first time the slide
/// is drawn and kept while presenting (so a dragged slider stays where the lecturer left it).
#[derive(Default)]
pub struct SlideState {
    pub(crate) widgets: HashMap<Vec<usize>, WidgetSlot>,
    /// Problems found while drawing (a formula that does not typeset), from the last frame:
    /// for the presenter's screen, never the audience's.
    problems: Vec<String>,
    /// The deck file, remembered from the last draw: widgets made before the slide is drawn
    /// (bookmarks, restores) resolve their files (problems, tableaux) against it too.
    deck_path: Option<std::path::PathBuf>,
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
        deck_path: Option<&std::path::Path>,
    ) -> &mut dyn SlideWidget {
        let slot = self
            .widgets
            .entry(path.to_vec())
            .and_modify(|slot| {
                if slot.spec != *spec {
                    let mut widget = spec.instantiate_in(deck_path);
                    carry_tweaks(&slot.spec, slot.widget.as_mut(), widget.as_mut(), deck_path);
                    *slot = WidgetSlot {
                        spec: spec.clone(),
                        widget,
                    };
                }
            })
            .or_insert_with(|| WidgetSlot {
                spec: spec.clone(),
                widget: spec.instantiate_in(deck_path),
            });
        slot.widget.as_mut()
    }

    /// After problem files changed on disk: widgets whose equation comes from one of `changed`
    /// are made again (their tweaks carried over; a broken file keeps the last good equation).
    pub fn reload_problem_files(&mut self, changed: &[std::path::PathBuf]) {
        let deck_path = self.deck_path.clone();
        for slot in self.widgets.values_mut() {
            let uses = slot
                .widget
                .ode()
                .and_then(|o| o.file().map(std::path::Path::to_path_buf))
                .is_some_and(|f| changed.iter().any(|c| same_file(c, &f)));
            if uses {
                let mut widget = slot.spec.instantiate_in(deck_path.as_deref());
                carry_tweaks(
                    &slot.spec,
                    slot.widget.as_mut(),
                    widget.as_mut(),
                    deck_path.as_deref(),
                );
                slot.widget = widget;
            }
        }
    }

    /// The live equations of the slide's widgets, by block path (the presenter's editor).
    pub fn odes(&mut self) -> Vec<(Vec<usize>, &'static str, &mut crate::widgets::LiveOde)> {
        let mut slots: Vec<(&Vec<usize>, &mut WidgetSlot)> = self.widgets.iter_mut().collect();
        slots.sort_by(|a, b| a.0.cmp(b.0));
        slots
            .into_iter()
            .filter_map(|(path, slot)| {
                let kind = slot.spec.kind();
                slot.widget.ode().map(|o| (path.clone(), kind, o))
            })
            .collect()
    }

    /// The widget at block path `path`, if it was made.
    pub fn widget_at(&mut self, path: &[usize]) -> Option<&mut dyn SlideWidget> {
        Some(self.widgets.get_mut(path)?.widget.as_mut())
    }

    pub(crate) fn note_problem(&mut self, problem: String) {
        if !self.problems.contains(&problem) {
            self.problems.push(problem);
        }
    }

    /// Problems found while drawing the slide the last time (e.g. a formula with an error).
    pub fn problems(&self) -> &[String] {
        &self.problems
    }

    /// The deck file whose folder the widgets' files are in (for widgets made before the
    /// slide is first drawn).
    pub fn set_deck_path(&mut self, deck: Option<&std::path::Path>) {
        self.deck_path = deck.map(std::path::Path::to_path_buf);
    }

    /// Makes every widget of `slide` (so tweaks can be set before it is first drawn).
    pub fn ensure_widgets(&mut self, slide: &Slide) {
        let deck = self.deck_path.clone();
        for (path, spec) in slide.widgets() {
            self.widget(&path, spec, deck.as_deref());
        }
    }

    /// Every live value, by widget path and parameter id (a bookmark).
    pub fn tweak_snapshot(&mut self) -> TweakSnapshot {
        let mut out: TweakSnapshot = self
            .widgets
            .iter_mut()
            .map(|(path, slot)| (path.clone(), params::snapshot(slot.widget.as_mut())))
            .collect();
        out.sort_by(|a, b| a.0.cmp(&b.0));
        out
    }

    /// Sets the values of a [`Self::tweak_snapshot`] (unknown widgets or ids are skipped).
    pub fn restore(&mut self, slide: &Slide, snapshot: &TweakSnapshot) {
        self.ensure_widgets(slide);
        for (path, values) in snapshot {
            if let Some(slot) = self.widgets.get_mut(path) {
                params::restore(slot.widget.as_mut(), values);
            }
        }
    }

    /// Sets one value by widget path and parameter id; false if there is no such parameter.
    pub fn set_param(&mut self, path: &[usize], id: &str, value: ParamSnapshot) -> bool {
        let Some(slot) = self.widgets.get_mut(path) else {
            return false;
        };
        slot.widget
            .params()
            .into_iter()
            .find(|p| p.id == id)
            .is_some_and(|mut p| p.set(value).is_ok())
    }

    /// One value by widget path and parameter id.
    pub fn param(&mut self, path: &[usize], id: &str) -> Option<ParamSnapshot> {
        let slot = self.widgets.get_mut(path)?;
        slot.widget
            .params()
            .iter()
            .find(|p| p.id == id)
            .map(|p| p.get())
    }

    /// `R`: every widget back to the file's values.
    pub fn reset(&mut self) {
        for slot in self.widgets.values_mut() {
            slot.widget.reset();
        }
    }

    /// Where write-back writes parameter `id` of the widget at `path`.
    pub fn write_target(&mut self, path: &[usize], id: &str) -> Option<crate::widgets::WriteTo> {
        let slot = self.widgets.get_mut(path)?;
        slot.widget
            .params()
            .into_iter()
            .find(|p| p.id == id)
            .map(|p| p.write)
    }

    /// The values that differ from the file's, by widget path: what write-back writes.
    pub fn tweaked(&mut self) -> Vec<(Vec<usize>, String, ParamSnapshot)> {
        let mut out = Vec::new();
        let deck = self.deck_path.clone();
        for (path, slot) in &mut self.widgets {
            let file: Vec<(String, ParamSnapshot)> =
                params::snapshot(slot.spec.instantiate_in(deck.as_deref()).as_mut());
            for (id, v) in params::snapshot(slot.widget.as_mut()) {
                if file.iter().any(|(fid, fv)| *fid == id && *fv != v) {
                    out.push((path.clone(), id, v));
                }
            }
        }
        out.sort_by(|a, b| (&a.0, &a.1).cmp(&(&b.0, &b.1)));
        out
    }

    /// The live controls of every widget on the slide (the presenter's panel).
    pub fn controls_ui(&mut self, ui: &mut egui::Ui) {
        let mut paths: Vec<Vec<usize>> = self.widgets.keys().cloned().collect();
        paths.sort();
        for path in paths {
            let Some(slot) = self.widgets.get_mut(&path) else {
                continue;
            };
            ui.label(egui::RichText::new(slot.spec.kind()).strong());
            ui.push_id(&path, |ui| {
                for mut p in slot.widget.params() {
                    p.ui(ui);
                }
            });
            ui.add_space(6.0);
        }
    }

    /// How many widgets are alive (for tests of the keep-alive rule).
    pub fn widget_count(&self) -> usize {
        self.widgets.len()
    }
}

/// A slide's live values: per widget path, (parameter id, value).
pub type TweakSnapshot = Vec<(Vec<usize>, Vec<(String, ParamSnapshot)>)>;

/// After a reload changed a widget's spec: the new widget takes the live values the lecturer
/// tweaked, except where the file changed that very value (then the file wins). Its equation
/// keeps what was typed live the same way, and the last good equation if the new one is broken.
fn carry_tweaks(
    old_spec: &WidgetSpec,
    live: &mut dyn SlideWidget,
    new: &mut dyn SlideWidget,
    deck_path: Option<&std::path::Path>,
) {
    if let (Some(old), Some(fresh)) = (live.ode(), new.ode()) {
        fresh.carry_from(old);
    }
    let old_file = params::snapshot(old_spec.instantiate_in(deck_path).as_mut());
    let new_file = params::snapshot(new);
    let keep: Vec<(String, ParamSnapshot)> = params::snapshot(live)
        .into_iter()
        .filter(|(id, v)| {
            let was = old_file.iter().find(|(i, _)| i == id).map(|(_, v)| *v);
            let now = new_file.iter().find(|(i, _)| i == id).map(|(_, v)| *v);
            was != Some(*v) && was == now
        })
        .collect();
    params::restore(new, &keep);
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

    /// The state of `slide` if it was ever drawn or tweaked.
    pub fn existing(&mut self, slide: &Slide) -> Option<&mut SlideState> {
        self.slides.get_mut(slide.key())
    }

    /// Problem files changed on disk: the widgets that read them re-read them.
    pub fn reload_problem_files(&mut self, changed: &[std::path::PathBuf]) {
        for state in self.slides.values_mut() {
            state.reload_problem_files(changed);
        }
    }

    /// After a reload: forget the states of slides that no longer exist. Widgets whose spec
    /// changed are recreated lazily by [`SlideState::widget`].
    pub fn retain_deck(&mut self, deck: &Deck) {
        self.slides.retain(|key, _| deck.find(key).is_some());
    }
}

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
}

impl Default for SlideOptions<'_> {
    fn default() -> Self {
        Self {
            footer: true,
            letterbox: true,
            background: true,
            ink: InkView::default(),
            drawing: false,
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
    /// While drawing: the whole canvas, on top of its widgets, sensing clicks and drags.
    pub ink: Option<egui::Response>,
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
    content.set_style(blocks::widget_style(ui.style(), &look, deck.theme));
    content.set_clip_rect(canvas.intersect(ui.clip_rect()));
    state.problems.clear();
    state.deck_path.clone_from(&deck.file);
    let bctx = BlockCtx {
        look,
        slide_key: slide.key(),
        base_dir: deck.base_dir.as_deref(),
        deck_file: deck.file.as_deref(),
        slide_index: index,
    };
    match slide.layout {
        Layout::Content => content_slide_ui(&mut content, slide, &bctx, state),
        Layout::Title => title_slide_ui(&mut content, slide, &bctx, state),
    }
    if options.footer && slide.layout == Layout::Content {
        footer_ui(ui, deck, index, canvas, &look);
    }
    // Typeset the neighbours' formulas in the background, so paging finds them ready.
    blocks::prefetch_formulas(ui.ctx(), deck, index.saturating_sub(1)..index + 3, &look);
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

/// Whether two paths name the same file (the watcher reports absolute paths, the deck relative
/// ones).
fn same_file(a: &std::path::Path, b: &std::path::Path) -> bool {
    a == b
        || match (a.canonicalize(), b.canonicalize()) {
            (Ok(x), Ok(y)) => x == y,
            _ => false,
        }
}
