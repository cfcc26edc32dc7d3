//! The `Table` block: a header row in bold over a rule, then the rows with hairlines between
//! them, so the header reads as labels, not as data (a bracketed matrix made it a first row).
//! Columns share the width in proportion to their widest cell; cells wrap.

use std::sync::Arc;

use egui::{Align, Sense, Stroke, vec2};

use super::inline_text::text_galley;
use super::theme::{self, Look, size};

/// Space either side of a cell's text, and above and below each row, in canvas points.
const CELL_PAD_X: f32 = 18.0;
const CELL_PAD_Y: f32 = 10.0;

/// Each column's width at `width` in total: proportional to its widest unwrapped cell, but
/// never less than a sixth of an even share (a short header must not crush its column).
fn column_widths(ui: &egui::Ui, cells: &[&[String]], width: f32, look: &Look) -> Vec<f32> {
    let n = cells.iter().map(|r| r.len()).max().unwrap_or(0);
    if n == 0 {
        return Vec::new();
    }
    let natural: Vec<f32> = (0..n)
        .map(|c| {
            cells
                .iter()
                .filter_map(|r| r.get(c))
                .map(|t| text_galley(ui, t, f32::INFINITY, look, Align::Min).size().x)
                .fold(0.0, f32::max)
                + 2.0 * look.scaled(CELL_PAD_X)
        })
        .collect();
    let total: f32 = natural.iter().sum();
    if total <= width {
        // room to spare: every column its natural width, the rest to the last
        let mut w = natural;
        if let Some(last) = w.last_mut() {
            *last += width - total;
        }
        return w;
    }
    let floor = width / n as f32 / 6.0;
    natural
        .iter()
        .map(|w| (w / total * width).max(floor))
        .collect()
}

/// The galleys of one row, laid out in their columns.
fn row_galleys(
    ui: &egui::Ui,
    row: &[String],
    widths: &[f32],
    look: &Look,
    bold: bool,
) -> Vec<Arc<egui::Galley>> {
    row.iter()
        .zip(widths)
        .map(|(t, w)| {
            let inner = (w - 2.0 * look.scaled(CELL_PAD_X)).max(1.0);
            if bold {
                let font = look.font(theme::SERIF_BOLD, size::BODY, ui.ctx());
                let mut job =
                    egui::text::LayoutJob::simple(t.clone(), font, look.palette.title, inner);
                job.halign = Align::Min;
                ui.painter().layout_job(job)
            } else {
                text_galley(ui, t, inner, look, Align::Min)
            }
        })
        .collect()
}

fn row_height(galleys: &[Arc<egui::Galley>], look: &Look) -> f32 {
    galleys.iter().map(|g| g.size().y).fold(0.0, f32::max) + 2.0 * look.scaled(CELL_PAD_Y)
}

/// The height the table takes at `width`.
pub(crate) fn table_height(
    ui: &egui::Ui,
    header: &[String],
    rows: &[Vec<String>],
    width: f32,
    look: &Look,
) -> f32 {
    let all: Vec<&[String]> = std::iter::once(header)
        .chain(rows.iter().map(Vec::as_slice))
        .collect();
    let widths = column_widths(ui, &all, width, look);
    let head = row_height(&row_galleys(ui, header, &widths, look, true), look);
    head + rows
        .iter()
        .map(|r| row_height(&row_galleys(ui, r, &widths, look, false), look))
        .sum::<f32>()
}

/// Draws the table across the width `ui` offers.
pub(crate) fn table_ui(ui: &mut egui::Ui, header: &[String], rows: &[Vec<String>], look: &Look) {
    let width = ui.available_width();
    let all: Vec<&[String]> = std::iter::once(header)
        .chain(rows.iter().map(Vec::as_slice))
        .collect();
    let widths = column_widths(ui, &all, width, look);
    let (pad_x, pad_y) = (look.scaled(CELL_PAD_X), look.scaled(CELL_PAD_Y));
    let rule = Stroke::new(look.scaled(3.0), look.palette.accent);
    let hairline = Stroke::new(look.scaled(1.0), look.palette.dim.gamma_multiply(0.6));
    let header_fill = look.palette.panel;
    for (r, row) in std::iter::once(header)
        .chain(rows.iter().map(Vec::as_slice))
        .enumerate()
    {
        let galleys = row_galleys(ui, row, &widths, look, r == 0);
        let h = row_height(&galleys, look);
        let (rect, _) = ui.allocate_exact_size(vec2(width, h), Sense::hover());
        if r == 0 {
            ui.painter().rect_filled(rect, 0.0, header_fill);
        }
        let mut x = rect.left();
        for (g, w) in galleys.into_iter().zip(&widths) {
            let color = if r == 0 {
                look.palette.title
            } else {
                look.palette.text
            };
            ui.painter()
                .galley(egui::pos2(x + pad_x, rect.top() + pad_y), g, color);
            x += w;
        }
        let stroke = if r == 0 { rule } else { hairline };
        if r == 0 || r < rows.len() {
            ui.painter()
                .hline(rect.left()..=rect.right(), rect.bottom(), stroke);
        }
    }
}
