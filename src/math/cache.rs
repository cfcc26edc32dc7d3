//! Formula textures for egui, cached by (source, syntax, size, colour), with last-good slots.

use std::collections::HashMap;
use std::sync::{Arc, Mutex};
use std::time::Instant;

use super::typeset::{MathError, MathSyntax, render_formula};

#[derive(Debug, Clone, PartialEq, Eq, Hash)]
struct Key {
    src: String,
    syntax: MathSyntax,
    /// Size in physical pixels per em, as f32 bits (exact-match key).
    size_bits: u32,
    rgba: [u8; 4],
}

/// A formula on the GPU. `size_px` is its size in physical pixels; divide by
/// `pixels_per_point` to lay it out in egui points.
#[derive(Clone)]
pub struct Formula {
    pub texture: egui::TextureHandle,
    pub size_px: egui::Vec2,
}

/// What a slot shows this frame: the newest good formula (maybe stale) and the error of the
/// newest edit, if it is broken.
#[derive(Clone, Default)]
pub struct MathView {
    pub formula: Option<Formula>,
    /// Set when the current source did not render; `formula` is then the last good one.
    pub error: Option<MathError>,
}

/// Cache of typeset formulas. One per egui context is enough: get it with [`MathCache::shared`].
#[derive(Default)]
pub struct MathCache {
    entries: HashMap<Key, Result<Formula, MathError>>,
    last_good: HashMap<String, Formula>,
    /// Milliseconds spent typesetting and rasterising (not cache hits), for reports.
    pub render_ms_total: f64,
    pub renders: usize,
}

/// Beyond this many cached formulas the cache is dropped wholesale (slots keep theirs); a deck
/// has a few hundred at most, so this only bounds a session of many edits.
const MAX_ENTRIES: usize = 2048;

impl MathCache {
    pub fn new() -> Self {
        Self::default()
    }

    /// The cache stored in `ctx`, shared by the slide renderer and widgets.
    pub fn shared(ctx: &egui::Context) -> Arc<Mutex<MathCache>> {
        ctx.data_mut(|d| {
            d.get_temp_mut_or_default::<Arc<Mutex<MathCache>>>(egui::Id::NULL.with("lectern::math"))
                .clone()
        })
    }

    /// The formula for `src` at `size_px` physical pixels per em in `color`, typeset on first
    /// use and cached (errors are cached too, so a broken formula costs nothing per frame).
    pub fn get(
        &mut self,
        ctx: &egui::Context,
        src: &str,
        syntax: MathSyntax,
        size_px: f32,
        color: egui::Color32,
    ) -> Result<Formula, MathError> {
        let key = Key {
            src: src.to_owned(),
            syntax,
            size_bits: size_px.to_bits(),
            rgba: color.to_srgba_unmultiplied(),
        };
        if let Some(hit) = self.entries.get(&key) {
            return hit.clone();
        }
        if self.entries.len() >= MAX_ENTRIES {
            self.entries.clear();
        }
        let start = Instant::now();
        let result = render_formula(src, syntax, size_px, key.rgba).map(|r| {
            let size = [r.width as usize, r.height as usize];
            let image = egui::ColorImage::from_rgba_premultiplied(size, &r.rgba_premultiplied);
            let name = format!("math:{}", self.entries.len());
            Formula {
                texture: ctx.load_texture(name, image, egui::TextureOptions::LINEAR),
                size_px: egui::vec2(r.width as f32, r.height as f32),
            }
        });
        self.render_ms_total += start.elapsed().as_secs_f64() * 1e3;
        self.renders += 1;
        self.entries.insert(key, result.clone());
        result
    }

    /// Like [`get`](Self::get), remembering per `slot` (e.g. "slide-id/3") the last formula
    /// that rendered, so a broken edit keeps showing the previous picture with the error beside.
    pub fn get_slot(
        &mut self,
        ctx: &egui::Context,
        slot: &str,
        src: &str,
        syntax: MathSyntax,
        size_px: f32,
        color: egui::Color32,
    ) -> MathView {
        match self.get(ctx, src, syntax, size_px, color) {
            Ok(f) => {
                self.last_good.insert(slot.to_owned(), f.clone());
                MathView {
                    formula: Some(f),
                    error: None,
                }
            }
            Err(e) => MathView {
                formula: self.last_good.get(slot).cloned(),
                error: Some(e),
            },
        }
    }
}

/// Draws display maths centred in `ui`, `em_points` points per em, keeping the last good
/// rendering of `slot`. Returns the error of the current source, for the presenter's screen.
pub fn math_ui(
    ui: &mut egui::Ui,
    slot: &str,
    src: &str,
    syntax: MathSyntax,
    em_points: f32,
    color: egui::Color32,
) -> Option<MathError> {
    let ppp = ui.ctx().pixels_per_point();
    let cache = MathCache::shared(ui.ctx());
    let view = cache
        .lock()
        .map(|mut c| c.get_slot(ui.ctx(), slot, src, syntax, em_points * ppp, color))
        .unwrap_or_default();
    if let Some(f) = &view.formula {
        let mut size = f.size_px / ppp;
        // Never overflow the slide: shrink to the width offered.
        let avail = ui.available_width();
        if size.x > avail && avail > 1.0 {
            size *= avail / size.x;
        }
        ui.vertical_centered(|ui| {
            ui.add(egui::Image::new((f.texture.id(), size)));
        });
    }
    view.error
}
