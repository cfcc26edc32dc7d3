//! Image blocks: PNGs from the deck's folder, decoded once and kept as egui textures; a changed
//! file (new modification time) is decoded again, so images hot-reload like the deck. Paths go
//! through [`crate::paths`] (nothing outside the project is shown) and decoding through
//! [`crate::image_file`] (a header claiming huge dimensions is refused before allocating).

use std::path::Path;
use std::time::SystemTime;

use egui::{Rect, Sense, Stroke, vec2};

use super::theme::{self, Look, size};

#[derive(Clone)]
struct Cached {
    modified: Option<SystemTime>,
    result: Result<egui::TextureHandle, String>,
}

fn texture(
    ctx: &egui::Context,
    base_dir: Option<&Path>,
    path: &str,
) -> Result<egui::TextureHandle, String> {
    let full = crate::paths::resolve_in(base_dir.unwrap_or(Path::new(".")), path)
        .map_err(|e| format!("image not shown: {e}"))?;
    let modified = std::fs::metadata(&full).and_then(|m| m.modified()).ok();
    let id = egui::Id::unique(("lectern-image", &full));
    if let Some(c) = ctx.data(|d| d.get_temp::<Cached>(id))
        && c.modified == modified
    {
        return c.result;
    }
    let result = crate::image_file::decode(&full).map(|rgba| {
        let size = [rgba.width() as usize, rgba.height() as usize];
        let color = egui::ColorImage::from_rgba_unmultiplied(size, rgba.as_raw());
        ctx.load_texture(full.display().to_string(), color, Default::default())
    });
    ctx.data_mut(|d| {
        d.insert_temp(
            id,
            Cached {
                modified,
                result: result.clone(),
            },
        )
    });
    result
}

/// Width and height in points of an image block at `avail_w` points of column width.
pub(crate) fn image_size(
    ctx: &egui::Context,
    base_dir: Option<&Path>,
    path: &str,
    width: &Option<f32>,
    avail_w: f32,
    look: &Look,
) -> (f32, f32) {
    let w = avail_w * width.unwrap_or(1.0).clamp(0.05, 1.0);
    match texture(ctx, base_dir, path) {
        Ok(t) => {
            let [tw, th] = t.size();
            (w, w * th as f32 / tw.max(1) as f32)
        }
        Err(_) => (w, look.scaled(size::BODY * 2.5)),
    }
}

/// Draws the picture, or in its place the reason it cannot be shown (returned too, for the
/// presenter's list of problems).
pub(crate) fn image_ui(
    ui: &mut egui::Ui,
    base_dir: Option<&Path>,
    path: &str,
    width: &Option<f32>,
    look: &Look,
) -> Option<String> {
    let avail_w = ui.available_width();
    let (w, h) = image_size(ui.ctx(), base_dir, path, width, avail_w, look);
    let (row, _) = ui.allocate_exact_size(vec2(avail_w, h), Sense::hover());
    let rect = Rect::from_center_size(row.center(), vec2(w, h));
    match texture(ui.ctx(), base_dir, path) {
        Ok(t) => {
            ui.painter().image(
                t.id(),
                rect,
                Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0)),
                egui::Color32::WHITE,
            );
            None
        }
        Err(msg) => {
            // A missing picture must not stop the talk: say which file, in the slide's place.
            ui.painter().rect_stroke(
                rect,
                look.scaled(8.0),
                Stroke::new(look.scaled(2.0), look.palette.dim),
                egui::StrokeKind::Inside,
            );
            let galley = ui.painter().layout(
                msg.clone(),
                look.font(theme::SERIF, size::FOOTER, ui.ctx()),
                look.palette.dim,
                rect.width() - look.scaled(24.0),
            );
            ui.painter().galley(
                rect.center() - galley.size() * 0.5,
                galley,
                look.palette.dim,
            );
            Some(msg)
        }
    }
}
