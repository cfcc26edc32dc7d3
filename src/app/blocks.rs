//! Slide body blocks: paragraphs, bullets, maths, images, live widgets and columns, laid out top
//! to bottom on the canvas. Text blocks take the height they need; widgets share what is left.

use std::path::Path;

use egui::text::{LayoutJob, TextFormat};
use egui::{Align, Rect, Sense, Stroke, UiBuilder, vec2};

use super::images;
use super::slide_view::SlideState;
use super::theme::{self, Look, size};
use crate::deck::{Block, Theme};

/// What every block needs to draw itself.
pub(crate) struct BlockCtx<'a> {
    pub look: Look,
    /// The slide's key, to name formula slots (each keeps its last good rendering).
    pub slide_key: &'a str,
    /// The deck's folder; image paths are relative to it.
    pub base_dir: Option<&'a Path>,
    /// The deck's file and the slide's index in it, to place a formula's error at its line.
    pub deck_file: Option<&'a Path>,
    pub slide_index: usize,
}

/// The style widgets see inside a slide: egui's dark or light visuals recoloured to the
/// palette, and every size scaled from canvas units, so a slider on a 4K projector is as large
/// (relative to the slide) as in a laptop window.
pub(crate) fn widget_style(base: &egui::Style, look: &Look, theme: Theme) -> egui::Style {
    use egui::{FontFamily, FontId, TextStyle};
    let mut style = base.clone();
    let p = look.palette;
    style.visuals = match theme {
        Theme::Dark => egui::Visuals::dark(),
        Theme::Light => egui::Visuals::light(),
    };
    style.visuals.extreme_bg_color = p.panel;
    style.visuals.panel_fill = p.background;
    style.visuals.window_fill = p.panel;
    style.visuals.widgets.noninteractive.fg_stroke.color = p.text;
    style.visuals.selection.bg_fill = p.accent.gamma_multiply(0.6);
    style.interaction.selectable_labels = false;
    // The canvas scale puts rects on fractional points by design; egui's debug-build marker for
    // that would otherwise show up in snapshots. (The field exists only in debug builds.)
    #[cfg(debug_assertions)]
    {
        style.debug.show_unaligned = false;
    }

    let text = |units: f32, family: FontFamily| FontId::new(look.scaled(units), family);
    let prop = FontFamily::Proportional;
    style.text_styles = [
        (
            TextStyle::Small,
            text(size::WIDGET_TEXT * 0.75, prop.clone()),
        ),
        (TextStyle::Body, text(size::WIDGET_TEXT, prop.clone())),
        (TextStyle::Button, text(size::WIDGET_TEXT, prop.clone())),
        (TextStyle::Heading, text(size::WIDGET_TEXT * 1.4, prop)),
        (
            TextStyle::Monospace,
            text(size::WIDGET_TEXT * 0.9, FontFamily::Monospace),
        ),
    ]
    .into();
    style.text_styles.insert(
        TextStyle::Name(theme::CANVAS_STYLE.into()),
        text(size::WIDGET_TEXT, FontFamily::Proportional),
    );

    // egui's default spacing is made for 12.5-point body text; scale it with ours.
    let k = look.scaled(size::WIDGET_TEXT) / 12.5;
    let s = &mut style.spacing;
    s.item_spacing *= k;
    s.button_padding *= k;
    s.interact_size *= k;
    s.slider_width *= k;
    s.slider_rail_height *= k;
    s.icon_width *= k;
    s.icon_width_inner *= k;
    s.icon_spacing *= k;
    s.combo_width *= k;
    s.text_edit_width *= k;
    s.indent *= k;
    s.menu_width *= k;
    s.tooltip_width *= k;
    let thick = (0.6 * k).max(1.0);
    for w in [
        &mut style.visuals.widgets.noninteractive,
        &mut style.visuals.widgets.inactive,
        &mut style.visuals.widgets.hovered,
        &mut style.visuals.widgets.active,
        &mut style.visuals.widgets.open,
    ] {
        w.fg_stroke.width *= thick;
        w.bg_stroke.width *= thick;
    }
    style
}

