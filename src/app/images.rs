//! Image blocks: PNGs from the deck's folder, decoded once and kept as egui textures; a changed
//! file (new modification time) is decoded again, so images hot-reload like the deck.

use std::path::{Path, PathBuf};
use std::time::SystemTime;

use egui::{Rect, Sense, Stroke, vec2};

use super::theme::{self, Look, size};

#[derive(Clone)]
struct Cached {
    modified: Option<SystemTime>,
    result: Result<egui::TextureHandle, String>,
}

fn resolve(base_dir: Option<&Path>, path: &str) -> PathBuf {
    match base_dir {
        Some(dir) => dir.join(path),
        None => PathBuf::from(path),
    }
}

fn texture(
    ctx: &egui::Context,
    base_dir: Option<&Path>,
    path: &str,
) -> Result<egui::TextureHandle, String> {
    let full = resolve(base_dir, path);
    let modified = std::fs::metadata(&full).and_then(|m| m.modified()).ok();
    let id = egui::Id::unique(("lectern-image", &full));
    if let Some(c) = ctx.data(|d| d.get_temp::<Cached>(id))
        && c.modified == modified
    {
        return c.result;
    }
    let result = image::open(&full)
        .map_err(|e| format!("cannot load image {}: {e}", full.display()))
        .map(|img| {
            let rgba = img.to_rgba8();
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
    let w = avail_w
        * width.unwrap_or(1.0).clamp(
            *crate::deck::IMAGE_WIDTH_RANGE.start(),
            *crate::deck::IMAGE_WIDTH_RANGE.end(),
        );
    match texture(ctx, base_dir, path) {
        Ok(t) => {
            let [tw, th] = t.size();
            (w, w * th as f32 / tw.max(1) as f32)
        }
        Err(_) => (w, look.scaled(size::BODY * 2.5)),
    }
}

pub(crate) fn image_ui(
    ui: &mut egui::Ui,
    base_dir: Option<&Path>,
    path: &str,
    width: &Option<f32>,
    look: &Look,
) {
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
        }
        Err(msg) => {
            // A missing picture must not stop the talk: say which file, in the slide's place.
            ui.painter().rect_stroke(
                rect,
                look.scaled(8.0),
                Stroke::new(look.scaled(2.0), look.palette.dim),
                egui::StrokeKind::Inside,
            );
            ui.painter().text(
                rect.center(),
                egui::Align2::CENTER_CENTER,
                msg,
                look.font(theme::SERIF, size::FOOTER, ui.ctx()),
                look.palette.dim,
            );
        }
    }
}
