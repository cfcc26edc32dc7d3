//! Slide body blocks: paragraphs, bullets, tables, maths, images, live widgets and columns, laid out top
//! to bottom on the canvas. Text blocks take the height they need; widgets share what is left.

use egui::{Align, Rect, Sense, UiBuilder, vec2};

use super::block_ctx::BlockCtx;
use super::block_problems::{block_ron_path, located_problem};
use super::formula_view::{formula, math_source_height, math_ui, placeholder_height};
use super::images;
use super::inline_text::{Paragraph, paragraph};
use super::slide_state::SlideState;
use super::theme::size;
use crate::deck::Block;
use crate::math::MathSyntax;

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
    // each block also gets egui's item spacing after the space before it: count it, or the
    // last widget's slot reaches under the footer
    let gaps = gap * blocks.len().saturating_sub(1) as f32
        + ui.spacing().item_spacing.y * blocks.len() as f32;
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
        Block::Text(t) => Some(
            paragraph(ui, written(&t.src, t.latex), width, look, Align::Min)
                .size()
                .y,
        ),
        Block::Bullets(list) => {
            let indent = look.scaled(bullet_indent());
            let h: f32 = (list.items.iter())
                .map(|t| paragraph(ui, written(t, list.latex), width - indent, look, Align::Min))
                .map(|p| p.size().y)
                .sum();
            let gaps = list.items.len().saturating_sub(1) as f32;
            Some(h + look.scaled(size::BULLET_GAP) * gaps)
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
        Block::Table { header, rows } => Some(super::table_view::table_height(
            ui, header, rows, width, look,
        )),
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
            let para = paragraph(ui, written(&t.src, t.latex), width, look, align);
            let (rect, _) = ui.allocate_exact_size(vec2(width, para.size().y), Sense::hover());
            para.paint(ui.painter(), rect, look.palette.text);
            let at = block_ron_path(bctx.slide_index, path) + t.tree_suffix();
            note_inline_errors(ui, bctx, &at, written(&t.src, t.latex), &para, state);
        }
        Block::Bullets(list) => bullets_ui(ui, list, path, bctx, state),
        Block::Table { header, rows } => super::table_view::table_ui(ui, header, rows, look),
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
            let widget = state.widget(path, spec, bctx.deck_file);
            widget.ui(&mut child);
            super::slide_state::record_drawn_widget(
                ui.ctx(),
                bctx.slide_index,
                path,
                spec.kind(),
                rect,
                child.min_rect(),
                bctx.content,
            );
            let problems = widget.problems();
            // the load-time faults (equations, tableau files) at the deck's line and column
            let placed: Vec<String> = (bctx.widget_problems.iter())
                .filter(|p| p.slide == bctx.slide_index && p.block == path)
                .map(|p| p.diagnostic.to_string())
                .collect();
            if !problems.is_empty() && !placed.is_empty() {
                placed.into_iter().for_each(|p| state.note_problem(p));
            } else {
                for problem in problems {
                    state.note_problem(format!("{} widget {path:?}: {problem}", spec.kind()));
                }
            }
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
            // What each column stacks above its first widget (a caption that wraps to two
            // lines in one column and not in the other): the shorter leads are padded at the
            // top, so the widgets beside each other start (and end) at the same height.
            // (Columns without a widget neither pad nor are padded.)
            let lead = |c: usize, col: &[Block]| -> f32 {
                let Some(first) = col.iter().position(is_flexible) else {
                    return 0.0;
                };
                (0..first)
                    .filter_map(|i| measure(ui, &col[i], &[path, &[c, i]].concat(), cw, bctx))
                    .map(|h| h + look.scaled(size::BLOCK_GAP) + ui.spacing().item_spacing.y)
                    .sum()
            };
            let leads: Vec<f32> = cols
                .iter()
                .enumerate()
                .map(|(c, col)| lead(c, col))
                .collect();
            let max_lead = leads.iter().copied().fold(0.0, f32::max);
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
                if col.iter().any(is_flexible) {
                    child.add_space(max_lead - leads[c]);
                }
                blocks_ui(&mut child, col, &here, bctx, state, Align::Min);
                used = used.max(child.min_rect().height());
            }
            ui.allocate_exact_size(vec2(width, used.max(h)), Sense::hover());
        }
    }
}

/// A paragraph's text and the syntax of its `$…$`.
fn written(text: &str, latex: bool) -> (&str, MathSyntax) {
    (text, crate::math::deck::syntax_of(latex))
}

fn bullet_indent() -> f32 {
    size::BODY * 1.1
}

fn bullets_ui(
    ui: &mut egui::Ui,
    list: &crate::deck::BulletList,
    path: &[usize],
    bctx: &BlockCtx,
    state: &mut SlideState,
) {
    let look = &bctx.look;
    let width = ui.available_width();
    let indent = look.scaled(bullet_indent());
    for (i, item) in list.items.iter().enumerate() {
        if i > 0 {
            ui.add_space(look.scaled(size::BULLET_GAP));
        }
        let para = paragraph(
            ui,
            written(item, list.latex),
            width - indent,
            look,
            Align::Min,
        );
        let first_row_h = para.first_row_height();
        let (rect, _) = ui.allocate_exact_size(vec2(width, para.size().y), Sense::hover());
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
        let text_rect = Rect::from_min_max(rect.min + vec2(indent, 0.0), rect.max);
        para.paint(ui.painter(), text_rect, look.palette.text);
        let at = block_ron_path(bctx.slide_index, path) + &list.item_tree_suffix(i);
        note_inline_errors(ui, bctx, &at, written(item, list.latex), &para, state);
    }
}

/// The inline formulas of `written` (the string at `ron_path`) that did not typeset, as
/// problems at their character in the deck file.
fn note_inline_errors(
    ui: &egui::Ui,
    bctx: &BlockCtx,
    ron_path: &str,
    (written, syntax): (&str, MathSyntax),
    para: &Paragraph,
    state: &mut SlideState,
) {
    for (start_char, e) in &para.errors {
        // LaTeX is converted before Typst sees it: its columns are not the written ones
        let col_in_formula = (syntax == MathSyntax::Typst).then_some(e.col).flatten();
        let col = start_char + col_in_formula.unwrap_or(1);
        let message = crate::math::deck::message(e);
        let line = located_problem(ui.ctx(), bctx, ron_path, written, Some(col), message);
        state.note_problem(line);
    }
}