/// Lays out `blocks` in `ui`; `path` is where they sit in the slide (for widget identity).
pub(crate) fn blocks_ui(
    ui: &mut egui::Ui,
    blocks: &[Block],
    path: &[usize],
    bctx: &BlockCtx,
    state: &mut SlideState,
    align: Align,
) {
    let look = &bctx.look;
    let width = ui.available_width();
    let gap = look.scaled(size::BLOCK_GAP);
    // Widgets (and columns holding them) share the height the other blocks leave.
    let fixed: f32 = blocks
        .iter()
        .enumerate()
        .filter_map(|(i, b)| measure(ui, b, &[path, &[i]].concat(), width, bctx))
        .sum();
    let flexible = blocks.iter().filter(|b| is_flexible(b)).count();
    let gaps = gap * blocks.len().saturating_sub(1) as f32;
    let flex_h = if flexible > 0 {
        ((ui.available_height() - fixed - gaps) / flexible as f32).max(look.scaled(240.0))
    } else {
        0.0
    };
    for (i, block) in blocks.iter().enumerate() {
        if i > 0 {
            ui.add_space(gap);
        }
        let mut here = path.to_vec();
        here.push(i);
        block_ui(ui, block, &here, bctx, state, align, flex_h);
    }
}

fn is_flexible(block: &Block) -> bool {
    match block {
        Block::Widget(_) => true,
        Block::Columns(cols) => cols.iter().flatten().any(is_flexible),
        _ => false,
    }
}

/// The height a non-flexible block at `path` will take at `width`, in points; `None` for
/// flexible ones.
fn measure(
    ui: &egui::Ui,
    block: &Block,
    path: &[usize],
    width: f32,
    bctx: &BlockCtx,
) -> Option<f32> {
    let look = &bctx.look;
    match block {
        Block::Text(t) => Some(paragraph_galley(ui, t, width, look, Align::Min).size().y),
        Block::Bullets(items) => {
            let indent = look.scaled(bullet_indent());
            let h: f32 = items
                .iter()
                .map(|t| {
                    paragraph_galley(ui, t, width - indent, look, Align::Min)
                        .size()
                        .y
                })
                .sum();
            Some(h + look.scaled(size::BULLET_GAP) * items.len().saturating_sub(1) as f32)
        }
        Block::Math { src, latex } => {
            let view = formula(ui, bctx, path, src, *latex);
            Some(match view.typeset {
                Some(f) => f.size(ui, width).y,
                None if view.pending => placeholder_height(src, look),
                None => math_source_height(src, look),
            })
        }
        Block::Image { path, width: w } => {
            let (_, h) = images::image_size(ui.ctx(), bctx.base_dir, path, w, width, look);
            Some(h)
        }
        Block::Widget(_) => None,
        Block::Columns(cols) => {
            if is_flexible(block) {
                return None;
            }
            let n = cols.len().max(1) as f32;
            let gap = look.scaled(size::BLOCK_GAP * 1.5);
            let cw = (width - gap * (n - 1.0)) / n;
            let col_h = |(c, col): (usize, &Vec<Block>)| -> f32 {
                let inner: f32 = col
                    .iter()
                    .enumerate()
                    .filter_map(|(i, b)| measure(ui, b, &[path, &[c, i]].concat(), cw, bctx))
                    .sum();
                inner + look.scaled(size::BLOCK_GAP) * col.len().saturating_sub(1) as f32
            };
            Some(cols.iter().enumerate().map(col_h).fold(0.0, f32::max))
        }
    }
}

fn block_ui(
    ui: &mut egui::Ui,
    block: &Block,
    path: &[usize],
    bctx: &BlockCtx,
    state: &mut SlideState,
    align: Align,
    flex_h: f32,
) {
    let look = &bctx.look;
    let width = ui.available_width();
    match block {
        Block::Text(t) => {
            let galley = paragraph_galley(ui, t, width, look, align);
            let (rect, _) = ui.allocate_exact_size(vec2(width, galley.size().y), Sense::hover());
            let x = if align == Align::Center {
                rect.center().x
            } else {
                rect.left()
            };
            ui.painter()
                .galley(egui::pos2(x, rect.top()), galley, look.palette.text);
        }
        Block::Bullets(items) => bullets_ui(ui, items, look),
        Block::Math { src, latex } => math_ui(ui, bctx, path, src, *latex, state),
        Block::Image { path: p, width: w } => {
            if let Some(e) = images::image_ui(ui, bctx.base_dir, p, w, look) {
                let at = format!("{}.path", block_ron_path(bctx.slide_index, path));
                state.note_problem(located_problem(ui.ctx(), bctx, &at, p, None, e));
            }
        }
        Block::Widget(spec) => {
            let (rect, _) = ui.allocate_exact_size(vec2(width, flex_h), Sense::hover());
            let mut child = ui.new_child(
                UiBuilder::new()
                    .id_salt(("widget", path))
                    .max_rect(rect)
                    .layout(egui::Layout::top_down(Align::Min)),
            );
            child.set_clip_rect(rect.intersect(ui.clip_rect()));
            state.widget(path, spec, bctx.base_dir).ui(&mut child);
        }
        Block::Columns(cols) => {
            let n = cols.len().max(1) as f32;
            let gap = look.scaled(size::BLOCK_GAP * 1.5);
            let cw = (width - gap * (n - 1.0)) / n;
            let h = if is_flexible(block) {
                flex_h
            } else {
                measure(ui, block, path, width, bctx).unwrap_or(0.0)
            };
            let top_left = ui.cursor().min;
            let mut used = 0.0f32;
            for (c, col) in cols.iter().enumerate() {
                let rect =
                    Rect::from_min_size(top_left + vec2(c as f32 * (cw + gap), 0.0), vec2(cw, h));
                let mut child = ui.new_child(
                    UiBuilder::new()
                        .id_salt(("column", path, c))
                        .max_rect(rect)
                        .layout(egui::Layout::top_down(Align::Min)),
                );
                let mut here = path.to_vec();
                here.push(c);
                blocks_ui(&mut child, col, &here, bctx, state, Align::Min);
                used = used.max(child.min_rect().height());
            }
            ui.allocate_exact_size(vec2(width, used.max(h)), Sense::hover());
        }
    }
}

fn bullet_indent() -> f32 {
    size::BODY * 1.1
}

fn bullets_ui(ui: &mut egui::Ui, items: &[String], look: &Look) {
    let width = ui.available_width();
    let indent = look.scaled(bullet_indent());
    for (i, item) in items.iter().enumerate() {
        if i > 0 {
            ui.add_space(look.scaled(size::BULLET_GAP));
        }
        let galley = paragraph_galley(ui, item, width - indent, look, Align::Min);
        let first_row_h = galley.rows.first().map_or(0.0, |r| r.height());
        let (rect, _) = ui.allocate_exact_size(vec2(width, galley.size().y), Sense::hover());
        // A small accent square, centred on the first line's x-height.
        let c = egui::pos2(
            rect.left() + look.scaled(12.0),
            rect.top() + first_row_h * 0.55,
        );
        ui.painter().rect_filled(
            Rect::from_center_size(c, vec2(look.scaled(11.0), look.scaled(11.0))),
            look.scaled(2.0),
            look.palette.accent,
        );
        ui.painter().galley(
            rect.left_top() + vec2(indent, 0.0),
            galley,
            look.palette.text,
        );
    }
}

/// A paragraph with light inline markup: `*emphasis*` in italics, `` `code` `` in monospace.
pub(crate) fn paragraph_galley(
    ui: &egui::Ui,
    text: &str,
    width: f32,
    look: &Look,
    align: Align,
) -> std::sync::Arc<egui::Galley> {
    let ctx = ui.ctx();
    let regular = look.font(theme::SERIF, size::BODY, ctx);
    let italic = look.font(theme::SERIF_ITALIC, size::BODY, ctx);
    let mono = look.font(theme::MONO, size::BODY * 0.85, ctx);
    let mut job = LayoutJob {
        halign: align,
        ..Default::default()
    };
    job.wrap.max_width = width.max(1.0);
    for (span, kind) in inline_spans(text) {
        let font = match kind {
            Inline::Plain => regular.clone(),
            Inline::Emphasis => italic.clone(),
            Inline::Code => mono.clone(),
        };
        let mut format = TextFormat::simple(font, look.palette.text);
        if kind == Inline::Emphasis {
            format.color = look.palette.title;
        }
        job.append(span, 0.0, format);
    }
    ui.painter().layout_job(job)
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Inline {
    Plain,
    Emphasis,
    Code,
}

/// Splits `*emphasis*` and `` `code` `` out of a paragraph. An unmatched marker is kept as
/// literal text, so a lone `*` (as in "a * b") never swallows the rest of the line.
pub(crate) fn inline_spans(text: &str) -> Vec<(&str, Inline)> {
    let mut out = Vec::new();
    let mut rest = text;
    while !rest.is_empty() {
        let next = rest.find(['*', '`']);
        let Some(start) = next else {
            out.push((rest, Inline::Plain));
            break;
        };
        let marker = rest.as_bytes()[start] as char;
        let after = &rest[start + 1..];
        match after.find(marker) {
            Some(len) if len > 0 => {
                if start > 0 {
                    out.push((&rest[..start], Inline::Plain));
                }
                let kind = if marker == '*' {
                    Inline::Emphasis
                } else {
                    Inline::Code
                };
                out.push((&after[..len], kind));
                rest = &after[len + 1..];
            }
            _ => {
                out.push((&rest[..=start], Inline::Plain));
                rest = after;
            }
        }
    }
    out
}

/// A typeset formula, as laid out on the slide.
struct Typeset {
    texture: egui::TextureId,
    /// Its size in physical pixels at the slide's current em (a stale picture is scaled).
    size_px: egui::Vec2,
}

impl Typeset {
    /// Its size in points, shrunk to `width` if wider (never overflow the slide).
    fn size(&self, ui: &egui::Ui, width: f32) -> egui::Vec2 {
        let size = self.size_px / ui.ctx().pixels_per_point();
        if size.x > width && width > 1.0 {
            size * (width / size.x)
        } else {
            size
        }
    }
}

/// What a Math block shows this frame.
struct FormulaView {
    /// The current formula, or the last good one of this slot (broken or pending edit).
    typeset: Option<Typeset>,
    /// The current source is still being typeset (live window only).
    pending: bool,
    error: Option<crate::math::MathError>,
}

fn syntax_of(latex: bool) -> crate::math::MathSyntax {
    if latex {
        crate::math::MathSyntax::Latex
    } else {
        crate::math::MathSyntax::Typst
    }
}

/// Formulas are typeset at this many physical pixels per em.
fn em_px(ctx: &egui::Context, look: &Look) -> f32 {
    look.scaled(size::MATH) * ctx.pixels_per_point()
}

/// The formula for `src` from the shared cache. In the live window this never waits: a formula
/// still being typeset shows the slot's last good picture, or nothing yet (`pending`).
fn formula(ui: &egui::Ui, bctx: &BlockCtx, path: &[usize], src: &str, latex: bool) -> FormulaView {
    use crate::math::MathCache;
    let ctx = ui.ctx();
    let em = em_px(ctx, &bctx.look);
    let slot = format!("{}/{path:?}", bctx.slide_key);
    let cache = MathCache::shared(ctx);
    let Ok(mut cache) = cache.lock() else {
        return FormulaView {
            typeset: None,
            pending: true,
            error: None,
        };
    };
    let view = cache.get_slot(
        ctx,
        &slot,
        src,
        syntax_of(latex),
        em,
        bctx.look.palette.title,
    );
    FormulaView {
        typeset: view.formula.map(|f| Typeset {
            texture: f.texture.id(),
            size_px: f.size_at(em),
        }),
        pending: view.pending,
        error: view.error,
    }
}

/// Asks for the formulas of `slides` at the size `look` draws them, so that paging there
/// finds them typeset. Only in the live window: headless paths wait for what they draw.
pub(crate) fn prefetch_formulas(
    ctx: &egui::Context,
    deck: &crate::deck::Deck,
    slides: std::ops::Range<usize>,
    look: &Look,
) {
    let cache = crate::math::MathCache::shared(ctx);
    let Ok(mut cache) = cache.lock() else { return };
    if cache.waits() {
        return;
    }
    let em = em_px(ctx, look);
    for f in crate::math::deck::formulas(deck, Some(slides)) {
        cache.prefetch(ctx, f.src, f.syntax, em, look.palette.title);
    }
}

fn math_source_height(src: &str, look: &Look) -> f32 {
    let lines = src.lines().count().max(1) as f32;
    look.scaled(size::MATH * 1.3 * lines + 48.0)
}

/// The height a formula is likely to take before it is typeset (so the blocks below it move
/// little when it arrives).
fn placeholder_height(src: &str, look: &Look) -> f32 {
    look.scaled(size::MATH * crate::math::typeset::estimated_height_em(src))
}

/// `slides[3].body[1][0]`: the [`crate::ron_tree`] path of the block at `path` on a slide.
fn block_ron_path(slide: usize, path: &[usize]) -> String {
    let mut p = format!("slides[{slide}].body");
    for i in path {
        p.push_str(&format!("[{i}]"));
    }
    p
}

/// A problem with the string `written` at `ron_path` in the deck (its character `col`, 1-based,
/// if given) as `file:line:col: message` when the deck came from a file that still has that
/// string there, else the message alone. Cached per problem (it reads the deck file).
fn located_problem(
    ctx: &egui::Context,
    bctx: &BlockCtx,
    ron_path: &str,
    written: &str,
    col: Option<usize>,
    message: String,
) -> String {
    let Some(file) = bctx.deck_file else {
        return message;
    };
    let id =
        egui::Id::unique(("lectern-located-problem", file, ron_path, written, col)).with(&message);
    if let Some(line) = ctx.data(|d| d.get_temp::<String>(id)) {
        return line;
    }
    let diag = std::fs::read_to_string(file)
        .ok()
        .and_then(|text| crate::math::deck::position(&text, ron_path, written, col))
        .map_or_else(
            || crate::diag::Diagnostic::whole_file(file, &message),
            |(line, col)| crate::diag::Diagnostic::new(file, line, col, &message),
        );
    let line = diag.to_string();
    ctx.data_mut(|d| d.insert_temp(id, line.clone()));
    line
}

/// The problem line for a formula's error, at the formula's character in the deck file.
fn formula_problem(
    ctx: &egui::Context,
    bctx: &BlockCtx,
    path: &[usize],
    src: &str,
    latex: bool,
    err: &crate::math::MathError,
) -> String {
    let at = format!("{}.src", block_ron_path(bctx.slide_index, path));
    // Columns only make sense against what the lecturer typed, i.e. for Typst input.
    let col = if latex { None } else { err.col };
    let message = match (bctx.deck_file, col) {
        (Some(_), _) | (None, None) => crate::math::deck::message(err),
        (None, Some(c)) => format!("formula {path:?}, column {c}: {}", err.message),
    };
    located_problem(ctx, bctx, &at, src, col, message)
}

/// Display maths, typeset by Typst (`crate::math`) and centred. A formula still being typeset
/// (live window) keeps its last good picture, or a quiet placeholder of about its height; one
/// that never rendered shows its source in a quiet monospace frame; a broken edit keeps the last
/// good picture. Errors go to the slide's problems, for the presenter's screen.
fn math_ui(
    ui: &mut egui::Ui,
    bctx: &BlockCtx,
    path: &[usize],
    src: &str,
    latex: bool,
    state: &mut SlideState,
) {
    let look = &bctx.look;
    let width = ui.available_width();
    let view = formula(ui, bctx, path, src, latex);
    if let Some(e) = &view.error {
        state.note_problem(formula_problem(ui.ctx(), bctx, path, src, latex, e));
    }
    if let Some(f) = &view.typeset {
        let size = f.size(ui, width);
        let (row, _) = ui.allocate_exact_size(vec2(width, size.y), Sense::hover());
        let rect = Rect::from_center_size(row.center(), size);
        ui.painter().image(
            f.texture,
            rect,
            Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0)),
            egui::Color32::WHITE,
        );
        return;
    }
    if view.pending {
        let h = placeholder_height(src, look);
        let (row, _) = ui.allocate_exact_size(vec2(width, h), Sense::hover());
        let quiet = Rect::from_center_size(row.center(), vec2(width * 0.4, h * 0.6));
        ui.painter().rect_filled(
            quiet,
            look.scaled(10.0),
            look.palette.panel.gamma_multiply(0.5),
        );
        return;
    }
    let h = math_source_height(src, look);
    let (rect, _) = ui.allocate_exact_size(vec2(width, h), Sense::hover());
    let font = look.font(theme::MONO, size::MATH * 0.9, ui.ctx());
    let galley = ui
        .painter()
        .layout(src.trim().to_owned(), font, look.palette.title, width);
    let frame = Rect::from_center_size(
        rect.center(),
        vec2(
            (galley.size().x + look.scaled(64.0)).min(width),
            rect.height(),
        ),
    );
    ui.painter()
        .rect_filled(frame, look.scaled(10.0), look.palette.panel);
    ui.painter().rect_stroke(
        frame,
        look.scaled(10.0),
        Stroke::new(look.scaled(1.5), look.palette.dim.gamma_multiply(0.5)),
        egui::StrokeKind::Inside,
    );
    ui.painter().galley(
        frame.center() - galley.size() * 0.5,
        galley,
        look.palette.title,
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inline_markup_splits_and_keeps_lone_markers() {
        use Inline::*;
        assert_eq!(
            inline_spans("a *b* `c` d"),
            vec![
                ("a ", Plain),
                ("b", Emphasis),
                (" ", Plain),
                ("c", Code),
                (" d", Plain)
            ]
        );
        assert_eq!(inline_spans("x * y"), vec![("x *", Plain), (" y", Plain)]);
    }
}
